// OBJ meshes and frame patterns.
#include "io/obj.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace weft::io;
using weft::test::ScratchDir;

std::string obj_error(const std::string& path) {
  try {
    read_obj(path);
  } catch (const FormatError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FormatError for " << path;
  return "";
}

TEST(WEFT_TEST_SUITE, obj_reads_quads_negative_indices_and_all_face_forms) {
  const ScratchDir dir("read");
  const std::string file = dir.write("mesh.obj",
                                     "# a quad and a triangle\r\n"
                                     "mtllib cloth.mtl\n"
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\nvn 0 0 1\n"
                                     "g panel\n"
                                     "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                                     "v 2 0.5 -1e-3 1.0\n"
                                     "f -4//1 -1//1 +3  # relative to the five vertices so far\n"
                                     "f 1/1 5/1 2/1\n"
                                     "l 1 2\n");
  const TriMesh m = read_obj(file);
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_TRUE(m.positions[4] == (weft::Vec3{2, 0.5, -1e-3}));
  const std::vector<std::array<int, 3>> expected{{0, 1, 2}, {0, 2, 3}, {1, 4, 2}, {0, 4, 1}};
  EXPECT_EQ(m.triangles, expected);
}

TEST(WEFT_TEST_SUITE, obj_errors_name_the_file_and_line) {
  const ScratchDir dir("errors");
  const std::string range = dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\nf 1 2 4\n");
  EXPECT_NE(obj_error(range).find(range + ": line 6: face vertex 4 is out of range"), std::string::npos)
      << obj_error(range);
  const std::string negative = dir.write("negative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n");
  EXPECT_NE(obj_error(negative).find("negative.obj: line 3: face vertex -3"), std::string::npos) << obj_error(negative);
  const std::string number = dir.write("number.obj", "v 0 0 0\nv 1 zero 0\n");
  EXPECT_NE(obj_error(number).find("number.obj: line 2: 'zero' is not a number"), std::string::npos)
      << obj_error(number);
  const std::string zero = dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_NE(obj_error(zero).find("zero.obj: line 4: '0' is not a vertex reference"), std::string::npos)
      << obj_error(zero);
  const std::string small = dir.write("small.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  EXPECT_NE(obj_error(small).find("small.obj: line 3: a face needs at least three vertices"), std::string::npos);
  EXPECT_THROW(read_obj(dir.file("absent.obj")), std::system_error);
}

TEST(WEFT_TEST_SUITE, obj_write_round_trips_exactly_and_atomically) {
  const ScratchDir dir("write");
  weft::test::TestRng rng(7);
  TriMesh m;
  for (int i = 0; i < 50; ++i)
    m.positions.push_back({rng.uniform(-3, 3), rng.uniform(-1e-9, 1e-9), rng.uniform(0, 1e6)});
  for (int i = 0; i + 2 < 50; ++i) m.triangles.push_back({i, i + 1, i + 2});
  const std::string file = dir.file("body.0001.obj");
  write_obj(m, file);
  const TriMesh back = read_obj(file);
  EXPECT_EQ(back.triangles, m.triangles);
  ASSERT_EQ(back.positions.size(), m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) EXPECT_TRUE(back.positions[i] == m.positions[i]) << i;
  EXPECT_EQ(dir.entries().size(), 1u);  // no temporary left

  TriMesh bad = m;
  bad.triangles.push_back({0, 1, 50});
  const std::string bad_file = dir.file("bad.obj");
  try {
    write_obj(bad, bad_file);
    ADD_FAILURE() << "no FormatError";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(bad_file + ": triangle 48 refers to vertex 50"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(bad_file));
  EXPECT_THROW(write_obj(m, dir.file("missing/x.obj")), std::system_error);
}

TEST(WEFT_TEST_SUITE, obj_frame_patterns_expand_like_houdini) {
  EXPECT_EQ(expand_frame_pattern("body.$F4.obj", 1, 2), (std::vector<std::string>{"body.0001.obj", "body.0002.obj"}));
  EXPECT_EQ(expand_frame_pattern("f$F.geo", 9, 10), (std::vector<std::string>{"f9.geo", "f10.geo"}));
  EXPECT_EQ(expand_frame_pattern("a_${F3}_b.$F2.bgeo", 7, 7), std::vector<std::string>{"a_007_b.07.bgeo"});
  EXPECT_EQ(expand_frame_pattern("f.$F4.obj", -1, -1), std::vector<std::string>{"f.-001.obj"});
  EXPECT_EQ(expand_frame_pattern("rest.obj", 1, 1), std::vector<std::string>{"rest.obj"});
  EXPECT_THROW(expand_frame_pattern("rest.obj", 1, 2), FormatError);
  EXPECT_THROW(expand_frame_pattern("f.$FPS.obj", 1, 2), FormatError);
  EXPECT_THROW(expand_frame_pattern("f.${F4.obj", 1, 2), FormatError);
  EXPECT_THROW(expand_frame_pattern("f.$F.obj", 3, 2), FormatError);
}

}  // namespace
