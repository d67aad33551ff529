// The demo: builtin:demo (a figure of capsules in a skirt of three layers sewn from gores) has its layers,
// panels, stitches, a pinned waist, an animated body and a
// size that scales; a few frames stay finite with a pinned hash; contact sheets are valid PNGs. `weft demo`
// and `weft render` writing their files are cli_render.
#include "io/builtin_scenes.hpp"
#include "io/cache_file.hpp"
#include "io/contact_sheet.hpp"
#include "io/demo_scene.hpp"
#include "tests/io_checks_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <cmath>
#include <set>
#include <string>
#include <utility>

namespace {

using namespace weft;
using namespace weft::io;
using weft::test::png_size;
using weft::test::ScratchDir;

TEST(WEFT_TEST_SUITE, demo_scene_is_a_sewn_layered_skirt_on_a_moving_body) {
  const int res = 6;
  const Scene s = make_builtin_scene("demo", {res});
  EXPECT_NO_THROW(validate_scene(s));
  EXPECT_TRUE(thickness_warnings(s).empty());
  EXPECT_EQ(std::set<int>(s.points.layer.begin(), s.points.layer.end()), (std::set<int>{0, 1, 2}));
  std::set<real> thickness(s.points.thickness.begin(), s.points.thickness.end());
  EXPECT_EQ(thickness.size(), 3u);  // one per layer
  // Panels: six separate gores a layer, each its own piece.
  std::set<int> pieces(s.points.piece.begin(), s.points.piece.end());
  EXPECT_EQ(pieces.size(), size_t(kDemoLayers * kDemoGores));
  // Stitches: distance constraints between points of different pieces, starting at their rest length (2.5 x
  // thickness apart across, just outside self contact, and diagonals), along every side seam below the waistband.
  int stitches = 0;
  for (const DistanceConstraint& c : s.constraints.distance) {
    if (s.points.piece[c.a] == s.points.piece[c.b]) continue;
    ++stitches;
    EXPECT_EQ(s.points.layer[c.a], s.points.layer[c.b]);
    EXPECT_NEAR(norm(s.points.position[c.a] - s.points.position[c.b]), c.rest, 1e-12);
    EXPECT_GE(c.rest, 1.2 * (s.points.thickness[c.a] + s.points.thickness[c.b]));
    EXPECT_LT(c.rest, 0.1);
  }
  EXPECT_GE(stitches, kDemoLayers * kDemoGores * 3 * res);
  // Flared: the hem is much wider than the waist.
  real waist = 1e9, hem = 0;
  for (const Vec3& p : s.points.position) {
    const real r = std::hypot(p.x, p.z);
    if (p.y > 0.97) waist = std::min(waist, r);
    hem = std::max(hem, r);
  }
  EXPECT_GT(hem, 2.5 * waist);
  ASSERT_EQ(s.colliders.size(), 1u);
  const Animation& body = s.colliders[0].motion;
  ASSERT_EQ(int(body.frames.size()), s.settings.frame_end - s.settings.frame_start + 1);
  EXPECT_GT(body.frames.size(), 24u);
  real moved = 0;
  for (size_t k = 0; k < body.frames[0].size(); ++k) moved = std::max(moved, norm(body.frames[12][k] - body.frames[0][k]));
  EXPECT_GT(moved, 0.05);  // legs and arms swing, the figure turns
  // The waistband (the top row of every gore but its corners, which the seams hold) follows the body: its
  // targets move with it and start where the cloth is.
  ASSERT_EQ(s.kinematic_point.size(), size_t(kDemoLayers * kDemoGores * (res - 1)));
  ASSERT_EQ(s.pin_targets.frames.size(), body.frames.size());
  for (size_t k = 0; k < s.kinematic_point.size(); ++k) {
    EXPECT_EQ(norm(s.pin_targets.frames[0][s.kinematic_target[k]] - s.points.position[s.kinematic_point[k]]), 0);
    EXPECT_NEAR(s.points.position[s.kinematic_point[k]].y, 0.98, 1e-9);
  }
  EXPECT_GT(norm(s.pin_targets.frames[12][0] - s.pin_targets.frames[0][0]), 0.01);
}

TEST(WEFT_TEST_SUITE, demo_size_sets_the_triangle_count) {
  for (long want : {3000L, 50000L, 300000L}) {
    const int res = demo_res_for_triangles(want);
    EXPECT_NEAR(double(demo_cloth_triangles(res)), double(want), 0.1 * want) << want;
  }
  EXPECT_GT(demo_cloth_triangles(demo_res_for_triangles(300000)), 280000);
  const int res = demo_res_for_triangles(2000);
  EXPECT_EQ(long(make_builtin_scene("demo", {res}).triangles.size()), demo_cloth_triangles(res));
  EXPECT_LT(demo_cloth_triangles(8), demo_cloth_triangles(16));
}

TEST(WEFT_TEST_SUITE, demo_frames_stay_finite_with_a_pinned_hash) {
  Scene s = make_builtin_scene("demo", {4});
  uint64_t h = 0;
  FrameStats last;
  const std::vector<Vec3> x = test::run_frames<WEFT_TEST_EXECSPACE>(s, 3, &h, &last);
  EXPECT_EQ(last.non_finite, 0);
  for (const Vec3& p : x) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  // max_strain includes the seam stitches, whose rest lengths are a few millimetres: a seam opening by a
  // millimetre reads as a strain of about 0.3.
  EXPECT_LT(last.max_strain, 1);
  EXPECT_EQ(hash_hex(h), "e3705e9bde9b5ef7");
}

TEST(WEFT_TEST_SUITE, contact_sheet_is_a_png_of_the_grid) {
  const ScratchDir dir("sheet");
  const Scene s = make_builtin_scene("demo", {4});
  CacheHeader header{s.name, "serial", s.points.size(), s.triangles, s.settings};
  const std::string cache = dir.file("tiny.h5");
  {
    CacheWriter w(cache, header);
    for (int f = s.settings.frame_start; f < s.settings.frame_start + 5; ++f) {
      FrameStats fs;
      fs.frame = f;
      std::vector<Vec3> x = s.points.position;
      for (Vec3& p : x) p.y -= 0.01 * (f - s.settings.frame_start);
      w.append(fs, x, s.points.velocity);
    }
    w.close();
  }
  const CacheReader reader(cache);
  const SheetContent c = cache_sheet(reader, &s, 1, 5, 3);
  ASSERT_EQ(c.frames.size(), 3u);
  EXPECT_EQ(c.frames[0].frame, 1);
  EXPECT_EQ(c.frames[1].frame, 3);
  EXPECT_EQ(c.frames[2].frame, 5);
  EXPECT_FALSE(c.frames[0].collider.empty());
  const std::string png = dir.file("sheet.png");
  write_contact_sheet(png, c, 2, 100);
  EXPECT_EQ(png_size(png), (std::pair<int, int>{200, 36 + 2 * 100}));
  // Without the scene: colours by piece (three layers of six gores: 18 pieces), no colliders.
  const SheetContent plain = cache_sheet(reader, nullptr, 1, 5, 8);
  EXPECT_EQ(plain.frames.size(), 5u);
  const std::set<int> piece_colours(plain.triangle_colour.begin(), plain.triangle_colour.end());
  EXPECT_EQ(int(piece_colours.size()), kDemoLayers * kDemoGores);
  EXPECT_TRUE(plain.frames[0].collider.empty());
  // Frames the cache lacks, or a scene it was not computed from: an error, no file.
  EXPECT_THROW(cache_sheet(reader, nullptr, 1, 9, 3), std::runtime_error);
  const Scene other = make_builtin_scene("demo", {6});
  EXPECT_THROW(cache_sheet(reader, &other, 1, 5, 3), std::runtime_error);
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"sheet.png", "tiny.h5"}));
}

}  // namespace
