#include "io/demo_scene.hpp"

#include "constraints/vellum_cloth.hpp"
#include "io/procedural.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>  // labs
#include <utility>

namespace weft::io {
namespace {

// The skirt: flared cones from the waist, each layer a little wider and shorter than the one inside so that
// every layer shows below the next. The hem is much wider than the waist: gravity gathers the excess into folds.
constexpr real kWaistY = 0.98, kWaistRadius = 0.165, kLayerGap = 0.012, kStitchStiffness = 1e10;
real hem_height(int layer) { return 0.33 + 0.06 * layer; }
real hem_radius(int layer) { return 0.42 + 0.025 * layer; }
// Rows of quads of one gore: quads at the hem about square, taller than wide near the waist.
int rows(int res, int layer) { return std::max(2, int(std::lround(1.5 * res * (kWaistY - hem_height(layer)) / 0.65))); }

// Pose at frame f: the body turns about the vertical axis; legs and arms swing in opposite phase. Motions
// ease in over the first half second so the cloth starts at rest.
struct Pose { real yaw, leg, arm; };
Pose pose(int f, real fps) {
  const real t = f / fps, ease = std::min(1.0, t / 0.5), e = ease * ease * (3 - 2 * ease);
  const real phase = std::sin(2 * pi * t / 2.0);  // a 2 s cycle
  return {e * 0.50 * phase, e * 0.70 * phase, -e * 0.30 * phase};
}

// Rotation about the vertical axis, and about the horizontal x axis through `pivot` (a forward swing).
Vec3 turn(Vec3 p, real a) { return {std::cos(a) * p.x + std::sin(a) * p.z, p.y, -std::sin(a) * p.x + std::cos(a) * p.z}; }
Vec3 swing(Vec3 p, Vec3 pivot, real a) {
  const Vec3 d = p - pivot;
  return pivot + Vec3{d.x, std::cos(a) * d.y - std::sin(a) * d.z, std::sin(a) * d.y + std::cos(a) * d.z};
}

// The body's parts; each swings about its joint, then the whole figure turns.
struct Part { Mesh mesh; Vec3 joint; int swing; };  // swing: 0 none, +-1 leg phase, +-2 arm phase
std::vector<Part> body_parts() {
  const int rg = 12, sg = 24;
  std::vector<Part> p;
  p.push_back({capsule({0, 0.95, 0}, {0, 1.38, 0}, 0.15, rg, sg), {}, 0});             // torso and pelvis
  p.push_back({capsule({0, 1.50, 0}, {0, 1.62, 0}, 0.09, rg, sg), {}, 0});             // head
  p.push_back({capsule({-0.30, 1.42, 0}, {0.30, 1.42, 0}, 0.06, rg, sg), {}, 0});      // shoulders
  for (int side : {-1, 1}) {
    const Vec3 hip{0.09 * side, 0.92, 0}, shoulder{0.30 * side, 1.42, 0};
    p.push_back({capsule(hip, {0.13 * side, 0.06, 0}, 0.06, rg, sg), hip, side});        // leg
    p.push_back({capsule(shoulder, {0.38 * side, 0.86, 0}, 0.05, rg, sg), shoulder, 2 * side});  // arm
  }
  return p;
}

}  // namespace

long demo_cloth_triangles(int res) {
  long n = 0;
  for (int l = 0; l < kDemoLayers; ++l) n += 2L * rows(res, l) * res * kDemoGores;
  return n;
}

int demo_res_for_triangles(long triangles) {
  int best = 2;
  for (int r = 2; r <= 4096; ++r)
    if (std::labs(demo_cloth_triangles(r) - triangles) < std::labs(demo_cloth_triangles(best) - triangles)) best = r;
  return best;
}

Scene demo_scene(int res) {
  Scene s;
  s.name = "builtin:demo";
  SolverSettings& st = s.settings;
  st.frame_end = 1 + 48;  // one 2 s cycle
  // Fewer substeps and iterations than the default (10 x 20): a laptop finishes the default size in minutes.
  st.substeps = 8;
  st.iterations = 10;
  st.collision_passes = 2;
  // Contact thickness well below the smallest edge (a gore's top edge at the waist), so that contacts never
  // reach a point's own neighbouring faces.
  const real thickness = std::min(0.003, 0.25 * 2 * pi * kWaistRadius / (kDemoGores * res));
  const XpbdMaterial stitch = xpbd_material(kStitchStiffness, -1, 0.001);
  for (int l = 0; l < kDemoLayers; ++l) {
    ClothMaterial mat;
    mat.layer = l;
    mat.thickness = thickness * (1 - 0.05 * l);  // inner layers a little thicker (lining, slip, skirt)
    mat.density = 0.12 - 0.02 * l;
    // Gore g spans the angles [g, g + 1] x 2 pi / gores, less 1.25 x `thickness` of arc at each side seam: seam
    // points of neighbouring gores start 2.5 x thickness apart (just outside where self contact pushes them) and
    // are stitched at that, straight across and diagonally to the next row (so the seam resists shear too).
    const int nu = res, nv = rows(res, l);
    const real r_top = kWaistRadius + kLayerGap * l, r_hem = hem_radius(l), y_hem = hem_height(l);
    std::vector<int> first(kDemoGores);
    for (int g = 0; g < kDemoGores; ++g) {
      Mesh m = grid(nu, nv, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // x: across the gore, y: up (0 hem, 1 waist)
      for (Vec3& p : m.x) {
        const real r = r_hem + (r_top - r_hem) * p.y, margin = 1.25 * mat.thickness / r;
        const real a = 2 * pi * g / kDemoGores + margin + p.x * (2 * pi / kDemoGores - 2 * margin);
        p = {r * std::sin(a), y_hem + (kWaistY - y_hem) * p.y, r * std::cos(a)};
      }
      first[size_t(g)] = add_cloth_piece(s, m.x, m.tris, mat);
      // The waistband: the top row is pinned to the figure, but for its two corners, which the seams hold. Pinned
      // seam corners would face each other across the seam at contact reach, and points that close can hardly
      // move relative to each other within their displacement bounds: the turning waist would trail behind.
      for (int i = 1; i < nu; ++i) {
        s.kinematic_point.push_back(first[size_t(g)] + nv * (nu + 1) + i);
        s.kinematic_target.push_back(int(s.kinematic_target.size()));
      }
    }
    for (int g = 0; g < kDemoGores; ++g)  // side seam: gore g's right edge to gore g + 1's left edge
      for (int j = 0; j < nv; ++j) {
        const int a = first[size_t(g)] + j * (nu + 1) + nu, b = first[size_t((g + 1) % kDemoGores)] + j * (nu + 1);
        for (const auto& [p, q] : {std::pair{a, b}, std::pair{a, b + nu + 1}, std::pair{a + nu + 1, b}})
          s.constraints.distance.push_back({p, q, norm(s.points.position[p] - s.points.position[q]), stitch});
      }
  }

  const std::vector<Part> parts = body_parts();
  Collider body;
  body.name = "body";
  body.thickness = 0.002;
  Mesh all;
  for (const Part& p : parts) append(all, p.mesh);
  body.triangles = all.tris;
  const int frames = st.frame_end - st.frame_start + 1;
  s.pin_targets.frames.resize(frames);
  for (int f = 0; f < frames; ++f) {
    const Pose q = pose(f, st.fps);
    std::vector<Vec3> x;
    for (const Part& p : parts) {
      const real a = p.swing == 0 ? 0 : (std::abs(p.swing) == 1 ? q.leg : q.arm) * (p.swing > 0 ? 1 : -1);
      for (const Vec3& v : p.mesh.x) x.push_back(turn(p.swing ? swing(v, p.joint, a) : v, q.yaw));
    }
    body.motion.frames.push_back(std::move(x));
    for (int k : s.kinematic_point) s.pin_targets.frames[f].push_back(turn(s.points.position[k], q.yaw));
  }
  s.colliders.push_back(std::move(body));
  s.needs_collisions = true;
  return s;
}

}  // namespace weft::io
