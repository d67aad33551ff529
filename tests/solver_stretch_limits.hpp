// Long-range stretch limits (constraints/build_stretch_limits.hpp): distance rows that only pull, built along
// straight paths of the cloth's edges; they hold a hanging sheet that too few Gauss-Seidel iterations let
// stretch, never push a compressed pair apart, and give the same bits on every backend.
#include "constraints/build_stretch_limits.hpp"
#include "constraints/xpbd.hpp"
#include "core/error.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <limits>

namespace {

using weft::real;
using weft::Vec3;

using weft::test::inverse_masses;

TEST(WEFT_TEST_SUITE, stretch_limits_run_straight_along_the_cloth) {
  // An 8 x 8 grid: every point has a straight path of 4 edges in some direction, so every limit is one:
  // along the two grid directions 2 x 5 x 9 pairs; the grid's cells alternate their diagonals, so straight
  // diagonal paths run from the points with i + j even, 13 each way.
  const weft::io::Mesh g = weft::io::grid(8, 8, {0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  weft::Scene s = weft::test::empty_scene("test-grid");
  weft::add_cloth_piece(s, g.x, g.tris, weft::ClothMaterial{});
  s.settings.stretch_limits = 1;
  const std::vector<weft::Row> rows = weft::build_stretch_limits(s, inverse_masses(s));
  ASSERT_EQ(rows.size(), 116u);
  const real edge = 1.0 / 8, compliance = s.constraints.distance.front().m.compliance;
  for (const weft::Row& r : rows) {
    EXPECT_EQ(r.kind, weft::kRowDistance);
    EXPECT_LT(r.idx[0], r.idx[1]);
    const real straight = weft::norm(s.points.position[r.idx[1]] - s.points.position[r.idx[0]]);
    EXPECT_NEAR(r.rest, straight, 1e-12) << r.idx[0] << "-" << r.idx[1];
    const bool axis = std::abs(r.rest - 4 * edge) < 1e-12, diagonal = std::abs(r.rest - 4 * edge * std::sqrt(2.0)) < 1e-12;
    EXPECT_TRUE(axis || diagonal) << r.rest << " " << r.idx[0] << "-" << r.idx[1];
    EXPECT_EQ(r.m.compliance, 4 * compliance);
    EXPECT_EQ(r.m.compress_compliance, std::numeric_limits<real>::infinity());
  }
  s.settings.stretch_limits = 0;
  EXPECT_TRUE(weft::build_stretch_limits(s, inverse_masses(s)).empty());
}

TEST(WEFT_TEST_SUITE, a_stretch_limit_only_pulls) {
  weft::XpbdMaterial m;
  m.compress_compliance = std::numeric_limits<real>::infinity();
  const Vec3 g[2] = {{-1, 0, 0}, {1, 0, 0}}, dx[2] = {};
  const real w[2] = {1, 1}, h = 0.01;
  EXPECT_LT(weft::xpbd_delta_lambda<2>(0.1, g, w, dx, 0, m, h), 0);     // stretched: pulls
  EXPECT_EQ(weft::xpbd_delta_lambda<2>(-0.1, g, w, dx, 0, m, h), 0);    // compressed: leaves the points alone
  EXPECT_EQ(weft::xpbd_delta_lambda<2>(-0.1, g, w, dx, -0.01, m, h), 0.01);  // gives back no more than it pulled
  EXPECT_NEAR(weft::xpbd_delta_lambda<2>(-0.001, g, w, dx, -0.01, m, h), 0.0005, 1e-15);  // just back to its length
}

// One substep a frame with few plain Gauss-Seidel iterations (Chebyshev off): the sheet hanging from two
// corners stretches; stretch limits hold it.
weft::Scene slack_limited_sheet(int levels) {
  weft::Scene s = weft::test::slack_hanging_sheet();
  s.settings.stretch_limits = levels;
  return s;
}

TEST(WEFT_TEST_SUITE, stretch_limits_hold_an_unconverged_hanging_sheet) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::FrameStats loose, held;
  weft::test::run_frames<Exec>(slack_limited_sheet(0), 24, nullptr, &loose);
  weft::test::run_frames<Exec>(slack_limited_sheet(2), 24, nullptr, &held);
  EXPECT_GT(loose.p99_strain, 0.2);
  EXPECT_LT(held.p99_strain, 0.5 * loose.p99_strain);
  EXPECT_LT(held.max_strain, loose.max_strain);
  EXPECT_LT(held.max_edge_strain, loose.max_edge_strain);  // the limits are not edges: not counted
  EXPECT_EQ(held.non_finite, 0);
}

TEST(WEFT_TEST_SUITE, stretch_limited_sheet_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t h = 0;
  weft::test::run_frames<Exec>(slack_limited_sheet(2), 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "86eb22b74884535e");
}

TEST(WEFT_TEST_SUITE, stretch_limits_beyond_three_levels_are_an_input_error) {
  const weft::Scene s = slack_limited_sheet(4);
  const std::string e = weft::test::input_error([&] { weft::validate_scene(s); });
  EXPECT_NE(e.find("builtin:hanging-sheet"), std::string::npos) << e;
  EXPECT_NE(e.find("stretch_limits"), std::string::npos) << e;
}

}  // namespace
