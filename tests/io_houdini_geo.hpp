// Houdini .geo / .bgeo: Houdini-written files, round trips, malformed input and atomic writing.
#include "io/houdini_bjson.hpp"
#include "io/houdini_geo.hpp"
#include "tests/input_error_fixture.hpp"
#include "tests/io_checks_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

using weft::test::contains;
using weft::test::expect_same_attributes;
using weft::test::ScratchDir;

namespace fs = std::filesystem;
using namespace weft::io;

std::string houdini_file(const std::string& name) { return weft::test::shared_dir() + "/data/houdini/" + name; }

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The FormatError message `f` throws; a test failure when it throws none.
std::string format_error(const std::function<void()>& f) {
  return weft::test::thrown_message<FormatError>(f, "FormatError");
}

void expect_same(const Geometry& a, const Geometry& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t p = 0; p < a.points.size(); ++p) EXPECT_TRUE(a.points[p] == b.points[p]) << "point " << p;
  EXPECT_EQ(a.position_storage, b.position_storage);
  ASSERT_EQ(a.primitives.size(), b.primitives.size());
  for (size_t i = 0; i < a.primitives.size(); ++i) {
    EXPECT_EQ(a.primitives[i].kind, b.primitives[i].kind) << "primitive " << i;
    EXPECT_EQ(a.primitives[i].points, b.primitives[i].points) << "primitive " << i;
    EXPECT_EQ(a.primitives[i].type_name, b.primitives[i].type_name) << "primitive " << i;
    EXPECT_EQ(a.primitives[i].transform, b.primitives[i].transform) << "primitive " << i;
  }
  expect_same_attributes(a.point_attributes, b.point_attributes, "point");
  expect_same_attributes(a.vertex_attributes, b.vertex_attributes, "vertex");
  expect_same_attributes(a.primitive_attributes, b.primitive_attributes, "primitive");
  expect_same_attributes(a.detail_attributes, b.detail_attributes, "detail");
}

double f32(double x) { return double(float(x)); }

// A Vellum-like asset in one geometry: a cloth quad, constraint polylines and an attach sphere.
Geometry vellum_like() {
  Geometry g;
  g.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, f32(0.25)}};
  g.point_attributes["mass"] = float_attribute(1, {0.5, 0.25, 0, 1});
  g.point_attributes["pscale"] = float_attribute(1, {0.01, 0.02, 0.03, 0.1}, Storage::Float64);
  g.point_attributes["stopped"] = int_attribute(1, {0, 1, 0, 0});
  g.point_attributes["layer"] = int_attribute(1, {0, 0, 1, -2}, Storage::Int8);
  g.point_attributes["id"] = int_attribute(1, {10, 11, 12, int64_t(1) << 40}, Storage::Int64);
  g.point_attributes["v"] = float_attribute(3, {0, 0, 0, f32(0.1), 0, 0, 0, f32(-9.81), 0, 1, 2, 3});
  g.point_attributes["v"].qualifier = "vector";

  const auto prim = [](PrimKind kind, std::vector<int> points) {
    Primitive p;
    p.kind = kind;
    p.points = std::move(points);
    return p;
  };
  g.primitives = {prim(PrimKind::Polygon, {0, 1, 3, 2}), prim(PrimKind::Polyline, {0, 1}),
                  prim(PrimKind::Polyline, {1, 3}),      prim(PrimKind::Polyline, {0, 3, 1, 2}),
                  prim(PrimKind::Sphere, {2}),           prim(PrimKind::Polyline, {2, 3})};
  g.primitives[4].transform = {0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1};
  g.primitive_attributes["type"] = string_attribute(1, {"", "distance", "distance", "bend", "attach", "stitch"});
  g.primitive_attributes["stiffness"] = float_attribute(1, {0, 1e10, 0.3, 1e-4, 1, 2}, Storage::Float64);
  g.primitive_attributes["restlength"] = float_attribute(1, {0, 1, f32(1.0307764), f32(-12.5), 0, 1});
  std::vector<double> restvector;
  for (int i = 0; i < 24; ++i) restvector.push_back(f32(0.1 * i));
  g.primitive_attributes["restvector"] = float_attribute(4, restvector);
  std::vector<double> uv;
  for (size_t i = 0; i < g.vertex_count() * 3; ++i) uv.push_back(f32(i / 16.0));
  g.vertex_attributes["uv"] = float_attribute(3, uv);
  g.detail_attributes["solver"] = string_attribute(1, {"weft \"xpbd\"\n"});
  g.detail_attributes["substeps"] = int_attribute(1, {5});
  g.detail_attributes["gravity"] = float_attribute(3, {0, -9.81, 0}, Storage::Float64);
  return g;
}

