// Commands that read what a run left: `weft compare` (bits or ULPs between two caches), `weft info` (a scene
// or cache file, or this build and its named schedules), `weft check-intersections` (a mesh), `weft check` (cloth
// that starts crossed).
#include "io/builtin_scenes.hpp"
#include "io/cache_file.hpp"
#include "io/scene_file.hpp"
#include "scene/schedules.hpp"
#include "tests/cli_fixture.hpp"
#include "tests/io_cache_fixture.hpp"

#include <cmath>
#include <fstream>
#include <string>
#include <utility>

namespace {

using namespace weft;
using namespace weft::io;
using weft::test::Cli;
using weft::test::Frames;
using weft::test::kSheet;
using weft::test::ScratchDir;
using weft::test::small_header;

// Two caches of 3 frames; the second differs at frame 8 (stored frame 1), point 3, position y, by 3 ULPs.
void write_pair(const ScratchDir& dir) {
  const Frames f(5, 7, 3, 4);
  Frames g = f;
  for (int i = 0; i < 3; ++i) g.x[1][3].y = std::nextafter(g.x[1][3].y, 2.0);
  for (const auto& [name, frames] : {std::pair<const char*, const Frames*>{"a.h5", &f}, {"b.h5", &g}}) {
    CacheWriter w(dir.file(name), small_header(5));
    frames->append_to(w, 0, 3);
    w.close();
  }
}

TEST(WEFT_TEST_SUITE, cli_compare_reports_the_first_difference) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_compare");
  write_pair(dir);
  Cli weft(dir);
  const std::string a = dir.file("a.h5"), b = dir.file("b.h5");
  EXPECT_EQ(weft("compare " + a + " " + a), 0);
  EXPECT_EQ(weft.output, "identical (3 frames)\n");
  EXPECT_EQ(weft("compare " + a + " " + b), 1);
  EXPECT_NE(weft.output.find("different: frame 8 point 3 position.y:"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("3 ULPs apart"), std::string::npos) << weft.output;
  EXPECT_EQ(weft("compare --ulp 2 " + a + " " + b), 1);
  EXPECT_EQ(weft("compare --ulp 3 " + a + " " + b), 0);
  EXPECT_EQ(weft.output, "within 3 ULPs (3 frames; largest difference 3 ULPs)\n");
  EXPECT_EQ(weft("compare " + a + " " + dir.file("absent.h5")), 2);
  EXPECT_NE(weft.output.find(dir.file("absent.h5") + ": no such file"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_info_describes_scene_and_cache_files) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_info");
  Cli weft(dir);
  write_scene(make_builtin_scene("hanging-sheet", {5}), dir.file("s.h5"));
  ASSERT_EQ(weft("info " + dir.file("s.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("weft scene, format version 1"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("points 36, triangles 50"), std::string::npos) << weft.output;
  ASSERT_EQ(weft(kSheet + " --frames 1-3 --quiet --hash -o " + dir.file("c.h5")), 0) << weft.output;
  const std::string hash = weft.hash();
  ASSERT_EQ(weft("info " + dir.file("c.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("weft cache, format version 1"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("frames 1-3 (3 stored, complete)"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("hash " + hash), std::string::npos) << weft.output;
  std::ofstream(dir.file("text.h5")) << "text";
  EXPECT_EQ(weft("info " + dir.file("text.h5")), 2);
  EXPECT_NE(weft.output.find("not an HDF5 file"), std::string::npos) << weft.output;
}

// weft info names each row of scene/schedules.hpp, one line each, for the report scripts to read.
TEST(WEFT_TEST_SUITE, cli_info_lists_the_named_schedules) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_info_schedules");
  Cli weft(dir);
  ASSERT_EQ(weft("info"), 0) << weft.output;
  for (const Schedule& s : kSchedules)
    EXPECT_NE(weft.output.find("\nschedule " + std::string(s.name) + ": substeps " + std::to_string(s.substeps) +
                               ", iterations " + std::to_string(s.iterations) + ", collision passes " +
                               std::to_string(s.collision_passes) + "\n"),
              std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_check_intersections_counts_a_static_obj_mesh) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_check_obj");
  Cli weft(dir);
  // Triangle 1 pierces triangle 2; triangle 3 shares a vertex with 1 (adjacent, not counted) and is far from 2.
  std::ofstream(dir.file("m.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "v 0.2 0.2 -0.5\nv 0.3 0.2 0.5\nv 0.2 0.3 0.5\n"
                                      "v -1 0 0\nv 0 -1 0\n"
                                      "f 1 2 3\nf 4 5 6\nf 1 7 8\n";
  ASSERT_EQ(weft("check-intersections " + dir.file("m.obj")), 0) << weft.output;
  EXPECT_EQ(weft.output, "intersections 1\n");
  std::ofstream(dir.file("bad.obj")) << "v 0 0 0\nf 1 2 3\n";
  EXPECT_NE(weft("check-intersections " + dir.file("bad.obj")), 0);
  EXPECT_NE(weft.output.find("bad.obj"), std::string::npos) << weft.output;
}

// Two sheets built through each other: `weft check` names the crossed pairs and fails, `weft run` warns and
// runs (with self collision; without it the sheets may pass through each other and nothing is said).
TEST(WEFT_TEST_SUITE, cli_check_lists_cloth_that_starts_crossed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_check_crossed");
  Cli weft(dir);
  const std::string scene = dir.write("crossed.json", R"({
    "settings": {"frames": [1, 2], "substeps": 2, "iterations": 4},
    "cloth": [
      {"generator": "grid", "res": [4, 4], "origin": [-0.5, 1, -0.5], "u": [1, 0, 0], "v": [0, 0, 1]},
      {"generator": "grid", "res": [4, 4], "origin": [-0.45, 0.5, 0.01], "u": [1, 0, 0], "v": [0, 1, 0]}
    ]})");
  EXPECT_EQ(weft("check " + scene), 1) << weft.output;
  EXPECT_NE(weft.output.find("the cloth starts with 26 intersecting triangle pairs\n"
                             "  triangles 16 (points 10 11 16) and 40 (points 30 31 35)\n"),
            std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("... and 6 more"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("26 cloth triangle pairs intersecting at the start: NOT clean"), std::string::npos)
      << weft.output;
  ASSERT_EQ(weft("run " + scene + " --quiet"), 0) << weft.output;
  EXPECT_NE(weft.output.find("warning: " + scene + ": the cloth starts with 26 intersecting triangle pairs, first "
                             "triangles 16 (points 10 11 16) and 40 (points 30 31 35)"),
            std::string::npos) << weft.output;
  ASSERT_EQ(weft("run " + scene + " --quiet --self-collision off"), 0) << weft.output;
  EXPECT_EQ(weft.output.find("starts with"), std::string::npos) << weft.output;
  // Untangled, the same sheets start clean.
  const std::string apart = dir.write("apart.json", R"({
    "cloth": [{"generator": "grid", "res": [4, 4], "origin": [-0.5, 1, -0.5], "u": [1, 0, 0], "v": [0, 0, 1]}]})");
  EXPECT_EQ(weft("check " + apart), 0) << weft.output;
  EXPECT_NE(weft.output.find("the cloth starts with 0 intersecting triangle pairs"), std::string::npos) << weft.output;
}

}  // namespace
