// The Gauss-Seidel sweep by patches (constraints/sweep_patches.hpp): what the patches promise, and the same
// bits on every backend and thread count.
#include "constraints/build_rows.hpp"
#include "constraints/sweep_patches.hpp"
#include "io/builtin_scenes.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <set>

namespace {

std::vector<char> movable_points(const weft::Scene& s) {
  std::vector<char> m(s.points.size());
  for (size_t i = 0; i < m.size(); ++i) m[i] = s.points.mass[i] > 0 && !(s.points.stopped[i] & 1);
  for (int k : s.kinematic_point) m[size_t(k)] = 0;
  return m;
}

TEST(WEFT_TEST_SUITE, patches_of_one_colour_and_rows_of_one_cell_share_no_moving_point) {
  const weft::Scene s = weft::io::make_builtin_scene("layer-stack", {10});
  const std::vector<weft::Row> rows = weft::build_rows(s, std::vector<int>(s.colliders.size(), 0));
  const std::vector<char> movable = movable_points(s);
  const weft::SweepPatches sp = weft::build_sweep_patches(rows, s.points.position, movable, 16);
  ASSERT_GT(sp.patches(), 4);
  EXPECT_EQ(sp.patch_points, 16);
  EXPECT_LE(sp.patch_colours(), 16);
  // Which patch (in sweep order) owns each cell.
  std::vector<long> cell_patch(size_t(sp.cells()));
  for (long p = 0; p < sp.patches(); ++p)
    for (long c = sp.cell_begin[size_t(p)]; c < sp.cell_begin[size_t(p) + 1]; ++c) cell_patch[size_t(c)] = p;
  std::vector<std::set<int>> cell_points(size_t(sp.cells()));
  std::vector<std::set<int>> patch_points(size_t(sp.patches()));
  for (size_t r = 0; r < rows.size(); ++r) {
    const weft::Row& row = rows[r];
    bool moves = false;
    for (int k = 0; k < row.n; ++k) moves = moves || movable[size_t(row.idx[k])];
    ASSERT_EQ(sp.row_cell[r] >= 0, moves) << "row " << r;
    if (!moves) continue;
    const long c = sp.row_cell[r], p = cell_patch[size_t(c)];
    for (int k = 0; k < row.n; ++k) {
      const int i = row.idx[k];
      // The row's local index names its point in the patch's table.
      ASSERT_EQ(sp.table[size_t(sp.table_begin[size_t(p)] + sp.local[r][size_t(k)])], i) << "row " << r;
      if (!movable[size_t(i)]) continue;
      EXPECT_TRUE(cell_points[size_t(c)].insert(i).second) << "point " << i << " twice in cell " << c;
      patch_points[size_t(p)].insert(i);
    }
  }
  for (int colour = 0; colour < sp.patch_colours(); ++colour) {
    std::set<int> seen;
    for (long p = sp.colour_begin[size_t(colour)]; p < sp.colour_begin[size_t(colour) + 1]; ++p)
      for (int i : patch_points[size_t(p)]) EXPECT_TRUE(seen.insert(i).second) << "point " << i << ", patch colour " << colour;
  }
}

TEST(WEFT_TEST_SUITE, sweep_by_patches_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("hanging-sheet", {12});
  s.settings.sweep_patch_points = 16;
  uint64_t h = 0;
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "49df477c777b949a");
}

TEST(WEFT_TEST_SUITE, sweep_by_patches_every_constraint_kind_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t all = 0;
  for (auto model : {weft::StretchModel::Distance, weft::StretchModel::Triarap, weft::StretchModel::Fem}) {
    weft::ClothMaterial mat;
    mat.stretch = model;
    mat.stretch_stiffness = 1e5;
    weft::Scene s = weft::test::sheet_scene(6, mat);
    s.points.stopped[0] = 1;
    s.constraints.pin.push_back({6, {0.6, 1.0, -0.5}, -1, 0, weft::xpbd_material(100, -1, 0.01)});
    s.constraints.ptprim.push_back({20, {0, 1, 7, -1}, {0.2, 0.3, 0.5, 0}, 3, 0.05, weft::xpbd_material(1e3, -1, 0)});
    s.settings.smoothing_iterations = model == weft::StretchModel::Fem ? 3 : 0;
    s.settings.sweep_patch_points = 8;
    uint64_t h = 0;
    weft::test::run_frames<Exec>(s, 6, &h);
    all = weft::hash_combine(all, h);
  }
  EXPECT_EQ(weft::hash_hex(all), "0274f8079143c7a9");
}

// Gauss-Seidel in another order: the hanging sheet stretches about as much as when swept colour by colour.
TEST(WEFT_TEST_SUITE, sweep_by_patches_holds_the_sheet_like_the_colour_sweep) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("hanging-sheet", {16});
  weft::FrameStats colours, patches;
  weft::test::run_frames<Exec>(s, 12, nullptr, &colours);
  s.settings.sweep_patch_points = 32;
  weft::test::run_frames<Exec>(s, 12, nullptr, &patches);
  EXPECT_EQ(patches.non_finite, 0);
  EXPECT_LT(patches.p99_strain, 1.5 * colours.p99_strain + 0.01);
  EXPECT_LT(patches.max_strain, 1.5 * colours.max_strain + 0.01);
}

}  // namespace