// A small valid .geo for the malformed-input tests to break.
const std::string kTriangle = R"(["fileversion","20.5.0","pointcount",3,"vertexcount",3,"primitivecount",1,
"topology",["pointref",["indices",[0,1,2]]],
"attributes",["pointattributes",[
 [["scope","public","type","numeric","name","P","options",{}],
  ["size",3,"storage","fpreal32","values",["size",3,"storage","fpreal32","tuples",[[0,0,0],[1,0,0],[0,1,0]]]]]]],
"primitives",[[["type","Polygon_run"],["startvertex",0,"nprimitives",1,"nvertices_rle",[3,1]]]]])";

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

TEST(WEFT_TEST_SUITE, houdini_default_geo_reads_its_documented_contents) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const Geometry g = read_geo(houdini_file("default.geo"));
  ASSERT_EQ(g.points.size(), 16u);
  ASSERT_EQ(g.primitives.size(), 18u);
  EXPECT_EQ(g.vertex_count(), 60u);
  for (size_t i = 0; i < 18; ++i) {
    EXPECT_EQ(g.primitives[i].kind, PrimKind::Polygon);
    EXPECT_EQ(g.primitives[i].points.size(), i < 12 ? 3u : 4u);
  }
  EXPECT_EQ(g.primitives[0].points, (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(g.primitives[12].points, (std::vector<int>{8, 9, 11, 10}));
  EXPECT_TRUE(g.points[0] == (weft::Vec3{0.5, -0.5, 0.5}));
  EXPECT_TRUE(g.points[15] == (weft::Vec3{0.5, 0.5, -0.5}));
  EXPECT_EQ(g.position_storage, Storage::Float32);

  ASSERT_EQ(g.point_attributes.size(), 1u);
  const Attribute& testpoint = g.point_attributes.at("testpoint");
  EXPECT_EQ(testpoint.size, 1);
  EXPECT_EQ(testpoint.floats, std::vector<double>(16, 1.0));
  const Attribute& testprim = g.primitive_attributes.at("testprim");
  EXPECT_EQ(testprim.size, 3);
  ASSERT_EQ(testprim.count(), 18u);
  for (size_t i = 0; i < 18; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(testprim.number(i, c), c + 1.0);
  EXPECT_EQ(g.detail_attributes.at("testdetail").strings, std::vector<std::string>{"string"});
  EXPECT_TRUE(g.vertex_attributes.empty());
  EXPECT_TRUE(g.warnings.empty());
}

TEST(WEFT_TEST_SUITE, houdini_geo_and_bgeo_of_the_same_geometry_read_identically) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  expect_same(read_geo(houdini_file("default.geo")), read_geo(houdini_file("default.bgeo")));
  const Geometry box = read_geo(houdini_file("box.geo"));
  expect_same(box, read_geo(houdini_file("box.bgeo")));
  ASSERT_EQ(box.points.size(), 8u);
  ASSERT_EQ(box.primitives.size(), 6u);
  for (const Primitive& p : box.primitives) EXPECT_EQ(p.points.size(), 4u);
  EXPECT_EQ(box.primitives[0].points, (std::vector<int>{0, 1, 3, 2}));
  EXPECT_TRUE(box.point_attributes.empty());
}

TEST(WEFT_TEST_SUITE, houdini_boxattr_bgeo_reads_its_extra_attribute) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const Geometry g = read_geo(houdini_file("boxattr.bgeo"));
  Geometry without_foo = g;
  without_foo.point_attributes.erase("foo");
  expect_same(without_foo, read_geo(houdini_file("box.geo")));
  const Attribute& foo = g.point_attributes.at("foo");
  EXPECT_EQ(foo.storage, Storage::Float32);
  ASSERT_EQ(foo.count(), 8u);
  for (size_t p = 0; p < 8; ++p) EXPECT_FLOAT_EQ(float(foo.number(p)), float(1.23 * double(p)));
}

