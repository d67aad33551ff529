// Frames back into Houdini: groups in .geo / .bgeo, frames as copies of the simulation geometry (frame_like,
// GeoFrameWriter), and the whole round trip Vellum .geo -> import-vellum -> run -> export, through the CLI.
#include "core/error.hpp"
#include "io/cache_file.hpp"
#include "io/geo_writeback.hpp"
#include "io/houdini_geo.hpp"
#include "tests/io_checks_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

namespace {

using weft::test::contains;
using weft::test::input_error;
using weft::test::expect_same_attributes;

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::ScratchDir;

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> listing(const std::string& folder) {
  std::vector<std::string> names;
  if (fs::exists(folder))
    for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Rounded to float. Through a volatile: GCC 12 -O3 drops the rounding of double(float(x)) when its SLP
// vectorizer packs two of them (as in a braced list of f32 calls).
double f32(double x) {
  volatile float f = float(x);
  return f;
}

std::vector<bool> flags(std::initializer_list<int> v) {
  std::vector<bool> out;
  for (const int x : v) out.push_back(x != 0);
  return out;
}

// A Vellum-style cloth as Houdini hands it over: a 4 x 3 grid 0.25 m apart at y = 1 (point j*4+i at
// (0.25 i, 1, 0.25 j)), six quads, UVs on vertices, an extra float and an int point attribute, a point and a
// primitive group, a primitive string and detail attributes (the frame range among them); no v.
Geometry cloth() {
  Geometry g;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) g.points.push_back({0.25 * i, 1, 0.25 * j});
  std::vector<double> uv;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      Primitive p;
      const int a = j * 4 + i;
      p.points = {a, a + 1, a + 5, a + 4};
      for (const int q : p.points) uv.insert(uv.end(), {f32(g.points[q].x / 0.75), f32(g.points[q].z / 0.5), 0});
      g.primitives.push_back(p);
    }
  g.vertex_attributes["uv"] = float_attribute(3, uv);
  std::vector<double> mask;
  for (int p = 0; p < 12; ++p) mask.push_back(f32(0.1 * p));
  g.point_attributes["clothmask"] = float_attribute(1, mask);
  g.point_attributes["stopped"] = int_attribute(1, {1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0});
  g.point_groups["pinned"] = flags({1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0});
  g.primitive_groups["front"] = flags({1, 1, 1, 0, 0, 0});
  g.primitive_attributes["name"] = string_attribute(1, {"shirt", "shirt", "shirt", "sleeve", "sleeve", "sleeve"});
  g.detail_attributes["framestart"] = int_attribute(1, {1});
  g.detail_attributes["frameend"] = int_attribute(1, {4});
  g.detail_attributes["asset"] = string_attribute(1, {"shirt_v3"});
  return g;
}

// The constraint geometry the Vellum Constraints node would write for it: a distance constraint per edge.
Geometry distance_constraints(const Geometry& sim) {
  Geometry c;
  c.points = sim.points;
  std::vector<std::string> type;
  std::vector<double> stiffness, rest;
  const auto edge = [&](int a, int b) {
    Primitive p;
    p.kind = PrimKind::Polyline;
    p.points = {a, b};
    c.primitives.push_back(p);
    type.push_back("distance");
    stiffness.push_back(1e4);
    rest.push_back(0.25);
  };
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      if (i < 3) edge(j * 4 + i, j * 4 + i + 1);
      if (j < 2) edge(j * 4 + i, j * 4 + i + 4);
    }
  c.primitive_attributes["type"] = string_attribute(1, type);
  c.primitive_attributes["stiffness"] = float_attribute(1, stiffness);
  c.primitive_attributes["restlength"] = float_attribute(1, rest);
  return c;
}

