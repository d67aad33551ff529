// Tethers (constraints/tether.hpp): built along the cloth's edges to the nearest hard pin, they hold a
// hanging sheet that too few Gauss-Seidel iterations let stretch, and give the same bits on every backend.
#include "constraints/build_tethers.hpp"
#include "core/error.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::real;
using weft::Vec3;

using weft::test::inverse_masses;

TEST(WEFT_TEST_SUITE, tethers_follow_the_shortest_path_along_the_cloth) {
  // A 4 x 1 strip of quads (points 0..4 in the first row, 5..9 in the second; diagonals 0-6, 2-6, 2-8, 4-8),
  // pinned at both ends of the first row. Points 2 and 7 are as far from 0 as from 4: the lower index wins.
  const weft::io::Mesh g = weft::io::grid(4, 1, {0, 0, 0}, {4, 0, 0}, {0, 0, 1});
  weft::Scene s = weft::test::empty_scene("test-strip");
  weft::add_cloth_piece(s, g.x, g.tris, weft::ClothMaterial{});
  s.points.stopped[0] = s.points.stopped[4] = 1;
  s.settings.tether_stretch = 1.5;
  const std::vector<weft::Tether> t = weft::build_tethers(s, inverse_masses(s));
  ASSERT_EQ(t.size(), 8u);  // every point but the two pins
  const real diag = std::sqrt(2.0);
  const int want_anchor[8] = {0, 0, 4, 0, 0, 0, 4, 4};
  const real want_path[8] = {1, 2, 1, 1, diag, 1 + diag, diag, 1};  // points 1-3, then 5-9
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(t[k].point, int(k < 3 ? k + 1 : k + 2)) << k;
    EXPECT_EQ(t[k].anchor, want_anchor[k]) << k;
    EXPECT_NEAR(t[k].length, 1.5 * want_path[k], 1e-12) << k;
  }
  s.settings.tether_stretch = 0;
  EXPECT_TRUE(weft::build_tethers(s, inverse_masses(s)).empty());
}

// One substep a frame with few plain Gauss-Seidel iterations (Chebyshev off): the sheet hanging from two
// corners stretches; tethers hold it.
weft::Scene slack_sheet(real tethers) {
  weft::Scene s = weft::test::slack_hanging_sheet();
  s.settings.tether_stretch = tethers;
  return s;
}

TEST(WEFT_TEST_SUITE, tethers_hold_an_unconverged_hanging_sheet) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::FrameStats loose, held;
  weft::test::run_frames<Exec>(slack_sheet(0), 24, nullptr, &loose);
  const weft::Scene s = slack_sheet(1.0);
  const std::vector<Vec3> x = weft::test::run_frames<Exec>(s, 24, nullptr, &held);
  EXPECT_GT(loose.max_strain, 0.5);
  EXPECT_LT(held.max_strain, 0.5 * loose.max_strain);
  EXPECT_EQ(held.non_finite, 0);
  const std::vector<weft::Tether> t = weft::build_tethers(s, inverse_masses(s));
  ASSERT_FALSE(t.empty());
  for (const weft::Tether& k : t) EXPECT_LE(weft::norm(x[k.point] - x[k.anchor]), k.length * (1 + 1e-12)) << k.point;
}

TEST(WEFT_TEST_SUITE, tethered_sheet_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t h = 0;
  weft::test::run_frames<Exec>(slack_sheet(1.05), 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "fbd2b12a8d5ba8ae");
}

TEST(WEFT_TEST_SUITE, tether_stretch_below_one_is_an_input_error) {
  const weft::Scene s = slack_sheet(0.5);
  const std::string e = weft::test::input_error([&] { weft::validate_scene(s); });
  EXPECT_NE(e.find("builtin:hanging-sheet"), std::string::npos) << e;
  EXPECT_NE(e.find("tether stretch"), std::string::npos) << e;
}

}  // namespace
