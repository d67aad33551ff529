// Pins that follow animation (JSON scenes, docs/scene-json.md): a waistband pinned to an animated OBJ
// sequence tracks it exactly on every backend; soft pins trail it; points attached to a moving collider move
// with its surface; stitches sew two pieces together.
#include "io/json_scene.hpp"
#include "io/obj.hpp"
#include "tests/scratch_dir_fixture.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <cmath>

namespace {

using weft::real;
using weft::Vec3;

// A grid piece of 4 x 4 quads (points j * 5 + i) and its animated copy: the top row (the waistband, points
// 20..24) slides along x and turns about y, frame by frame.
weft::io::TriMesh band_frame(int frame) {
  const weft::io::Mesh g = weft::io::grid(4, 4, {-0.2, 0.6, 0}, {0.4, 0, 0}, {0, 0.4, 0});
  weft::io::TriMesh m{g.x, g.tris};
  const real a = 0.05 * (frame - 1), dx = 0.02 * (frame - 1);
  for (Vec3& p : m.positions) p = {std::cos(a) * p.x + std::sin(a) * p.z + dx, p.y, -std::sin(a) * p.x + std::cos(a) * p.z};
  return m;
}

std::string pinned_band_json(const weft::test::ScratchDir& dir, const std::string& pin) {
  for (int f = 1; f <= 6; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "band.%04d.obj", f);
    weft::io::write_obj(band_frame(f), dir.file(name));
  }
  weft::io::write_obj(band_frame(1), dir.file("cloth.obj"));
  return R"({"settings": {"frames": [1, 6], "substeps": 4, "iterations": 10},
             "cloth": [{"obj": "cloth.obj", "pins": [{"box": {"min": [-1, 0.99, -1], "max": [1, 1.01, 1]}, )" +
         pin + R"(}]}]})";
}

TEST(WEFT_TEST_SUITE, waistband_pinned_to_an_animated_sequence_tracks_it_exactly) {
  using Exec = WEFT_TEST_EXECSPACE;
  const weft::test::ScratchDir dir("animated_pins_hard");
  dir.write("scene.json", pinned_band_json(dir, R"("target": "band.$F4.obj")"));
  const weft::Scene s = weft::io::read_json_scene(dir.file("scene.json"));
  ASSERT_EQ(s.kinematic_point.size(), 5u);
  weft::SimulationOn<Exec> sim(s);
  for (int f = 2; f <= 6; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    EXPECT_EQ(fs.max_pin_lag, 0) << "frame " << f;
    const std::vector<Vec3> x = sim.positions();
    const weft::io::TriMesh want = band_frame(f);
    for (int p = 20; p <= 24; ++p) EXPECT_EQ(weft::norm(x[size_t(p)] - want.positions[size_t(p)]), 0) << "point " << p << " frame " << f;
    EXPECT_GT(x[0].y, 0.59 - 1.0) << "the rest of the piece hangs from the band";
  }
}

TEST(WEFT_TEST_SUITE, soft_pins_to_an_animated_sequence_are_pulled_along) {
  using Exec = WEFT_TEST_EXECSPACE;
  const weft::test::ScratchDir dir("animated_pins_soft");
  dir.write("scene.json", pinned_band_json(dir, R"("target": "band.$F4.obj", "stiffness": 1e6)"));
  const weft::Scene s = weft::io::read_json_scene(dir.file("scene.json"));
  ASSERT_EQ(s.constraints.pin.size(), 5u);
  for (const auto& p : s.constraints.pin) EXPECT_GE(p.target, 0);
  const std::vector<Vec3> x = weft::test::run_frames<Exec>(s, 5);
  const weft::io::TriMesh want = band_frame(6);
  for (int p = 20; p <= 24; ++p) EXPECT_LT(weft::norm(x[size_t(p)] - want.positions[size_t(p)]), 0.01) << p;
}

TEST(WEFT_TEST_SUITE, attached_points_ride_a_moving_collider_and_stitches_sew_pieces) {
  using Exec = WEFT_TEST_EXECSPACE;
  const weft::test::ScratchDir dir("attach_and_stitch");
  // A box rising 5 cm a frame; a strip attached to its top by one edge, and a second strip sewn to the first
// (1 cm apart at the start: each point's contact thickness is 5 mm).
  for (int f = 1; f <= 6; ++f) {
    const weft::io::Mesh b = weft::io::box({-0.3, -0.1 + 0.05 * (f - 1), -0.3}, {0.3, 0.05 * (f - 1), 0.3});
    char name[32];
    std::snprintf(name, sizeof name, "lift.%04d.obj", f);
    weft::io::write_obj({b.x, b.tris}, dir.file(name));
  }
  dir.write("scene.json", R"({"settings": {"frames": [1, 6], "substeps": 4, "iterations": 20},
    "cloth": [
      {"generator": "grid", "res": [4, 4], "origin": [-0.2, 0.01, -0.2], "u": [0.4, 0, 0], "v": [0, 0, 0.4],
       "pins": [{"points": [0, 1, 2, 3, 4], "attach": "lift"}]},
      {"generator": "grid", "res": [4, 4], "origin": [-0.2, 0.01, 0.21], "u": [0.4, 0, 0], "v": [0, 0, 0.4]}],
    "stitches": [{"a": [0, 20], "b": [1, 0]}, {"a": [0, 24], "b": [1, 4]}],
    "colliders": [{"obj": "lift.$F4.obj"}]})");
  const weft::Scene s = weft::io::read_json_scene(dir.file("scene.json"));
  ASSERT_EQ(s.constraints.attach.size(), 5u);
  for (const auto& a : s.constraints.attach) EXPECT_NEAR(a.rest, 0.01, 1e-12);
  const std::vector<Vec3> x = weft::test::run_frames<Exec>(s, 5);
  // The box top is at 0.25 after 5 frames; the points rode up with it (trailing it by less than a frame's
  // 5 cm), and the unpinned second strip hangs from the stitches, as close as the two thicknesses allow.
  for (int p = 0; p <= 4; ++p) EXPECT_NEAR(x[size_t(p)].y, 0.25 + 0.01, 0.01) << "attached point " << p;
  EXPECT_LT(weft::norm(x[20] - x[25]), 0.0125);
  EXPECT_LT(weft::norm(x[24] - x[29]), 0.0125);
}

TEST(WEFT_TEST_SUITE, animated_pin_mistakes_name_the_file_and_the_pin) {
  const weft::test::ScratchDir dir("animated_pins_errors");
  const auto error = [&](const std::string& text) {
    dir.write("scene.json", text);
    try {
      weft::io::read_json_scene(dir.file("scene.json"));
    } catch (const weft::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  weft::io::write_obj(band_frame(1), dir.file("cloth.obj"));
  weft::io::TriMesh small = band_frame(1);
  small.positions.resize(20);
  small.triangles.resize(16);
  weft::io::write_obj(small, dir.file("small.obj"));
  const std::string head = R"({"cloth": [{"obj": "cloth.obj", "pins": [{"points": [20], )";
  std::string e = error(head + R"("target": "small.obj"}]}]})");
  EXPECT_NE(e.find("cloth[0].pins[0].target: " + dir.file("small.obj") + " has 20 points, this cloth piece 25"),
            std::string::npos) << e;
  e = error(head + R"("attach": "body"}]}]})");
  EXPECT_NE(e.find("pins[0].attach: no collider named 'body' (colliders: none)"), std::string::npos) << e;
  e = error(head + R"("target": "small.obj", "attach": "body"}]}]})");
  EXPECT_NE(e.find("at most one of 'target' and 'attach'"), std::string::npos) << e;
  e = error(R"({"cloth": [{"obj": "cloth.obj"}], "stitches": [{"a": [0, 3], "b": [0, 3]}]})");
  EXPECT_NE(e.find("stitches[0]: a stitch joins two different points"), std::string::npos) << e;
  e = error(R"({"cloth": [{"obj": "cloth.obj"}], "stitches": [{"a": [1, 3], "b": [0, 3]}]})");
  EXPECT_NE(e.find("stitches[0].a[0]: expected an integer in 0..0"), std::string::npos) << e;
}

}  // namespace