// Everything of `original` but P and the point attribute v is in `frame`, unchanged.
void expect_same_but_p_and_v(const Geometry& original, const Geometry& frame) {
  ASSERT_EQ(frame.points.size(), original.points.size());
  EXPECT_EQ(frame.position_storage, original.position_storage);
  ASSERT_EQ(frame.primitives.size(), original.primitives.size());
  for (size_t i = 0; i < original.primitives.size(); ++i) {
    EXPECT_EQ(frame.primitives[i].kind, original.primitives[i].kind) << "primitive " << i;
    EXPECT_EQ(frame.primitives[i].points, original.primitives[i].points) << "primitive " << i;
  }
  AttributeMap points = frame.point_attributes, original_points = original.point_attributes;
  points.erase("v");
  original_points.erase("v");
  expect_same_attributes(original_points, points, "point");
  expect_same_attributes(original.vertex_attributes, frame.vertex_attributes, "vertex");
  expect_same_attributes(original.primitive_attributes, frame.primitive_attributes, "primitive");
  expect_same_attributes(original.detail_attributes, frame.detail_attributes, "detail");
  EXPECT_EQ(frame.point_groups, original.point_groups);
  EXPECT_EQ(frame.vertex_groups, original.vertex_groups);
  EXPECT_EQ(frame.primitive_groups, original.primitive_groups);
}

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
  EXPECT_EQ(bytes_of(dir.file("tri.0001.bgeo")).substr(0, 5), "\x7fNSJb");
  EXPECT_EQ(listing(dir.path.string()), (std::vector<std::string>{"cloth.bgeo", "part.geo", "tri.0001.bgeo"}));
}