TEST(WEFT_TEST_SUITE, houdini_triangulation_fans_polygons_counter_clockwise) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const Triangulation t = triangulate(read_geo(houdini_file("default.geo")));
  ASSERT_EQ(t.mesh.triangles.size(), 12u + 6u * 2u);
  ASSERT_EQ(t.primitive.size(), t.mesh.triangles.size());
  for (int i = 0; i < 12; ++i) EXPECT_EQ(t.primitive[size_t(i)], i);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(t.primitive[size_t(12 + i)], 12 + i / 2);
  EXPECT_EQ(t.mesh.positions.size(), 16u);

  // The box is centred on the origin: counter-clockwise triangles have outward normals.
  const weft::io::TriMesh box = to_trimesh(read_geo(houdini_file("box.geo")));
  ASSERT_EQ(box.triangles.size(), 12u);
  for (const auto& tri : box.triangles) {
    const weft::Vec3 a = box.positions[size_t(tri[0])], b = box.positions[size_t(tri[1])],
                     c = box.positions[size_t(tri[2])];
    EXPECT_GT(weft::dot(weft::cross(b - a, c - a), a + b + c), 0.0);
  }
}

TEST(WEFT_TEST_SUITE, houdini_binary_json_decodes_either_byte_order) {
  // [258, 1.0, token "ab" defined then referenced, bools [false, true], halves [1.0, -2.0], a 0xf2-prefixed
  // 300-byte string], big-endian ("bJSN") and then the same little-endian ("NSJb").
  const std::string big = std::string(
                              "\x7f"
                              "bJSN"
                              "\x5b"
                              "\x12\x01\x02"
                              "\x19\x3f\x80\x00\x00"
                              "\x2b\x05\x02"
                              "ab"
                              "\x26\x05"
                              "\x40\x10\x02\x00\x00\x00\x02"
                              "\x40\x18\x02\x3c\x00\xc0\x00"
                              "\x27\xf2\x01\x2c",
                              39) +
                          std::string(300, 'x') + "\x5d";
  std::string little = big;
  little.replace(1, 4, "NSJb");
  for (const auto& [bytes, little_endian] : {std::pair{big, false}, std::pair{little, true}}) {
    std::string b = bytes;
    if (little_endian) {  // reverse each multi-byte datum
      std::swap(b[7], b[8]);
      std::swap(b[10], b[13]), std::swap(b[11], b[12]);
      std::swap(b[24], b[27]), std::swap(b[25], b[26]);
      std::swap(b[31], b[32]), std::swap(b[33], b[34]);
      std::swap(b[37], b[38]);
    }
    const nlohmann::json j = decode_binary_json(b, "mem.bgeo");
    ASSERT_EQ(j.size(), 6u) << j.dump();
    EXPECT_EQ(j[0], 258);
    EXPECT_EQ(j[1], 1.0);
    EXPECT_EQ(j[2], "ab");
    EXPECT_EQ(j[3], nlohmann::json::parse("[false, true]"));
    EXPECT_EQ(j[4], nlohmann::json::parse("[1.0, -2.0]"));
    EXPECT_EQ(j[5], std::string(300, 'x'));
  }
}

