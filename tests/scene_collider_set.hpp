// The collider set: every collider as one mesh over their concatenated vertices, in the scene's order.
#include "scene/collider_set.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::Vec3;

TEST(WEFT_TEST_SUITE, collider_set_concatenates_in_scene_order_and_holds_last_frames) {
  weft::Collider a, b;
  a.thickness = 0.01;
  a.friction = 0.5;
  a.triangles = {{0, 1, 2}};
  a.motion.frames = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};  // static: one frame
  b.thickness = 0.02;
  b.friction = 0.25;
  b.triangles = {{0, 1, 2}, {1, 3, 2}};
  for (int f = 0; f < 3; ++f)
    b.motion.frames.push_back({{0, 0, weft::real(f)}, {1, 0, weft::real(f)}, {0, 1, weft::real(f)}, {1, 1, weft::real(f)}});
  const std::vector<weft::Collider> colliders = {a, b};
  const weft::ColliderSet s = weft::make_collider_set(colliders);
  EXPECT_EQ(s.colliders(), 2);
  EXPECT_EQ(s.vertices(), 7);
  EXPECT_EQ(s.first_vertex, (std::vector<int>{0, 3, 7}));
  EXPECT_EQ(s.triangles, (std::vector<std::array<int, 3>>{{0, 1, 2}, {3, 4, 5}, {4, 6, 5}}));
  EXPECT_EQ(s.triangle_collider, (std::vector<int>{0, 1, 1}));
  EXPECT_EQ(s.vertex_thickness, (std::vector<weft::real>{0.01, 0.01, 0.01, 0.02, 0.02, 0.02, 0.02}));
  EXPECT_EQ(s.vertex_friction[2], 0.5);
  EXPECT_EQ(s.vertex_friction[3], 0.25);
  EXPECT_EQ(s.frames, 3);
  const std::vector<Vec3> x = weft::collider_positions(colliders, s, 2);
  ASSERT_EQ(x.size(), 7u);
  EXPECT_EQ(x[1].x, 1.0);  // the static collider holds its only frame
  EXPECT_EQ(x[6].z, 2.0);  // the animated one is at its frame 2
  EXPECT_EQ(weft::collider_positions(colliders, s, 5)[6].z, 2.0);  // past the end: the last frame
  const weft::ColliderSet none = weft::make_collider_set({});
  EXPECT_EQ(none.colliders(), 0);
  EXPECT_EQ(none.vertices(), 0);
  EXPECT_EQ(none.frames, 0);
}

}  // namespace
