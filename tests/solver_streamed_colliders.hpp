// Colliders streamed frame by frame (Simulation::set_collider_frame): a run handed, before each frame, the
// positions the scene's animation holds at its end gives the animated run's bits; a frame without a new
// call keeps the colliders still; wrong sizes are refused.
#include "core/device_copy.hpp"
#include "core/error.hpp"
#include "core/hash.hpp"
#include "io/builtin_scenes.hpp"
#include "io/procedural.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::Vec3;

// Every collider's vertices at animation frame k (a collider holds its last frame), concatenated.
std::vector<Vec3> colliders_at(const weft::Scene& s, size_t k) {
  std::vector<Vec3> x;
  for (const weft::Collider& c : s.colliders) {
    const auto& f = c.motion.frames[std::min(k, c.motion.frames.size() - 1)];
    x.insert(x.end(), f.begin(), f.end());
  }
  return x;
}

enum class Colliders { Animated, Streamed, StreamedFirstOnly };

// The hash of every frame's positions over `frames` frames.
template <class Exec>
uint64_t run_hash(const weft::Scene& s, int frames, Colliders how) {
  weft::SimulationOn<Exec> sim(s);
  uint64_t h = weft::hash_combine(0, sim.hash_positions());
  for (int f = 0; f < frames; ++f) {
    const size_t end = size_t(sim.frame() + 1 - s.settings.frame_start);
    if (how == Colliders::Streamed) sim.set_collider_frame(colliders_at(s, end));
    if (how == Colliders::StreamedFirstOnly) sim.set_collider_frame(0, s.colliders[0].motion.frames[end]);
    sim.step_frame();
    h = weft::hash_combine(h, sim.hash_positions());
  }
  return h;
}

// The built-in drape over a sphere that rises and sways, above a static ground.
weft::Scene moving_sphere(int frames) {
  weft::Scene s = weft::io::make_builtin_scene("drape-sphere", {8});
  weft::Collider& sphere = s.colliders[0];
  const std::vector<Vec3> rest = sphere.motion.frames[0];
  for (int f = 1; f <= frames; ++f) {
    std::vector<Vec3> x = rest;
    for (Vec3& p : x) p = p + Vec3{0.01 * f, 0.03 * f, 0};
    sphere.motion.frames.push_back(x);
  }
  const weft::io::Mesh g = weft::io::grid(1, 1, {-2, 0, -2}, {0, 0, 4}, {4, 0, 0});
  weft::Collider ground;
  ground.name = "ground";
  ground.triangles = g.tris;
  ground.motion.frames.push_back(g.x);
  s.colliders.push_back(ground);
  return s;
}

TEST(WEFT_TEST_SUITE, streamed_colliders_give_the_animated_bits) {
  using Exec = WEFT_TEST_EXECSPACE;
  const int frames = 6;
  const weft::Scene fast = weft::io::make_builtin_scene("fast-collider", {8});
  const uint64_t animated = run_hash<Exec>(fast, frames, Colliders::Animated);
  EXPECT_EQ(run_hash<Exec>(fast, frames, Colliders::Streamed), animated);
  EXPECT_EQ(run_hash<Exec>(fast, frames, Colliders::StreamedFirstOnly), animated);

  const weft::Scene sphere = moving_sphere(frames);
  const uint64_t draped = run_hash<Exec>(sphere, frames, Colliders::Animated);
  EXPECT_NE(draped, run_hash<Exec>(moving_sphere(0), frames, Colliders::Animated));  // the motion matters
  EXPECT_EQ(run_hash<Exec>(sphere, frames, Colliders::Streamed), draped);
  EXPECT_EQ(run_hash<Exec>(sphere, frames, Colliders::StreamedFirstOnly), draped);  // the ground holds anyway
}

TEST(WEFT_TEST_SUITE, streamed_colliders_hold_without_a_new_frame) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("fast-collider", {4});
  s.settings.substeps = 2;
  weft::Solver<Exec> solver(s);
  const std::vector<Vec3> first = colliders_at(s, 1);
  solver.set_collider_frame(first);
  solver.step_frame();
  const auto same = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].z != b[i].z) return false;
    return a.size() == b.size();
  };
  EXPECT_TRUE(same(weft::to_host(solver.state().collider_x), first));
  solver.step_frame();  // the animation would move the box on; streamed, it stays
  EXPECT_TRUE(same(weft::to_host(solver.state().collider_x_start), first));
  EXPECT_TRUE(same(weft::to_host(solver.state().collider_x), first));
}

TEST(WEFT_TEST_SUITE, streamed_collider_frames_of_the_wrong_size_are_refused) {
  using Exec = WEFT_TEST_EXECSPACE;
  const weft::Scene s = moving_sphere(2);
  weft::SimulationOn<Exec> sim(s);
  const size_t sphere = s.colliders[0].motion.frames[0].size(), all = sphere + 4;
  const auto message = [&](auto&& call) -> std::string {
    try {
      call();
    } catch (const weft::InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message([&] { sim.set_collider_frame(std::vector<Vec3>(all - 1)); }).find(std::to_string(all)),
            std::string::npos);
  EXPECT_NE(message([&] { sim.set_collider_frame(0, std::vector<Vec3>(3)); }).find(std::to_string(sphere)),
            std::string::npos);
  EXPECT_NE(message([&] { sim.set_collider_frame(2, std::vector<Vec3>(4)); }).find("2 colliders"), std::string::npos);
  sim.set_collider_frame(1, std::vector<Vec3>(4, Vec3{0, 0, 0}));  // the ground's four corners
}

}  // namespace