// Runs `weft <args>` (serial backend) and keeps its output.
struct Weft {
  const ScratchDir& dir;
  std::string output;
  static std::string binary() { return std::string(WEFT_BIN_DIR) + "/weft"; }
  int operator()(const std::string& args) {
    const std::string log = dir.file("weft.log");
    const int status = std::system((binary() + " --backend serial " + args + " > '" + log + "' 2>&1").c_str());
    output = bytes_of(log);
    fs::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
};

// The artist's loop: a Vellum .geo into weft, simulated, and back as .bgeo and .geo frames that can stand in
// for the Vellum solver's output, with P and v from the cache (float32, as the file stores P).
TEST(WEFT_TEST_SUITE, io_geo_vellum_cloth_round_trips_through_import_run_and_export) {
  if (!fs::exists(Weft::binary())) GTEST_SKIP() << Weft::binary() << " is not built";
  const ScratchDir dir("geo_round_trip");
  Weft weft{dir};
  const Geometry sim = cloth();
  write_geo(sim, dir.file("cloth.geo"));
  write_bgeo(sim, dir.file("cloth.bgeo"));
  write_geo(distance_constraints(sim), dir.file("constraints.geo"));
  ASSERT_EQ(weft("import-vellum " + dir.file("cloth.geo") + " " + dir.file("constraints.geo") + " -o " +
                 dir.file("scene.h5") + " --substeps 2 --iterations 4"),
            0)
      << weft.output;
  ASSERT_EQ(weft("run " + dir.file("scene.h5") + " --quiet -o " + dir.file("cache.h5") + " --geo-sequence " +
                 dir.file("run") + " --like " + dir.file("cloth.geo") + " --geo-format bgeo"),
            0)
      << weft.output;
  ASSERT_EQ(weft("export " + dir.file("cache.h5") + " --format bgeo " + dir.file("bgeo") + " --like " +
                 dir.file("cloth.geo")),
            0)
      << weft.output;
  EXPECT_TRUE(contains(weft.output, "wrote frames 1-4 to " + dir.file("bgeo") + "/cloth.$F4.bgeo")) << weft.output;
  ASSERT_EQ(weft("export " + dir.file("cache.h5") + " " + dir.file("geo") + " --format geo --like " +
                 dir.file("cloth.bgeo")),
            0)
      << weft.output;
  // No --format: the --like file's kind.
  ASSERT_EQ(weft("export " + dir.file("cache.h5") + " " + dir.file("auto") + " --like " + dir.file("cloth.bgeo")), 0)
      << weft.output;

  const std::vector<std::string> bgeo_frames{"cloth.0001.bgeo", "cloth.0002.bgeo", "cloth.0003.bgeo",
                                             "cloth.0004.bgeo"};
  EXPECT_EQ(listing(dir.file("run")), bgeo_frames);
  EXPECT_EQ(listing(dir.file("bgeo")), bgeo_frames);
  EXPECT_EQ(listing(dir.file("auto")), bgeo_frames);
  EXPECT_EQ(listing(dir.file("geo")),
            (std::vector<std::string>{"cloth.0001.geo", "cloth.0002.geo", "cloth.0003.geo", "cloth.0004.geo"}));

  const CacheReader cache(dir.file("cache.h5"));
  ASSERT_EQ(cache.frame_count(), 4);
  bool moved = false;
  for (int k = 0; k < 4; ++k) {
    const std::string name = "cloth.000" + std::to_string(k + 1);
    // weft run writes what the cache holds, frame by frame, through the same writer.
    EXPECT_EQ(bytes_of(dir.file("run/" + name + ".bgeo")), bytes_of(dir.file("bgeo/" + name + ".bgeo"))) << name;
    EXPECT_EQ(bytes_of(dir.file("auto/" + name + ".bgeo")), bytes_of(dir.file("bgeo/" + name + ".bgeo"))) << name;
    const std::vector<Vec3> x = cache.positions(k), v = cache.velocities(k);
    for (const std::string file : {"bgeo/" + name + ".bgeo", "geo/" + name + ".geo"}) {
      SCOPED_TRACE(file);
      const Geometry g = read_geo(dir.file(file));
      expect_same_but_p_and_v(sim, g);  // quads stay quads, point order, UVs, groups, attributes
      EXPECT_TRUE(g.warnings.empty());
      ASSERT_EQ(g.points.size(), x.size());
      const Attribute& vel = g.point_attributes.at("v");
      EXPECT_EQ(vel.storage, Storage::Float32);
      EXPECT_EQ(vel.qualifier, "vector");
      for (size_t p = 0; p < x.size(); ++p) {
        EXPECT_TRUE(g.points[p] == (Vec3{f32(x[p].x), f32(x[p].y), f32(x[p].z)})) << "point " << p;
        EXPECT_TRUE((Vec3{vel.number(p, 0), vel.number(p, 1), vel.number(p, 2)}) ==
                    (Vec3{f32(v[p].x), f32(v[p].y), f32(v[p].z)}))
            << "point " << p;
        moved = moved || !(x[p] == sim.points[p]);
      }
    }
  }
  EXPECT_TRUE(moved);  // the frames are the simulation's, not the input's
}

// A --like file of another cloth: exit 2 naming the file and both counts, and nothing written.
TEST(WEFT_TEST_SUITE, io_geo_like_file_of_another_point_count_is_refused) {
  if (!fs::exists(Weft::binary())) GTEST_SKIP() << Weft::binary() << " is not built";
  const ScratchDir dir("geo_mismatch");
  Weft weft{dir};
  ASSERT_EQ(weft("run builtin:hanging-sheet --res 2 --frames 1-2 --quiet -o " + dir.file("c.h5")), 0) << weft.output;
  write_bgeo(cloth(), dir.file("cloth.bgeo"));  // 12 points; the 2 x 2 sheet has 9

  EXPECT_EQ(weft("export " + dir.file("c.h5") + " --format bgeo " + dir.file("out") + " --like " +
                 dir.file("cloth.bgeo")),
            2);
  EXPECT_TRUE(contains(weft.output, dir.file("cloth.bgeo") + " has 12 points but the cache " + dir.file("c.h5") +
                                        " has 9"))
      << weft.output;
  EXPECT_FALSE(fs::exists(dir.file("out")));

  EXPECT_EQ(weft("run builtin:hanging-sheet --res 2 --frames 1-2 -o " + dir.file("r.h5") + " --geo-sequence " +
                 dir.file("seq") + " --like " + dir.file("cloth.bgeo")),
            2);
  EXPECT_TRUE(contains(weft.output, dir.file("cloth.bgeo") + " has 12 points but the scene builtin:hanging-sheet has 9"))
      << weft.output;
  EXPECT_EQ(listing(dir.path.string()), (std::vector<std::string>{"c.h5", "cloth.bgeo"}));

  // --like writes Houdini geometry only, and goes with --geo-sequence in weft run.
  EXPECT_EQ(weft("export " + dir.file("c.h5") + " --format obj " + dir.file("out") + " --like " + dir.file("cloth.bgeo")),
            2);
  EXPECT_TRUE(contains(weft.output, "--like goes with --format geo or bgeo")) << weft.output;
  EXPECT_NE(weft("run builtin:hanging-sheet --res 2 --frames 1-2 --like " + dir.file("cloth.bgeo")), 0);
  EXPECT_TRUE(contains(weft.output, "--geo-sequence")) << weft.output;

  // Without --like: the triangulated sheet with P and v, in the format asked for.
  ASSERT_EQ(weft("export " + dir.file("c.h5") + " --format bgeo " + dir.file("out")), 0) << weft.output;
  EXPECT_EQ(listing(dir.file("out")), (std::vector<std::string>{"hanging-sheet.0001.bgeo", "hanging-sheet.0002.bgeo"}));
  const Geometry sheet = read_geo(dir.file("out/hanging-sheet.0002.bgeo"));
  EXPECT_EQ(sheet.points.size(), 9u);
  EXPECT_EQ(sheet.primitives.size(), 8u);
  EXPECT_TRUE(sheet.point_attributes.count("v"));
}

}  // namespace
