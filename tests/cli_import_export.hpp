// Files in and out of weft from the command line: `weft run --geo-sequence` and `weft export` write one file
// per frame; the artist's loop Vellum .geo -> `weft import-vellum` -> run -> export back to Houdini, and what
// each of those commands refuses.
#include "io/cache_file.hpp"
#include "io/houdini_geo.hpp"
#include "io/obj.hpp"
#include "io/scene_file.hpp"
#include "tests/cli_fixture.hpp"
#include "tests/houdini_geometry_fixture.hpp"
#include "tests/io_cache_fixture.hpp"
#include "tests/io_checks_fixture.hpp"

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::Cli;
using weft::test::cloth;
using weft::test::cloth_sim;
using weft::test::ConstraintGeo;
using weft::test::contains;
using weft::test::distance_constraints;
using weft::test::expect_same_but_p_and_v;
using weft::test::f32;
using weft::test::kSheet;
using weft::test::same_bits;
using weft::test::ScratchDir;

TEST(WEFT_TEST_SUITE, cli_geo_sequence_and_export_write_one_file_per_frame) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_files");
  Cli weft(dir);
  const std::string cache = dir.file("c.h5");
  ASSERT_EQ(weft(kSheet + " --frames 1-4 -o " + cache + " --geo-sequence " + dir.file("geo")), 0) << weft.output;
  EXPECT_EQ(dir.entries("geo"), (std::set<std::string>{"hanging-sheet.0001.geo", "hanging-sheet.0002.geo",
                                                       "hanging-sheet.0003.geo", "hanging-sheet.0004.geo"}));
  const CacheReader r(cache);
  const Geometry g = read_geo(dir.file("geo/hanging-sheet.0004.geo"));
  ASSERT_EQ(g.points.size(), r.header().points);
  ASSERT_EQ(g.primitives.size(), r.header().triangles.size());
  ASSERT_EQ(g.point_attributes.count("v"), 1u);
  const std::vector<Vec3> x = r.positions(3), v = r.velocities(3);
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(g.points[i].y, double(float(x[i].y))) << "point " << i;
    EXPECT_EQ(g.point_attributes.at("v").number(i, 1), double(float(v[i].y))) << "point " << i;
  }

  ASSERT_EQ(weft("export " + cache + " --format obj " + dir.file("obj") + " --frames 2-3"), 0) << weft.output;
  EXPECT_EQ(dir.entries("obj"), (std::set<std::string>{"hanging-sheet.0002.obj", "hanging-sheet.0003.obj"}));
  const TriMesh m = read_obj(dir.file("obj/hanging-sheet.0003.obj"));
  EXPECT_TRUE(same_bits(m.positions, r.positions(2)));
  EXPECT_EQ(m.triangles, r.header().triangles);
  EXPECT_EQ(weft("export " + cache + " " + dir.file("geo2")), 0) << weft.output;
  EXPECT_EQ(dir.entries("geo2"), dir.entries("geo"));
  EXPECT_EQ(weft("export " + cache + " " + dir.file("geo3") + " --frames 3-5"), 2);
}