TEST(WEFT_TEST_SUITE, houdini_vellum_like_geometry_round_trips_exactly) {
  const ScratchDir dir("roundtrip");
  const Geometry g = vellum_like();
  write_geo(g, dir.file("asset.geo"));
  write_bgeo(g, dir.file("asset.bgeo"));
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"asset.bgeo", "asset.geo"}));  // no temporary left
  EXPECT_EQ(read_bytes(dir.file("asset.geo")).substr(0, 1), "[");
  EXPECT_EQ(read_bytes(dir.file("asset.bgeo")).substr(0, 5), "\x7fNSJb");

  for (const char* name : {"asset.geo", "asset.bgeo"}) {
    SCOPED_TRACE(name);
    const Geometry r = read_geo(dir.file(name));
    expect_same(g, r);
    EXPECT_TRUE(r.warnings.empty());
  }
  write_bgeo(Geometry{}, dir.file("empty.bgeo"));
  EXPECT_TRUE(read_geo(dir.file("empty.bgeo")).points.empty());
  fs::remove(dir.file("empty.bgeo"));
  // Writing what was read changes nothing.
  write_geo(read_geo(dir.file("asset.bgeo")), dir.file("again.geo"));
  EXPECT_EQ(read_bytes(dir.file("again.geo")), read_bytes(dir.file("asset.geo")));
}

TEST(WEFT_TEST_SUITE, houdini_cloth_frame_from_a_trimesh_round_trips) {
  const ScratchDir dir("frame");
  weft::io::TriMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Geometry g = from_trimesh(mesh);
  // Houdini's winding is clockwise seen from the front: the normal of the first polygon points to -z.
  const weft::Vec3 a = g.points[size_t(g.primitives[0].points[0])], b = g.points[size_t(g.primitives[0].points[1])],
                   c = g.points[size_t(g.primitives[0].points[2])];
  EXPECT_LT(weft::cross(b - a, c - a).z, 0.0);
  Geometry exact = g;
  exact.position_storage = Storage::Float64;
  write_geo(exact, dir.file("cloth.0001.geo"));
  const weft::io::TriMesh back = to_trimesh(read_geo(dir.file("cloth.0001.geo")));
  EXPECT_EQ(back.triangles, mesh.triangles);
  ASSERT_EQ(back.positions.size(), mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) EXPECT_TRUE(back.positions[i] == mesh.positions[i]);
}

TEST(WEFT_TEST_SUITE, houdini_older_primitive_forms_and_paged_attributes_read) {
  const ScratchDir dir("forms");
  // A run of open polys, a single closed Poly whose vertex list runs backwards, a Sphere; P stored in pages
  // of 2 with packing [1, 2] and constant pages; a per-vertex attribute that must follow the vertex order.
  const std::string doc = R"(["pointcount",3,"vertexcount",8,"primitivecount",4,
"topology",["pointref",["indices",[0,1,1,2,0,1,2,2]]],
"attributes",[
 "vertexattributes",[[["scope","public","type","numeric","name","w","options",{}],
  ["size",1,"storage","int32","values",["size",1,"storage","int32","arrays",[[0,1,2,3,4,5,6,7]]]]]],
 "pointattributes",[[["scope","public","type","numeric","name","P","options",{}],
  ["size",3,"storage","fpreal64","values",["size",3,"storage","fpreal64","pagesize",2,"packing",[1,2],
   "constantpageflags",[[false,true],[true,false]],"rawpagedata",[1,2,5,6,3,7,8]]]]]],
"primitives",[
 [["type","run","runtype","Poly","varyingfields",["vertex"],"uniformfields",{"closed":false}],[[[0,1]],[[2,3]]]],
 [["type","Poly"],["vertex",[6,5,4],"closed",true]],
 [["type","Sphere"],["vertex",7,"transform",[2,0,0,0,2,0,0,0,2]]]]])";
  dir.write("forms.geo", doc);
  const Geometry g = read_geo(dir.file("forms.geo"));
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_TRUE(g.points[0] == (weft::Vec3{1, 5, 6}));
  EXPECT_TRUE(g.points[1] == (weft::Vec3{2, 5, 6}));
  EXPECT_TRUE(g.points[2] == (weft::Vec3{3, 7, 8}));
  ASSERT_EQ(g.primitives.size(), 4u);
  EXPECT_EQ(g.primitives[0].kind, PrimKind::Polyline);
  EXPECT_EQ(g.primitives[0].points, (std::vector<int>{0, 1}));
  EXPECT_EQ(g.primitives[1].kind, PrimKind::Polyline);
  EXPECT_EQ(g.primitives[1].points, (std::vector<int>{1, 2}));
  EXPECT_EQ(g.primitives[2].kind, PrimKind::Polygon);
  EXPECT_EQ(g.primitives[2].points, (std::vector<int>{2, 1, 0}));
  EXPECT_EQ(g.primitives[3].kind, PrimKind::Sphere);
  EXPECT_EQ(g.primitives[3].points, (std::vector<int>{2}));
  EXPECT_EQ(g.primitives[3].transform[4], 2.0);
  EXPECT_EQ(g.vertex_attributes.at("w").ints, (std::vector<int64_t>{0, 1, 2, 3, 6, 5, 4, 7}));
}

