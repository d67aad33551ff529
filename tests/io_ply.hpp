// The PLY reader: ASCII and binary little-endian files it writes here read back exactly, whatever their
// numeric types and extra elements; malformed files fail naming the file and element; the cloth-funnel frames.
#include "io/ply.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

namespace {

using weft::Vec3;
using weft::io::FormatError;
using weft::io::read_ply;
using weft::test::ScratchDir;

// Little-endian bytes of a value.
template <class T>
std::string le(T v) {
  using U = std::conditional_t<sizeof(T) == 1, uint8_t,
                               std::conditional_t<sizeof(T) == 2, uint16_t, std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>>;
  U u;
  std::memcpy(&u, &v, sizeof(T));
  std::string out;
  for (size_t i = 0; i < sizeof(T); ++i) out.push_back(char((u >> (8 * i)) & 0xFF));
  return out;
}

// The message of the FormatError that reading `path` throws, or "" if none.
std::string format_error(const std::string& path) {
  try {
    read_ply(path);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

const std::vector<Vec3> kPositions = {{0, 0, 0}, {1.5, -2.25, 3}, {0.1, 0.2, 0.3}, {-1e-300, 7, 1e10}};
const std::vector<std::array<int, 3>> kTriangles = {{0, 1, 2}, {3, 2, 1}};

TEST(WEFT_TEST_SUITE, ply_ascii_reads_exactly) {
  const ScratchDir dir("ply_ascii");
  const std::string text =
      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info nothing\r\nelement vertex 4\r\n"
      "property double x\r\nproperty double y\r\nproperty double z\r\nproperty uchar red\r\n"
      "element face 2\r\nproperty list uchar int vertex_indices\r\nproperty float quality\r\n"
      "element edge 1\r\nproperty int vertex1\r\nproperty list int float weights\r\nend_header\r\n"
      "0 0 0 255\n1.5 -2.25 +3 0\n0.1 0.2 0.3 7\n-1e-300 7 1e10 1\n"
      "3 0 1 2 0.5\n3 3 2 1 1.5\n"
      "1 2 0.25 0.75\n";
  const weft::io::TriMesh m = read_ply(dir.write("a.ply", text));
  ASSERT_EQ(m.positions.size(), kPositions.size());
  for (size_t i = 0; i < kPositions.size(); ++i) EXPECT_TRUE(m.positions[i] == kPositions[i]) << i;
  EXPECT_EQ(m.triangles, kTriangles);
}

TEST(WEFT_TEST_SUITE, ply_ascii_float_properties_hold_float_values) {
  const ScratchDir dir("ply_ascii_float");
  const weft::io::TriMesh m = read_ply(dir.write(
      "f.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
               "end_header\n0.1 -0.2 3\n"));
  ASSERT_EQ(m.positions.size(), 1u);
  EXPECT_EQ(m.positions[0].x, double(0.1f));
  EXPECT_EQ(m.positions[0].y, double(-0.2f));
  EXPECT_TRUE(m.triangles.empty());  // no face element: a point cloud
}

TEST(WEFT_TEST_SUITE, ply_binary_reads_exactly_in_every_type) {
  const ScratchDir dir("ply_binary");
  // Doubles and int indices, with other properties interleaved.
  std::string d =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty short id\nproperty double x\n"
      "property double y\nproperty double z\nelement face 2\nproperty uchar flags\n"
      "property list uchar int vertex_indices\nproperty list ushort double extra\nend_header\n";
  for (int i = 0; i < 4; ++i)
    d += le<int16_t>(int16_t(-i)) + le(kPositions[i].x) + le(kPositions[i].y) + le(kPositions[i].z);
  for (const auto& t : kTriangles)
    d += le<uint8_t>(9) + le<uint8_t>(3) + le<int32_t>(t[0]) + le<int32_t>(t[1]) + le<int32_t>(t[2]) +
         le<uint16_t>(2) + le(1.0) + le(2.0);
  weft::io::TriMesh m = read_ply(dir.write("d.ply", d));
  ASSERT_EQ(m.positions.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_TRUE(m.positions[i] == kPositions[i]) << i;
  EXPECT_EQ(m.triangles, kTriangles);

  // Floats and uint indices with a uint count (names of the sized types), vertex_index.
  std::string f =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float32 x\nproperty float32 y\n"
      "property float32 z\nelement face 2\nproperty list uint32 uint32 vertex_index\nend_header\n";
  for (const Vec3& p : kPositions) f += le(float(p.x)) + le(float(p.y)) + le(float(p.z));
  for (const auto& t : kTriangles) f += le<uint32_t>(3) + le<uint32_t>(t[0]) + le<uint32_t>(t[1]) + le<uint32_t>(t[2]);
  m = read_ply(dir.write("f.ply", f));
  ASSERT_EQ(m.positions.size(), 4u);
  for (size_t i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m.positions[i][c], double(float(kPositions[i][c]))) << i;
  EXPECT_EQ(m.triangles, kTriangles);
}

TEST(WEFT_TEST_SUITE, ply_malformed_files_fail_naming_file_and_element) {
  const ScratchDir dir("ply_malformed");
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
  struct Bad {
    std::string name, bytes, expect;  // expect: a piece of the message
  };
  const std::vector<Bad> bad = {
      {"quad.ply", head + verts + "4 0 1 2 0\n", "element 'face' 0, property 'vertex_indices': a face of 4 vertices"},
      {"range.ply", head + verts + "3 0 1 3\n", "element 'face' 0, property 'vertex_indices': vertex index 3 is out of range"},
      {"negative.ply", head + verts + "3 0 -1 2\n", "vertex index -1 is out of range"},
      {"short.ply", head + verts + "3 0 1\n", "element 'face' 0, property 'vertex_indices': the data ends early"},
      {"word.ply", head + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "element 'vertex' 1, property 'y': 'zero' is not a number"},
      {"uchar.ply", head + verts + "300 0 1 2\n", "'300' is not a valid integer"},
      {"trailing.ply", head + verts + "3 0 1 2\n5\n", "data after the last element"},
      {"nox.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nend_header\n0 0\n",
       "element 'vertex' has no scalar property 'x'"},
      {"novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
       "no 'vertex' element"},
      {"nolist.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 0\nproperty int vertex_indices\nend_header\n",
       "element 'face' has no list property 'vertex_indices'"},
      {"big.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\nend_header\n", "big-endian PLY is not supported"},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 0\n", "no end_header"},
      {"noformat.ply", "ply\nelement vertex 0\nproperty float x\nend_header\n", "no format line"},
      {"keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 0\nend_header\n", "header line 3: unknown keyword 'elemnt'"},
      {"notply.ply", "solid cube\n", "not a PLY file"},
      {"huge.ply", "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n0 0 0\n",
       "element 'vertex': 2000000000 instances cannot fit"},
      {"binshort.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
       "property double z\nend_header\n" + le(1.0) + le(2.0),
       "element 'vertex' 0, property 'z': the data ends early"},
  };
  for (const Bad& b : bad) {
    const std::string path = dir.write(b.name, b.bytes);
    const std::string message = format_error(path);
    EXPECT_NE(message.find(path + ": "), std::string::npos) << b.name << ": " << message;
    EXPECT_NE(message.find(b.expect), std::string::npos) << b.name << ": " << message;
  }
  EXPECT_THROW(read_ply(dir.file("missing.ply")), std::system_error);
}

TEST(WEFT_TEST_SUITE, ply_reads_cloth_funnel_frames) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const std::string dir = weft::test::shared_dir() + "/data/ccd/scalable/cloth-funnel/frames/";
  const weft::io::TriMesh a = read_ply(dir + "227.ply"), b = read_ply(dir + "228.ply");
  EXPECT_EQ(a.positions.size(), 9450u);
  EXPECT_EQ(a.triangles.size(), 18484u);
  EXPECT_EQ(a.triangles, b.triangles);
  size_t moved = 0;
  for (size_t i = 0; i < a.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(a.positions[i][c]) && std::isfinite(b.positions[i][c]));
    moved += !(a.positions[i] == b.positions[i]);
  }
  EXPECT_GT(moved, 0u);
}

}  // namespace
