#include "io/demo_scene.hpp"

#include "constraints/vellum_cloth.hpp"
#include "io/procedural.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>  // labs

namespace weft::io {
namespace {

// The dress: cones hung from a ring around the chest, each layer wider and shorter than the one inside, so
// that every layer shows below the next.
constexpr real kTop = 1.30, kTopRadius = 0.17, kHemRadius = 0.30, kGap = 0.010;
real hem_height(int layer) { return 0.50 + 0.07 * layer; }
// Quads a little taller than wide: fewer rings make the hanging cloth's constraint chains shorter.
int rings(int res, int layer) { return std::max(2, int(std::lround(1.6 * res * (kTop - hem_height(layer)) / 0.8))); }
constexpr real kWaist = 1.0;  // a second sewn ring, so that less cloth hangs from one ring

// Pose at frame f: the body turns about the vertical axis; legs and arms swing in opposite phase. Motions
// ease in over the first half second so the cloth starts at rest.
struct Pose { real yaw, leg, arm; };
Pose pose(int f, real fps) {
  const real t = f / fps, ease = std::min(1.0, t / 0.5), e = ease * ease * (3 - 2 * ease);
  const real phase = std::sin(2 * pi * t / 2.0);  // a 2 s cycle
  return {e * 0.45 * phase, e * 0.35 * phase, -e * 0.30 * phase};
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
    const Vec3 hip{0.08 * side, 0.92, 0}, shoulder{0.30 * side, 1.42, 0};
    p.push_back({capsule(hip, {0.09 * side, 0.06, 0}, 0.06, rg, sg), hip, side});        // leg
    p.push_back({capsule(shoulder, {0.38 * side, 0.86, 0}, 0.05, rg, sg), shoulder, 2 * side});  // arm
  }
  return p;
}

}  // namespace

long demo_cloth_triangles(int res) {
  long n = 0;
  for (int l = 0; l < kDemoLayers; ++l) n += 2L * rings(res, l) * (4 * res);
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
  const int segments = 4 * res;
  // Contact thickness well below the smallest edge (the top ring's segments): thicker cloth starts in
  // contact with itself where the cone's top gathers, and the pinned ring makes those contacts stiff.
  const real thickness = std::min(0.003, 0.18 * 2 * pi * kTopRadius / segments);
  for (int l = 0; l < kDemoLayers; ++l) {
    const real gap = kGap * l;
    const Mesh t = tube(hem_height(l), kTop, rings(res, l), segments, kHemRadius + 2 * gap, kTopRadius + gap);
    ClothMaterial mat;
    mat.layer = l;
    mat.thickness = thickness * (1 - 0.05 * l);  // inner layers a little thicker (lining, slip, dress, veil)
    mat.density = 0.12 - 0.02 * l;
    const int first = add_cloth_piece(s, t.x, t.tris, mat);
    const int n = rings(res, l), waist = int(std::lround(n * (kWaist - hem_height(l)) / (kTop - hem_height(l))));
    for (int ring : {n, waist})  // the top ring is sewn to the chest, and one ring to the waist
      for (int k = 0; k < segments; ++k) {
        s.kinematic_point.push_back(first + ring * segments + k);
        s.kinematic_target.push_back(int(s.kinematic_target.size()));
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
