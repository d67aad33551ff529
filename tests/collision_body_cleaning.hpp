// The animation solvability check (collision/body_cleaning.hpp): a pinched arm is pulled out of the torso,
// a 4-layer sleeve gets its gap, a clean body stays bit for bit the same, every backend agrees.
#include "backends/simulation_on.hpp"
#include "collision/body_cleaning.hpp"
#include "constraints/vellum_cloth.hpp"
#include "core/hash.hpp"
#include "io/builtin_scenes.hpp"
#include "io/procedural.hpp"

namespace {

using weft::real;
using weft::Vec3;

constexpr real kTorsoRadius = 0.15, kArmRadius = 0.12, kLayerThickness = 0.002, kBodyThickness = 0.001;

weft::io::Mesh torso() { return weft::io::capsule({0, 0.6, 0}, {0, 1.2, 0}, kTorsoRadius, 12, 24); }
weft::io::Mesh arm(real x) { return weft::io::capsule({x, 0.65, 0}, {x, 1.15, 0}, kArmRadius, 12, 24); }

weft::Collider collider(const char* name, const std::vector<weft::io::Mesh>& frames) {
  weft::Collider c;
  c.name = name;
  c.triangles = frames[0].tris;
  for (const auto& m : frames) c.motion.frames.push_back(m.x);
  c.thickness = kBodyThickness;
  return c;
}

// A torso and an arm whose centre lines are `arm_x` apart at each frame; with `layers`, the arm wears that
// many sleeve tubes, dressed on the first frame.
weft::Scene body_scene(const std::vector<real>& arm_x, int layers) {
  weft::Scene s;
  s.name = "test-body";
  s.settings.frame_start = 1;
  s.settings.frame_end = int(arm_x.size());
  std::vector<weft::io::Mesh> t, a;
  for (real x : arm_x) {
    t.push_back(torso());
    a.push_back(arm(x));
  }
  s.colliders = {collider("torso", t), collider("arm", a)};
  for (int l = 0; l < layers; ++l) {
    const real r = kArmRadius + kBodyThickness + (2 * l + 1) * kLayerThickness + 0.0005;
    weft::io::Mesh sleeve = weft::io::tube(0.55, 1.25, 8, 24, r, r);  // past the arm's side vertices
    for (Vec3& p : sleeve.x) p.x += arm_x[0];
    weft::ClothMaterial mat;
    mat.layer = l;
    mat.thickness = kLayerThickness;
    weft::add_cloth_piece(s, sleeve.x, sleeve.tris, mat);
  }
  return s;
}

// Closest distance from p to triangle abc (Ericson, "Real-Time Collision Detection", 5.1.5).
real point_triangle_distance(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const real d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(p - a);
  const Vec3 bp = p - b;
  const real d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(p - b);
  const real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return norm(p - (a + (d1 / (d1 - d3)) * ab));
  const Vec3 cp = p - c;
  const real d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(p - c);
  const real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return norm(p - (a + (d2 / (d2 - d6)) * ac));
  const real va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return norm(p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)));
  const real den = 1 / (va + vb + vc);
  return norm(p - (a + (vb * den) * ab + (vc * den) * ac));
}

// The smallest distance from a vertex of one collider to a triangle of the other, both ways, at frame f.
real body_gap(const std::vector<weft::Collider>& c, int f) {
  real gap = 1e30;
  for (int from = 0; from < 2; ++from) {
    const auto& p = c[from].motion.frames[f];
    const auto& q = c[1 - from].motion.frames[f];
    for (const Vec3& x : p)
      for (const auto& t : c[1 - from].triangles) gap = std::min(gap, point_triangle_distance(x, q[t[0]], q[t[1]], q[t[2]]));
  }
  return gap;
}

uint64_t colliders_hash(const std::vector<weft::Collider>& cs) {
  uint64_t h = 0;
  for (const auto& c : cs)
    for (const auto& frame : c.motion.frames)
      for (const Vec3& p : frame)
        for (int k = 0; k < 3; ++k) h = weft::hash_combine(h, weft::test::bits(p[k]));
  return h;
}

TEST(WEFT_TEST_SUITE, procedural_colliders_are_closed_and_face_outward) {
  for (const weft::io::Mesh& m : {torso(), arm(0.3), weft::io::uv_sphere({0, 0.4, 0}, 0.3, 8, 16),
                                  weft::io::box({0, 0, 0}, {1, 2, 3})}) {
    EXPECT_TRUE(weft::is_closed_surface(m.tris));
    EXPECT_GT(weft::signed_volume6(m.x, m.tris), 0);
  }
  EXPECT_FALSE(weft::is_closed_surface(weft::io::grid(2, 2, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}).tris));
}