// The artist's loop: a Vellum .geo into weft, simulated, and back as .bgeo and .geo frames that can stand in
// for the Vellum solver's output, with P and v from the cache (float32, as the file stores P).
TEST(WEFT_TEST_SUITE, io_geo_vellum_cloth_round_trips_through_import_run_and_export) {
  WEFT_NEED_CLI();
  const ScratchDir dir("geo_round_trip");
  Cli weft(dir);
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

  const std::set<std::string> bgeo_frames{"cloth.0001.bgeo", "cloth.0002.bgeo", "cloth.0003.bgeo",
                                             "cloth.0004.bgeo"};
  EXPECT_EQ(dir.entries("run"), bgeo_frames);
  EXPECT_EQ(dir.entries("bgeo"), bgeo_frames);
  EXPECT_EQ(dir.entries("auto"), bgeo_frames);
  EXPECT_EQ(dir.entries("geo"),
            (std::set<std::string>{"cloth.0001.geo", "cloth.0002.geo", "cloth.0003.geo", "cloth.0004.geo"}));

  const CacheReader cache(dir.file("cache.h5"));
  ASSERT_EQ(cache.frame_count(), 4);
  bool moved = false;
  for (int k = 0; k < 4; ++k) {
    const std::string name = "cloth.000" + std::to_string(k + 1);
    // weft run writes what the cache holds, frame by frame, through the same writer.
    EXPECT_EQ(dir.read("run/" + name + ".bgeo"), dir.read("bgeo/" + name + ".bgeo")) << name;
    EXPECT_EQ(dir.read("auto/" + name + ".bgeo"), dir.read("bgeo/" + name + ".bgeo")) << name;
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
  WEFT_NEED_CLI();
  const ScratchDir dir("geo_mismatch");
  Cli weft(dir);
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
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"c.h5", "cloth.bgeo"}));

  // --like writes Houdini geometry only, and goes with --geo-sequence in weft run.
  EXPECT_EQ(weft("export " + dir.file("c.h5") + " --format obj " + dir.file("out") + " --like " + dir.file("cloth.bgeo")),
            2);
  EXPECT_TRUE(contains(weft.output, "--like goes with --format geo or bgeo")) << weft.output;
  EXPECT_NE(weft("run builtin:hanging-sheet --res 2 --frames 1-2 --like " + dir.file("cloth.bgeo")), 0);
  EXPECT_TRUE(contains(weft.output, "--geo-sequence")) << weft.output;

  // Without --like: the triangulated sheet with P and v, in the format asked for.
  ASSERT_EQ(weft("export " + dir.file("c.h5") + " --format bgeo " + dir.file("out")), 0) << weft.output;
  EXPECT_EQ(dir.entries("out"), (std::set<std::string>{"hanging-sheet.0001.bgeo", "hanging-sheet.0002.bgeo"}));
  const Geometry sheet = read_geo(dir.file("out/hanging-sheet.0002.bgeo"));
  EXPECT_EQ(sheet.points.size(), 9u);
  EXPECT_EQ(sheet.primitives.size(), 8u);
  EXPECT_TRUE(sheet.point_attributes.count("v"));
}

// weft import-vellum --collider-thickness / --collider-friction [NAME=]VALUE: every collider, or one by name.
TEST(WEFT_TEST_SUITE, io_vellum_cli_sets_each_colliders_thickness_and_friction) {
  WEFT_NEED_CLI();
  const ScratchDir dir("collider_values");
  const Geometry sim = cloth_sim();
  write_geo(sim, dir.file("cloth.geo"));
  Geometry body;
  body.points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  body.primitives.resize(1);
  body.primitives[0].points = {0, 1, 2};
  write_geo(body, dir.file("body.geo"));
  write_geo(body, dir.file("rock.geo"));
  ConstraintGeo(sim).write(dir.file("constraints.geo"));
  Cli weft(dir);
  const std::string import = "import-vellum " + dir.file("cloth.geo") + " " + dir.file("constraints.geo") +
                             " --collider " + dir.file("body.geo") + " --collider " + dir.file("rock.geo") + " -o " +
                             dir.file("s.h5") + " ";
  ASSERT_EQ(weft(import + "--collider-thickness 0.004 --collider-thickness rock=0.02 --collider-friction body=0.1"), 0)
      << weft.output;
  const Scene s = read_scene(dir.file("s.h5"));
  ASSERT_EQ(s.colliders.size(), 2u);
  EXPECT_EQ(s.colliders[0].thickness, 0.004);
  EXPECT_EQ(s.colliders[1].thickness, 0.02);
  EXPECT_EQ(s.colliders[0].friction, 0.1);
  EXPECT_EQ(s.colliders[1].friction, Collider{}.friction);
  EXPECT_EQ(weft(import + "--collider-thickness skin=0.01"), 2);
  EXPECT_EQ(weft(import + "--collider-thickness -1"), 2);
}

}  // namespace
