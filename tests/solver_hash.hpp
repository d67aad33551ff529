// The same scene gives the same bits on every backend and thread count: pinned hashes.
#include "io/builtin_scenes.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

TEST(WEFT_TEST_SUITE, hanging_sheet_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("hanging-sheet", {12});
  uint64_t h = 0;
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "41e3c70778decd82");
}

TEST(WEFT_TEST_SUITE, every_constraint_kind_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  uint64_t all = 0;
  for (auto model : {weft::StretchModel::Distance, weft::StretchModel::Triarap,
                     weft::StretchModel::TriarapNorm, weft::StretchModel::Fem}) {
    weft::ClothMaterial mat;
    mat.stretch = model;
    mat.stretch_stiffness = 1e5;
    weft::Scene s = weft::test::sheet_scene(6, mat);
    s.points.stopped[0] = 1;
    s.constraints.pin.push_back({6, {0.6, 1.0, -0.5}, -1, 0, weft::xpbd_material(100, -1, 0.01)});
    s.constraints.ptprim.push_back({20, {0, 1, 7, -1}, {0.2, 0.3, 0.5, 0}, 3, 0.05, weft::xpbd_material(1e3, -1, 0)});
    s.settings.smoothing_iterations = model == weft::StretchModel::Fem ? 3 : 0;
    uint64_t h = 0;
    weft::test::run_frames<Exec>(s, 6, &h);
    all = weft::hash_combine(all, h);
  }
  EXPECT_EQ(weft::hash_hex(all), "280f3472a72a6da7");
}

}  // namespace
