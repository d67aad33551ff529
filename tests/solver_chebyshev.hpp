// Chebyshev acceleration of a substep's iterations (docs/solver.md), on by default: it carries a hanging
// sheet's stretch further per iteration than plain Gauss-Seidel, keeps tethers, leaves the bits alone when a
// delay puts it past the last iteration, and gives the same bits on every backend.
#include "constraints/build_tethers.hpp"
#include "core/error.hpp"
#include "io/builtin_scenes.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::real;

// One substep a frame of 50 iterations: too few to hold the sheet hanging from two corners.
weft::Scene unconverged_sheet(real rho) {
  weft::Scene s = weft::io::make_builtin_scene("hanging-sheet", {16});
  s.settings.substeps = 1;
  s.settings.iterations = 50;
  s.settings.chebyshev_rho = rho;
  s.settings.coarse_levels = 0;  // the scene's levels would hold it
  return s;
}

TEST(WEFT_TEST_SUITE, chebyshev_is_on_by_default) {
  EXPECT_EQ(weft::SolverSettings{}.chebyshev_rho, 0.95);
  EXPECT_EQ(weft::SolverSettings{}.chebyshev_delay, 4);
}

TEST(WEFT_TEST_SUITE, chebyshev_holds_an_unconverged_sheet_closer_to_its_rest_lengths) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::FrameStats plain, fast;
  weft::test::run_frames<Exec>(unconverged_sheet(0), 24, nullptr, &plain);
  weft::test::run_frames<Exec>(unconverged_sheet(0.95), 24, nullptr, &fast);
  EXPECT_GT(plain.p99_strain, 0.1);
  EXPECT_LT(fast.p99_strain, 0.7 * plain.p99_strain) << plain.p99_strain;
  EXPECT_LT(fast.max_strain, plain.max_strain);
  EXPECT_EQ(fast.non_finite, 0);
}

TEST(WEFT_TEST_SUITE, chebyshev_leaves_no_point_past_its_tether) {
  // The blend pushes points past the sweep's result, tethers included: they are projected again after it.
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = unconverged_sheet(0.95);
  s.settings.tether_stretch = 1.0;
  const std::vector<weft::Vec3> x = weft::test::run_frames<Exec>(s, 12);
  const std::vector<weft::Tether> t = weft::build_tethers(s, weft::test::inverse_masses(s));
  ASSERT_FALSE(t.empty());
  for (const weft::Tether& k : t) EXPECT_LE(weft::norm(x[k.point] - x[k.anchor]), k.length * (1 + 1e-12)) << k.point;
}

TEST(WEFT_TEST_SUITE, chebyshev_after_the_last_iteration_changes_no_bit) {
  // A delay past the substep's iterations never blends: the same bits as the acceleration off.
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t off = 0, late = 0;
  weft::test::run_frames<Exec>(unconverged_sheet(0), 4, &off);
  weft::Scene s = unconverged_sheet(0.95);
  s.settings.chebyshev_delay = 50;
  weft::test::run_frames<Exec>(s, 4, &late);
  EXPECT_EQ(weft::hash_hex(late), weft::hash_hex(off));
}

TEST(WEFT_TEST_SUITE, chebyshev_sheet_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t h = 0;
  weft::test::run_frames<Exec>(unconverged_sheet(0.95), 6, &h);
  EXPECT_EQ(weft::hash_hex(h), "17eeca10c7a9a346");
}

TEST(WEFT_TEST_SUITE, chebyshev_leaves_fem_membrane_scenes_alone) {
  // Blended, the stable neo-Hookean pair of rows stretches a stiff sheet further (max strain 0.61 against
  // 0.23 on this one): a scene with FEM membrane rows runs without the acceleration, whatever the rate.
  using Exec = WEFT_TEST_EXECSPACE;
  weft::ClothMaterial mat;
  mat.stretch = weft::StretchModel::Fem;
  mat.young = 1e6;
  weft::Scene s = weft::test::sheet_scene(6, mat);
  s.points.stopped[0] = s.points.stopped[6] = 1;
  uint64_t on = 0, off = 0;
  weft::test::run_frames<Exec>(s, 6, &on);
  s.settings.chebyshev_rho = 0;
  weft::test::run_frames<Exec>(s, 6, &off);
  EXPECT_EQ(weft::hash_hex(on), weft::hash_hex(off));
}

TEST(WEFT_TEST_SUITE, chebyshev_rate_of_one_or_more_is_an_input_error) {
  const weft::Scene s = unconverged_sheet(1.0);
  const std::string e = weft::test::input_error([&] { weft::validate_scene(s); });
  EXPECT_NE(e.find("builtin:hanging-sheet"), std::string::npos) << e;
  EXPECT_NE(e.find("chebyshev_rho"), std::string::npos) << e;
}

}  // namespace