TEST(WEFT_TEST_SUITE, pinched_arm_leaves_the_torso) {
  using Exec = WEFT_TEST_EXECSPACE;
  const weft::Scene s = body_scene({kTorsoRadius + kArmRadius - 0.03}, 0);  // the arm 3 cm deep in the torso
  const weft::BodyCleaning c = weft::clean_body_on<Exec>(s, {});
  ASSERT_EQ(c.frames.size(), 1u);
  const weft::FrameCleaning& f = c.frames[0];
  std::printf("pinch: %ld intersecting pairs, %ld points inside; %d steps, %ld points moved (largest %.4f m)\n",
              f.intersections_before, f.interior_before, f.self_steps, f.points_moved, f.max_displacement);
  EXPECT_GT(f.intersections_before, 0);
  EXPECT_GT(f.interior_before, 0);
  EXPECT_TRUE(c.clean()) << weft::cleaning_summary(c);
  EXPECT_EQ(f.gap_violations_before, 0);  // no cloth: no gap to keep
  // Checked afresh, the cleaned body is left as it is.
  weft::Scene cleaned = s;
  cleaned.colliders = c.colliders;
  const weft::BodyCleaning again = weft::clean_body_on<Exec>(cleaned, {});
  EXPECT_EQ(again.frames[0].intersections_before, 0);
  EXPECT_EQ(again.frames[0].interior_before, 0);
  EXPECT_EQ(again.points_moved(), 0);
  EXPECT_GT(body_gap(c.colliders, 0), 0);
}

TEST(WEFT_TEST_SUITE, four_layer_sleeve_gets_its_gap) {
  using Exec = WEFT_TEST_EXECSPACE;
  // Frame 1: the arm, dressed in 4 sleeve layers, 10 cm from the torso; frame 2: 3 mm from it.
  const real near = kTorsoRadius + kArmRadius + 0.003;
  const weft::Scene s = body_scene({near + 0.1, near}, 4);
  const weft::BodyCleaning c = weft::clean_body_on<Exec>(s, {});
  EXPECT_NEAR(c.max_reserved, 4 * kLayerThickness, 1e-15);
  EXPECT_GT(c.reserved_points, 0);
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_EQ(c.frames[0].points_moved, 0);
  EXPECT_GT(c.frames[1].gap_violations_before, 0);
  EXPECT_TRUE(c.clean()) << weft::cleaning_summary(c);
  const real gap = body_gap(c.colliders, 1);
  std::printf("4-layer sleeve: gap %.4f m before, %.4f m after (4 fabric thicknesses: %.4f m); %d iterations\n",
              body_gap(s.colliders, 1), gap, 4 * 2 * kLayerThickness, c.frames[1].gap_iterations);
  EXPECT_GE(gap, 4 * 2 * kLayerThickness);  // every layer takes twice its thickness (its contact distance)
  // The first frame comes back bit for bit.
  for (int k = 0; k < 2; ++k)
    EXPECT_EQ(std::memcmp(c.colliders[k].motion.frames[0].data(), s.colliders[k].motion.frames[0].data(),
                          s.colliders[k].motion.frames[0].size() * sizeof(Vec3)),
              0);
  // The same bits on every backend.
  EXPECT_EQ(weft::hash_hex(colliders_hash(c.colliders)), "8aead4decf54b66b");
}

TEST(WEFT_TEST_SUITE, clean_body_is_left_bit_for_bit) {
  using Exec = WEFT_TEST_EXECSPACE;
  // The dressed arm 10 cm from the torso: layers on the body, room everywhere.
  const weft::Scene s = body_scene({kTorsoRadius + kArmRadius + 0.1}, 4);
  const weft::BodyCleaning c = weft::clean_body_on<Exec>(s, {});
  EXPECT_GT(c.reserved_points, 0);
  EXPECT_TRUE(c.clean()) << weft::cleaning_summary(c);
  EXPECT_EQ(c.points_moved(), 0);
  EXPECT_EQ(colliders_hash(c.colliders), colliders_hash(s.colliders));
  // And a swaying skirt's body, frame after frame.
  weft::Scene skirt = weft::io::make_builtin_scene("skirt", {4});
  skirt.colliders[0].motion.frames.resize(6);
  const weft::BodyCleaning k = weft::clean_body_on<Exec>(skirt, {});
  EXPECT_TRUE(k.clean()) << weft::cleaning_summary(k);
  EXPECT_EQ(colliders_hash(k.colliders), colliders_hash(skirt.colliders));
}

// Cloth points in contacts that violate their thickness by more than 10% (the impact zones), summed over
// the frames of a run.
template <class Exec>
long squeezed_points(const weft::Scene& s) {
  weft::SimulationOn<Exec> sim(s);
  long n = 0;
  while (sim.frame() < s.settings.frame_end) n += sim.step_frame().collision.impact_zone_points;
  return n;
}

TEST(WEFT_TEST_SUITE, cleaned_body_squeezes_the_sleeve_less) {
  using Exec = WEFT_TEST_EXECSPACE;
  // The dressed arm swings in against the torso, weightless, over 5 frames.
  const real near = kTorsoRadius + kArmRadius + 0.003;
  weft::Scene s = body_scene({near + 0.1, near + 0.06, near + 0.03, near + 0.01, near}, 4);
  s.settings.gravity = {0, 0, 0};
  s.settings.substeps = 4;
  s.settings.iterations = 10;
  s.settings.collision_passes = 1;
  // What the contacts make of the room cleaning gives: the fail-safe, which holds crossing points back in
  // their squeezed spots, would blur that.
  s.settings.collision.collision_failsafe = false;
  s.settings.collision.contact_model = weft::ContactModel::Ccd;  // impact zones count the squeeze in the paper's model
  const long before = squeezed_points<Exec>(s);
  s.colliders = weft::clean_body_on<Exec>(s, {}).colliders;
  const long after = squeezed_points<Exec>(s);
  std::printf("sleeve pressed against the torso: %ld squeezed contact points before cleaning, %ld after\n", before, after);
  EXPECT_GT(before, 0);
  EXPECT_LT(after, before);
}

}  // namespace
