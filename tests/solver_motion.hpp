// The frame loop: ballistic motion, rest, stretch under load, stiff and extreme settings.
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::real;
using weft::Vec3;

TEST(WEFT_TEST_SUITE, free_fall_follows_the_ballistic_path) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::ClothMaterial mat;
  mat.stretch_stiffness = 1e4;
  mat.bend_stiffness = 0;
  weft::Scene s = weft::test::sheet_scene(4, mat);
  const Vec3 v0{0.3, 2.0, -0.1};
  for (auto& v : s.points.velocity) v = v0;
  s.settings.substeps = 5;
  const int frames = 12;
  const auto x = weft::test::run_frames<Exec>(s, frames);
  // Symplectic Euler: after n substeps, x = x0 + n h v0 + h^2 g n (n + 1) / 2 (exact for this integrator),
  // which is the continuous path x0 + v0 t + g t^2 / 2 plus g h t / 2.
  const long n = long(frames) * s.settings.substeps;
  const real h = 1 / (s.settings.fps * s.settings.substeps), t = n * h;
  const Vec3 g = s.settings.gravity;
  for (size_t i = 0; i < x.size(); ++i) {
    const Vec3 p0 = s.points.position[i];
    const Vec3 discrete = p0 + (real(n) * h) * v0 + (h * h * real(n) * real(n + 1) / 2) * g;
    const Vec3 continuous = p0 + t * v0 + (t * t / 2) * g;
    EXPECT_LT(weft::norm(x[i] - discrete), 1e-9) << i;
    EXPECT_LT(weft::norm(x[i] - continuous), weft::norm(g) * h * t / 2 + 1e-9) << i;
  }
}

TEST(WEFT_TEST_SUITE, hanging_sheet_comes_to_rest) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::test::sheet_scene(6);
  s.points.stopped[0] = s.points.stopped[6] = 1;
  s.settings.velocity_damping = 4.0;
  weft::SimulationOn<Exec> sim(s);
  weft::FrameStats last;
  real peak = 0;
  for (int f = 0; f < 4 * 24; ++f) {
    last = sim.step_frame();
    peak = std::max(peak, last.kinetic_energy);
    if (f == 4 * 24 - 24) std::printf("kinetic energy: peak %.3e J, at 3 s %.3e J\n", peak, last.kinetic_energy);
  }
  std::printf("kinetic energy at 4 s %.3e J\n", last.kinetic_energy);
  EXPECT_GT(peak, 1e-3);
  EXPECT_LT(last.kinetic_energy, 1e-6 * peak);
  EXPECT_EQ(last.non_finite, 0);
  // Pinned corners stayed put, the rest hangs below them.
  const auto x = sim.positions();
  EXPECT_EQ(x[0], s.points.position[0]);
  EXPECT_LT(x[48].y, 0.5);
}

// A grid of equal masses hanging from its top row, with only vertical and horizontal distance constraints:
// every column carries the weight below it, so at rest the top edge of a column is stretched by
// (number of points below) m g / k.
// With Chebyshev acceleration as well: it blends the rows' multipliers with the points, so compliant rows
// settle where plain Gauss-Seidel does.
void expect_stretch_matches_stiffness(real chebyshev_rho) {
  using Exec = WEFT_TEST_EXECSPACE;
  const int nx = 4, ny = 6;
  const real L = 0.1, k = 200.0, m = 0.01;
  weft::Scene s = weft::test::empty_scene("test-chain-grid");
  auto id = [](int i, int j) { return j * nx + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      s.points.position.push_back({i * L, -j * L, 0});
      s.points.velocity.push_back({});
      s.points.mass.push_back(m);
      s.points.thickness.push_back(0.001);
      s.points.friction.push_back(1);
      s.points.dynamic_friction.push_back(1);
      s.points.layer.push_back(0);
      s.points.stopped.push_back(j == 0 ? 1 : 0);
      s.points.piece.push_back(0);
    }
  const auto mat = weft::xpbd_material(k, -1, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) s.constraints.distance.push_back({id(i, j), id(i + 1, j), L, mat});
      if (j + 1 < ny) s.constraints.distance.push_back({id(i, j), id(i, j + 1), L, mat});
    }
  s.settings.velocity_damping = 5;
  s.settings.iterations = 50;
  s.settings.chebyshev_rho = chebyshev_rho;
  weft::SimulationOn<Exec> sim(s);
  for (int f = 0; f < 10 * 24; ++f) sim.step_frame();
  const auto x = sim.positions();
  const real g = -s.settings.gravity.y;
  for (int j = 0; j + 1 < ny; ++j) {
    const real expect = L + (ny - 1 - j) * m * g / k;
    const real got = weft::norm(x[id(1, j + 1)] - x[id(1, j)]);
    EXPECT_NEAR(got, expect, 0.01 * (expect - L)) << "row " << j;
  }
}

TEST(WEFT_TEST_SUITE, stretch_under_gravity_matches_stiffness) { expect_stretch_matches_stiffness(0); }

TEST(WEFT_TEST_SUITE, stretch_under_gravity_matches_stiffness_with_chebyshev) { expect_stretch_matches_stiffness(0.95); }

void expect_stable(weft::Scene s, int frames) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::SimulationOn<Exec> sim(s);
  real max_ke = 0;
  for (int f = 0; f < frames; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0) << "frame " << fs.frame;
    max_ke = std::max(max_ke, fs.kinetic_energy);
  }
  // Nothing gains energy from nowhere: a sheet falling from rest can at most convert its potential energy.
  real mass = 0;
  for (real mm : s.points.mass) mass += mm;
  EXPECT_LT(max_ke, mass * 9.81 * 2.0);
}

TEST(WEFT_TEST_SUITE, stiff_and_extreme_settings_stay_finite) {
  {
    weft::ClothMaterial mat;
    mat.stretch_stiffness = 1e9;
    mat.bend_stiffness = 1e9;
    weft::Scene s = weft::test::sheet_scene(8, mat);
    s.points.stopped[0] = 1;
    expect_stable(s, 24);
  }
  {  // compliance 0 (infinitely stiff) with triangle stretch
    weft::ClothMaterial mat;
    mat.stretch = weft::StretchModel::Triarap;
    mat.stretch_stiffness = 1.0 / 0.0;
    weft::Scene s = weft::test::sheet_scene(8, mat);
    s.points.stopped[0] = 1;
    expect_stable(s, 24);
  }
  {  // mass ratio 1:1000 across the sheet
    weft::Scene s = weft::test::sheet_scene(8);
    for (size_t i = 0; i < s.points.size(); i += 2) s.points.mass[i] *= 1000;
    s.points.stopped[0] = 1;
    expect_stable(s, 24);
  }
  {  // 1 substep per frame at 24 fps
    weft::Scene s = weft::test::sheet_scene(8);
    s.settings.substeps = 1;
    s.points.stopped[0] = 1;
    expect_stable(s, 48);
  }
}

}  // namespace
