// Frames back into Houdini: groups in .geo / .bgeo, frames as copies of the simulation geometry (frame_like,
// GeoFrameWriter). The whole round trip Vellum .geo -> import-vellum -> run -> export, through the command
// line, is in cli_import_export.
#include "io/geo_writeback.hpp"
#include "io/houdini_geo.hpp"
#include "tests/houdini_geometry_fixture.hpp"
#include "tests/io_checks_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace {

using weft::test::contains;
using weft::test::input_error;

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::cloth;
using weft::test::expect_same_but_p_and_v;
using weft::test::flags;
using weft::test::ScratchDir;

// A file as Houdini writes groups: i8 and boolRLE selections, an ordered group, and a vertex group in a
// file whose vertex numbers run in another order than the primitives' (the older run form).
const std::string kGroups = R"(["fileversion","16.5.268","hasindex",false,
"pointcount",4,"vertexcount",6,"primitivecount",2,
"topology",["pointref",["indices",[0,1,2,2,1,3]]],
"attributes",["pointattributes",[
 [["scope","public","type","numeric","name","P","options",{}],
  ["size",3,"storage","fpreal32","values",["size",3,"storage","fpreal32","tuples",[[0,0,0],[1,0,0],[0,1,0],[1,1,0]]]]]]],
"primitives",[[["type","run","runtype","Poly","varyingfields",["vertex"],"uniformfields",{"closed":true}],
 [[[3,4,5]],[[0,1,2]]]]],
"pointgroups",[[["name","corner"],["selection",["unordered",["i8",[1,0,0,1]]]]]],
"primitivegroups",[[["name","second"],["selection",["unordered",["boolRLE",[1,false,1,true]]]]],
 [["name","picked","type","primitive"],["selection",["defaults",["size",1,"storage","fpreal64","values",[0]],
  "ordered",[1]]]]],
"vertexgroups",[[["name","tip"],["selection",["unordered",["i8",[0,0,0,0,0,1]]]]]]])";

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

TEST(WEFT_TEST_SUITE, io_geo_groups_read_as_houdini_writes_them_and_round_trip) {
  const ScratchDir dir("geo_groups");
  dir.write("houdini.geo", kGroups);
  const Geometry g = read_geo(dir.file("houdini.geo"));
  EXPECT_EQ(g.point_groups, (GroupMap{{"corner", flags({1, 0, 0, 1})}}));
  EXPECT_EQ(g.primitive_groups, (GroupMap{{"picked", flags({0, 1})}, {"second", flags({0, 1})}}));
  // File vertex 5 is the third vertex of primitive 0.
  EXPECT_EQ(g.vertex_groups, (GroupMap{{"tip", flags({0, 0, 1, 0, 0, 0})}}));
  ASSERT_EQ(g.warnings.size(), 1u);
  EXPECT_TRUE(contains(g.warnings[0], "primitive group 'picked': ordered")) << g.warnings[0];

  for (const char* name : {"again.geo", "again.bgeo"}) {
    SCOPED_TRACE(name);
    if (contains(name, "bgeo"))
      write_bgeo(g, dir.file(name));
    else
      write_geo(g, dir.file(name));
    const Geometry r = read_geo(dir.file(name));
    EXPECT_EQ(r.point_groups, g.point_groups);
    EXPECT_EQ(r.primitive_groups, g.primitive_groups);
    EXPECT_EQ(r.vertex_groups, g.vertex_groups);
    EXPECT_TRUE(r.warnings.empty());
  }
  EXPECT_TRUE(contains(dir.read("again.geo"), R"("boolRLE",[1,true,2,false,1,true])"));  // the corner group

  // Malformed selections name the file and the group; a group of the wrong size is not written.
  dir.write("short.geo", replaced(kGroups, "[1,false,1,true]", "[1,false]"));
  std::string e = input_error([&] { read_geo(dir.file("short.geo")); });
  EXPECT_TRUE(contains(e, "short.geo: primitive group 'second': boolRLE describes 1 primitives, there are 2")) << e;
  dir.write("i8.geo", replaced(kGroups, "[1,0,0,1]", "[1,0,0]"));
  e = input_error([&] { read_geo(dir.file("i8.geo")); });
  EXPECT_TRUE(contains(e, "i8.geo: point group 'corner': i8 holds 3 flags, there are 4 points")) << e;
  dir.write("range.geo", replaced(kGroups, R"("ordered",[1])", R"("ordered",[2])"));
  e = input_error([&] { read_geo(dir.file("range.geo")); });
  EXPECT_TRUE(contains(e, "primitive group 'picked': element 2 is out of range, there are 2 primitives")) << e;
  Geometry wrong = g;
  wrong.vertex_groups["tip"].pop_back();
  e = input_error([&] { write_bgeo(wrong, dir.file("wrong.bgeo")); });
  EXPECT_TRUE(contains(e, "wrong.bgeo: vertex group 'tip': holds 5 flags, expected 6")) << e;
  EXPECT_FALSE(fs::exists(dir.file("wrong.bgeo")));
}