TEST(WEFT_TEST_SUITE, houdini_unknown_primitives_and_attributes_are_reported) {
  const ScratchDir dir("unknown");
  std::string doc =
      replaced(kTriangle, R"([[["type","Polygon_run"],["startvertex",0,"nprimitives",1,"nvertices_rle",[3,1]]]])",
               R"([[["type","Part"],["vertex",[0,1,2],"renderproperties",{}]]])");
  doc = replaced(doc, R"("pointattributes",[)",
                 R"("pointattributes",[[["scope","public","type","dict","name","meta","options",{}],["size",1]],)");
  dir.write("part.geo", doc);
  const Geometry g = read_geo(dir.file("part.geo"));
  ASSERT_EQ(g.primitives.size(), 1u);
  EXPECT_EQ(g.primitives[0].kind, PrimKind::Other);
  EXPECT_EQ(g.primitives[0].type_name, "Part");
  EXPECT_EQ(g.primitives[0].points, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(g.point_attributes.empty());
  ASSERT_EQ(g.warnings.size(), 2u);
  EXPECT_TRUE(contains(g.warnings[0], "'meta'") && contains(g.warnings[0], "'dict'")) << g.warnings[0];
  EXPECT_TRUE(contains(g.warnings[1], "'Part'")) << g.warnings[1];

  // An opaque primitive cannot be written back; nothing is left behind.
  const std::string out = dir.file("out.geo");
  const std::string msg = format_error([&] { write_geo(g, out); });
  EXPECT_TRUE(contains(msg, out) && contains(msg, "primitive 0") && contains(msg, "'Part'")) << msg;
  EXPECT_FALSE(fs::exists(out));

  // A type whose vertices cannot be read stops the read, naming the primitive.
  dir.write("packed.geo",
            replaced(kTriangle, R"([["type","Polygon_run"],["startvertex",0,"nprimitives",1,"nvertices_rle",[3,1]]])",
                     R"([["type","PackedGeometry"],["parameters",[]]])"));
  const std::string packed = format_error([&] { read_geo(dir.file("packed.geo")); });
  EXPECT_TRUE(contains(packed, "packed.geo: primitive 0") && contains(packed, "'PackedGeometry'")) << packed;
}

TEST(WEFT_TEST_SUITE, houdini_malformed_files_name_the_file_and_the_element) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const ScratchDir dir("malformed");
  const auto error_for = [&](const std::string& name, const std::string& bytes) {
    dir.write(name, bytes);
    return format_error([&] { read_geo(dir.file(name)); });
  };
  const std::string text = read_bytes(houdini_file("default.geo"));
  const std::string truncated = error_for("truncated.geo", text.substr(0, text.size() / 2));
  EXPECT_TRUE(contains(truncated, dir.file("truncated.geo") + ": ") && contains(truncated, "line")) << truncated;

  const std::string binary = read_bytes(houdini_file("default.bgeo"));
  std::string bad = binary;
  bad[6] = char(0x99);
  const std::string bad_token = error_for("bad_token.bgeo", bad);
  EXPECT_TRUE(contains(bad_token, "bad_token.bgeo: byte 6: ") && contains(bad_token, "0x99")) << bad_token;
  const std::string cut = error_for("cut.bgeo", binary.substr(0, 0x3b0));  // inside P's page data
  EXPECT_TRUE(contains(cut, "cut.bgeo: byte ") && contains(cut, "ends inside")) << cut;
  const std::string magic = error_for("magic.bgeo", "\x7fNSJx" + binary.substr(5));
  EXPECT_TRUE(contains(magic, "magic.bgeo: ") && contains(magic, "magic")) << magic;

  const std::string range = error_for("range.geo", replaced(kTriangle, "[0,1,2]", "[0,1,7]"));
  EXPECT_TRUE(contains(range, "range.geo: topology: vertex 2 refers to point 7")) << range;
  const std::string no_p = error_for("no_p.geo", replaced(kTriangle, R"("name","P")", R"("name","Q")"));
  EXPECT_TRUE(contains(no_p, "no_p.geo: point attribute 'P': missing")) << no_p;
  const std::string tuple = error_for("tuple.geo", replaced(kTriangle, "[1,0,0]", "[1,0]"));
  EXPECT_TRUE(contains(tuple, "tuple.geo: point attribute 'P': tuple 1 has 2 values, expected 3")) << tuple;
  const std::string prim =
      error_for("prim.geo", replaced(kTriangle, R"("nvertices_rle",[3,1])", R"("nvertices_rle",[4,1])"));
  EXPECT_TRUE(contains(prim, "prim.geo: primitive 0: vertices 0 to 3 are out of range")) << prim;
  const std::string count =
      error_for("count.geo", replaced(kTriangle, R"("primitivecount",1)", R"("primitivecount",2)"));
  EXPECT_TRUE(contains(count, "count.geo: primitives: ")) << count;
  const std::string other = error_for("other.geo", "PGEOMETRY V5\n");
  EXPECT_TRUE(contains(other, "other.geo: ") && contains(other, "classic")) << other;
}

