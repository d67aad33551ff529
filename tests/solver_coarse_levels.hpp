// Coarse levels (constraints/build_coarse_levels.hpp): levels of the stretch rows, each a maximal set of the
// level below's points no two of them neighbours, with rows that only pull and followers that move with their
// parents; they hold a hanging sheet that too few Gauss-Seidel iterations let stretch, leave pins on their
// targets, and give the same bits on every backend.
#include "constraints/build_coarse_levels.hpp"
#include "core/error.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <algorithm>
#include <limits>
#include <set>

namespace {

using weft::real;
using weft::Vec3;

using weft::test::inverse_masses;

TEST(WEFT_TEST_SUITE, coarse_levels_coarsen_the_cloth_graph) {
  const weft::io::Mesh g = weft::io::grid(16, 16, {0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  weft::Scene s = weft::test::empty_scene("test-grid");
  weft::add_cloth_piece(s, g.x, g.tris, weft::ClothMaterial{});
  const int pinned = 144;  // the middle point does not move: it is on every level
  s.points.stopped[pinned] = 1;
  s.settings.coarse_levels = 3;
  const std::vector<weft::CoarseLevel> levels = weft::build_coarse_levels(s, inverse_masses(s));
  ASSERT_EQ(levels.size(), 3u);
  s.settings.coarse_levels = 16;  // no level is built past one that would have no rows
  const size_t most = weft::build_coarse_levels(s, inverse_masses(s)).size();
  EXPECT_GE(most, 3u);
  EXPECT_LT(most, 16u);
  const real compliance = s.constraints.distance.front().m.compliance;
  // Level 0: every point of the grid, linked by the distance rows.
  std::set<int> below;
  std::set<std::pair<int, int>> links;
  for (const weft::DistanceConstraint& d : s.constraints.distance) {
    below.insert(d.a);
    below.insert(d.b);
    links.insert({std::min(d.a, d.b), std::max(d.a, d.b)});
  }
  for (const weft::CoarseLevel& lv : levels) {
    ASSERT_TRUE(std::is_sorted(lv.follower.begin(), lv.follower.end()));
    ASSERT_EQ(lv.offset.size(), lv.follower.size() + 1);
    std::set<int> on = below;
    for (int f : lv.follower) on.erase(f);
    EXPECT_TRUE(on.count(pinned));
    EXPECT_LT(on.size(), below.size());
    // No two points of the level are linked below it, and every follower has a parent on it, linked to it.
    for (const auto& [a, b] : links) EXPECT_FALSE(on.count(a) && on.count(b)) << a << "-" << b;
    for (size_t k = 0; k < lv.follower.size(); ++k) {
      ASSERT_LT(lv.offset[k], lv.offset[k + 1]) << "follower " << lv.follower[k];
      real sum = 0;
      for (long j = lv.offset[k]; j < lv.offset[k + 1]; ++j) {
        const int p = lv.parent[size_t(j)];
        EXPECT_TRUE(on.count(p));
        EXPECT_TRUE(links.count({std::min(p, lv.follower[k]), std::max(p, lv.follower[k])}));
        EXPECT_GT(lv.weight[size_t(j)], 0);
        sum += lv.weight[size_t(j)];
      }
      EXPECT_NEAR(sum, 1, 1e-12);
    }
    // Rows only pull, between the level's points, no shorter than the straight line at rest, with the
    // compliance of two or three rows of the level below in series.
    ASSERT_FALSE(lv.rows.empty());
    links.clear();
    for (const weft::Row& r : lv.rows) {
      EXPECT_EQ(r.kind, weft::kRowDistance);
      EXPECT_TRUE(on.count(r.idx[0]) && on.count(r.idx[1]));
      EXPECT_LT(r.idx[0], r.idx[1]);
      EXPECT_GE(r.rest, weft::norm(s.points.position[r.idx[1]] - s.points.position[r.idx[0]]) * (1 - 1e-12));
      EXPECT_EQ(r.m.compress_compliance, std::numeric_limits<real>::infinity());
      EXPECT_GE(r.m.compliance, 2 * compliance * (1 - 1e-12));
      links.insert({r.idx[0], r.idx[1]});
    }
    below = on;
  }
  s.settings.coarse_levels = 0;
  EXPECT_TRUE(weft::build_coarse_levels(s, inverse_masses(s)).empty());
}

// One substep a frame with few plain Gauss-Seidel iterations (Chebyshev off): the sheet hanging from two
// corners stretches; coarse levels carry its weight across it.
weft::Scene slack_coarse_sheet(int levels) {
  weft::Scene s = weft::test::slack_hanging_sheet();
  s.settings.coarse_levels = levels;
  return s;
}

TEST(WEFT_TEST_SUITE, coarse_levels_hold_an_unconverged_hanging_sheet) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::FrameStats loose, held;
  weft::test::run_frames<Exec>(slack_coarse_sheet(0), 24, nullptr, &loose);
  weft::test::run_frames<Exec>(slack_coarse_sheet(4), 24, nullptr, &held);
  EXPECT_GT(loose.p99_strain, 0.2);
  EXPECT_LT(held.p99_strain, 0.25 * loose.p99_strain);
  EXPECT_LT(held.max_strain, 0.5 * loose.max_strain);
  EXPECT_EQ(held.max_pin_lag, 0);  // the pinned corners are on every level and never move
  EXPECT_EQ(held.non_finite, 0);
}

// With self collision too (the scene's own schedule, 10 x 20, proximity contacts): the levels' moves are
// cut back by the contacts' bounds like any other, and the sheet, hanging from its two still corners,
// still ends less stretched (at 16 x 16, `weft run` frame 20: p99 0.0075 without levels, 0.0022 with four).
TEST(WEFT_TEST_SUITE, coarse_levels_hold_a_hanging_sheet_with_self_collision) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("hanging-sheet", {16});
  s.settings.collision.self_collision = true;
  s.settings.coarse_levels = 0;  // the scene's own are six
  weft::FrameStats loose, held;
  weft::test::run_frames<Exec>(s, 20, nullptr, &loose);
  s.settings.coarse_levels = 4;
  weft::test::run_frames<Exec>(s, 20, nullptr, &held);
  EXPECT_LT(held.p99_strain, 0.5 * loose.p99_strain);
  EXPECT_EQ(held.max_pin_lag, 0);
  EXPECT_EQ(loose.max_pin_lag, 0);
  EXPECT_GT(held.collision.queries, 0);
}

TEST(WEFT_TEST_SUITE, coarse_sheet_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t h = 0;
  weft::test::run_frames<Exec>(slack_coarse_sheet(4), 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "2eaeb998987d904c");
}

TEST(WEFT_TEST_SUITE, coarse_levels_out_of_range_are_an_input_error) {
  const weft::Scene s = slack_coarse_sheet(17);
  const std::string e = weft::test::input_error([&] { weft::validate_scene(s); });
  EXPECT_NE(e.find("builtin:hanging-sheet"), std::string::npos) << e;
  EXPECT_NE(e.find("coarse levels"), std::string::npos) << e;
}

}  // namespace