TEST(WEFT_TEST_SUITE, io_geo_frame_like_replaces_p_and_v_only) {
  const Geometry like = cloth();
  std::vector<Vec3> x, v;
  for (size_t p = 0; p < like.points.size(); ++p) {
    x.push_back(like.points[p] + Vec3{0.1, -0.3 * double(p), 0.01});
    v.push_back({0, -1.0 / 3 * double(p), 0.5});
  }
  const Geometry g = frame_like(like, x, v);
  expect_same_but_p_and_v(like, g);
  for (size_t p = 0; p < x.size(); ++p) EXPECT_TRUE(g.points[p] == x[p]) << p;
  // v is added as Houdini keeps velocities: a float32 vector.
  const Attribute& added = g.point_attributes.at("v");
  EXPECT_EQ(added.storage, Storage::Float32);
  EXPECT_EQ(added.size, 3);
  EXPECT_EQ(added.qualifier, "vector");
  EXPECT_EQ(added.number(4, 1), v[4].y);

  // A v the file has keeps its storage; one that is not a float triple is replaced.
  Geometry with_v = like;
  with_v.point_attributes["v"] = float_attribute(3, std::vector<double>(36, 7.0), Storage::Float64);
  const Attribute& kept = frame_like(with_v, x, v).point_attributes.at("v");
  EXPECT_EQ(kept.storage, Storage::Float64);
  EXPECT_EQ(kept.qualifier, "");
  EXPECT_EQ(kept.number(11, 2), 0.5);
  with_v.point_attributes["v"] = int_attribute(1, std::vector<int64_t>(12, 1));
  EXPECT_EQ(frame_like(with_v, x, v).point_attributes.at("v").storage, Storage::Float32);

  x.pop_back();
  const std::string e = input_error([&] { frame_like(like, x, v); });
  EXPECT_TRUE(contains(e, "11 positions and 12 velocities")) << e;
}

TEST(WEFT_TEST_SUITE, io_geo_frame_writer_checks_the_like_file_first) {
  const ScratchDir dir("geo_frame_writer");
  write_bgeo(cloth(), dir.file("cloth.bgeo"));
  EXPECT_EQ(geo_format("", dir.file("cloth.bgeo")), GeoFormat::Binary);
  EXPECT_EQ(geo_format("", dir.file("cloth.geo")), GeoFormat::Text);
  EXPECT_EQ(geo_format("geo", dir.file("cloth.bgeo")), GeoFormat::Text);
  EXPECT_EQ(geo_format(""), GeoFormat::Text);
  EXPECT_TRUE(contains(input_error([] { geo_format("usd"); }), "'usd'"));

  std::string e = input_error([&] { GeoFrameWriter("", dir.file("cloth.bgeo"), 13, {}, "the cache c.h5"); });
  EXPECT_TRUE(contains(e, dir.file("cloth.bgeo") + " has 12 points but the cache c.h5 has 13")) << e;
  e = input_error([&] { GeoFrameWriter("", dir.file("missing.geo"), 12, {}, "the cache c.h5"); });
  EXPECT_TRUE(contains(e, "missing.geo")) << e;
  // Geometry that cannot be written back (an opaque primitive) is refused before the first frame.
  dir.write("part.geo", replaced(kGroups, R"(["type","run","runtype","Poly")", R"(["type","run","runtype","Part")"));
  e = input_error([&] { GeoFrameWriter("geo", dir.file("part.geo"), 4, {}, "the scene s"); });
  EXPECT_TRUE(contains(e, "part.geo: primitive 0: type 'Part' cannot be written")) << e;

  // Without a --like file: the triangulated mesh with P and v, in either format.
  GeoFrameWriter mesh("bgeo", "", 3, {{0, 1, 2}}, "the cache c.h5");
  EXPECT_STREQ(mesh.extension(), "bgeo");
  mesh.write(dir.file("tri.0001.bgeo"), {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 0}, {0, -1, 0}, {0, 0, 0}});
  const Geometry tri = read_geo(dir.file("tri.0001.bgeo"));
  EXPECT_EQ(tri.primitives.size(), 1u);
  EXPECT_EQ(tri.point_attributes.at("v").number(1, 1), -1);
  EXPECT_EQ(dir.read("tri.0001.bgeo").substr(0, 5), "\x7fNSJb");
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"cloth.bgeo", "part.geo", "tri.0001.bgeo"}));
}

}  // namespace