TEST(WEFT_TEST_SUITE, houdini_writer_is_all_or_nothing) {
  const ScratchDir dir("atomic");
  const Geometry g = vellum_like();

  const std::string missing = dir.file("no_such_folder/frame.0001.geo");
  EXPECT_THROW(write_geo(g, missing), std::system_error);
  EXPECT_FALSE(fs::exists(missing));

  // The rename fails (the target is a folder): the temporary is removed.
  fs::create_directory(dir.path / "taken.bgeo");
  EXPECT_THROW(write_bgeo(g, dir.file("taken.bgeo")), std::system_error);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"taken.bgeo"});

  // Geometry the file could not describe is refused before anything is written.
  Geometry wrong = g;
  wrong.point_attributes["mass"].floats.pop_back();
  const std::string msg = format_error([&] { write_geo(wrong, dir.file("wrong.geo")); });
  EXPECT_TRUE(contains(msg, dir.file("wrong.geo") + ": point attribute 'mass': holds 3 values")) << msg;
  Geometry dangling = g;
  dangling.primitives[1].points[1] = 9;
  const std::string msg2 = format_error([&] { write_bgeo(dangling, dir.file("dangling.bgeo")); });
  EXPECT_TRUE(contains(msg2, "dangling.bgeo: primitive 1: refers to point 9")) << msg2;
  Geometry narrow = g;
  narrow.point_attributes["layer"].ints[0] = 300;
  const std::string msg3 = format_error([&] { write_geo(narrow, dir.file("narrow.geo")); });
  EXPECT_TRUE(contains(msg3, "point attribute 'layer': element 0 holds 300")) << msg3;
  EXPECT_EQ(dir.entries(), std::set<std::string>{"taken.bgeo"});

  write_geo(g, dir.file("ok.geo"));
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"ok.geo", "taken.bgeo"}));
}

}  // namespace
