#include "io/builtin_scenes.hpp"

#include "constraints/vellum_cloth.hpp"
#include "core/error.hpp"
#include "io/demo_scene.hpp"
#include "io/procedural.hpp"

#include <algorithm>
#include <cmath>

namespace weft::io {
namespace {

Collider static_collider(const std::string& name, const Mesh& m, real thickness) {
  Collider c;
  c.name = name;
  c.triangles = m.tris;
  c.motion.frames.push_back(m.x);
  c.thickness = thickness;
  return c;
}

// A 1 m sheet, horizontal at 1 m height, hard-pinned at the two corners of one edge.
Scene hanging_sheet(int res) {
  Scene s;
  s.name = "builtin:hanging-sheet";
  const Mesh g = grid(res, res, {-0.5, 1.0, -0.5}, {1, 0, 0}, {0, 0, 1});
  // Used only when self collision is switched on (weft run --self-collision on): as for the skirt, the
  // thickness stays below 0.3 of the triangle height so that a point never reaches its own next faces.
  ClothMaterial mat;
  mat.thickness = std::min(0.005, 0.3 / (res * std::sqrt(2.0)));  // triangle height 1 / (res sqrt 2)
  add_cloth_piece(s, g.x, g.tris, mat);
  s.points.stopped[0] = 1;
  s.points.stopped[res] = 1;
  s.settings.frame_end = 72;
  // Cloth hanging free from two corners: its weight crosses the whole sheet, which the sweeps alone carry
  // about one edge each (docs/solver.md, "Coarse levels"; six levels hold the 100K sheet with self collision
  // at p99 strain 0.03 where it hung at 0.97).
  s.settings.coarse_levels = 6;
  s.settings.collision.self_collision = false;  // a single hanging sheet: the solver's reference scene
  return s;
}

// A square cloth held at two opposite edges that turn in opposite directions, two full turns each, while
// moving closer (paper Fig. 9).
Scene twist(int res) {
  Scene s;
  s.name = "builtin:twist";
  const real L = 1.0;
  const Mesh g = grid(res, res, {-L / 2, 1.0, -L / 2}, {L, 0, 0}, {0, 0, L});
  ClothMaterial mat;
  mat.thickness = 0.004;
  add_cloth_piece(s, g.x, g.tris, mat);
  s.settings.frame_end = 1 + 120;
  const int frames = s.settings.frame_end - s.settings.frame_start + 1;
  std::vector<int> held;
  for (int j = 0; j <= res; ++j) { held.push_back(j * (res + 1)); held.push_back(j * (res + 1) + res); }
  s.pin_targets.frames.resize(frames);
  for (int f = 0; f < frames; ++f) {
    const real t = std::min(1.0, real(f) / 96);  // two turns over 4 s, then hold
    const real angle = 2 * (2 * pi) * t;
    const real inward = 0.2 * std::min(1.0, 2 * t);  // each edge moves 0.2 m in
    for (int k : held) {
      const Vec3 p = g.x[k];
      const real side = p.x < 0 ? 1.0 : -1.0;
      const real a = side * angle, yc = 1.0;
      const real dy = p.y - yc, dz = p.z;
      s.pin_targets.frames[f].push_back({p.x + side * inward, yc + dy * std::cos(a) - dz * std::sin(a),
                                         dy * std::sin(a) + dz * std::cos(a)});
    }
  }
  for (size_t k = 0; k < held.size(); ++k) { s.kinematic_point.push_back(held[k]); s.kinematic_target.push_back(int(k)); }
  s.needs_collisions = true;
  return s;
}

// A sheet dropped onto a static sphere.
Scene drape_sphere(int res) {
  Scene s;
  s.name = "builtin:drape-sphere";
  const Mesh g = grid(res, res, {-0.6, 0.75, -0.6}, {1.2, 0, 0}, {0, 0, 1.2});
  add_cloth_piece(s, g.x, g.tris, ClothMaterial{});
  s.colliders.push_back(static_collider("sphere", uv_sphere({0, 0.4, 0}, 0.3, 32, 64), 0.002));
  s.settings.frame_end = 72;
  s.settings.coarse_levels = 4;  // the flaps' weight carried to the top within a substep: half the strain
  s.needs_collisions = true;
  return s;
}

// Six layers dropped onto a ground plane and pressed by a heavy top layer.
Scene layer_stack(int res) {
  Scene s;
  s.name = "builtin:layer-stack";
  for (int l = 0; l < 6; ++l) {
    const Mesh g = grid(res, res, {-0.4, 0.05 + 0.03 * l, -0.4}, {0.8, 0, 0}, {0, 0, 0.8});
    ClothMaterial mat;
    mat.layer = l;
    mat.thickness = 0.004;
    if (l == 5) mat.density = 2.0;  // the press
    add_cloth_piece(s, g.x, g.tris, mat);
  }
  s.colliders.push_back(static_collider("ground", grid(1, 1, {-2, 0, -2}, {0, 0, 4}, {4, 0, 0}), 0.0));
  s.settings.frame_end = 96;
  s.needs_collisions = true;
  return s;
}

// Fifty square sheets dropped onto a sphere and the ground: the paper's many-layer scaling case (at --res 69,
// 476,100 triangles). Each layer is turned 7 degrees from the one below, so no two layers' points line up;
// layers start 2.8 thicknesses apart, outside contact reach, and the thickness stays below 0.3 of a
// triangle's height, as in the skirt.
Scene layer_drop(int res) {
  Scene s;
  s.name = "builtin:layer-drop";
  const real side = 1.0, height = side / res / std::sqrt(2.0);
  const real thickness = std::min(0.003, 0.3 * height);
  for (int l = 0; l < 50; ++l) {
    Mesh g = grid(res, res, {-side / 2, 0.75 + 2.8 * thickness * l, -side / 2}, {side, 0, 0}, {0, 0, side});
    const real a = l * 7 * pi / 180, c = std::cos(a), sn = std::sin(a);
    for (Vec3& p : g.x) p = {c * p.x - sn * p.z, p.y, sn * p.x + c * p.z};
    ClothMaterial mat;
    mat.layer = l;
    mat.thickness = thickness;
    add_cloth_piece(s, g.x, g.tris, mat);
  }
  s.colliders.push_back(static_collider("sphere", uv_sphere({0, 0.4, 0}, 0.3, 32, 64), 0.002));
  s.colliders.push_back(static_collider("ground", grid(1, 1, {-2, 0, -2}, {0, 0, 4}, {4, 0, 0}), 0.0));
  s.settings.frame_end = 72;
  s.needs_collisions = true;
  return s;
}

// A box crossing a hanging sheet at 10 m/s.
Scene fast_collider(int res) {
  Scene s;
  s.name = "builtin:fast-collider";
  const Mesh g = grid(res, res, {-0.5, 0.2, 0}, {1, 0, 0}, {0, 1, 0});
  add_cloth_piece(s, g.x, g.tris, ClothMaterial{});
  for (int i = 0; i <= res; ++i) s.points.stopped[res * (res + 1) + i] = 1;  // top edge
  Collider c = static_collider("box", box({-0.1, 0.5, -0.1}, {0.1, 0.7, 0.1}), 0.002);
  const Mesh b = box({-0.1, 0.5, -0.1}, {0.1, 0.7, 0.1});
  s.settings.frame_end = 48;
  c.motion.frames.clear();
  for (int f = 0; f <= s.settings.frame_end - s.settings.frame_start; ++f) {
    const real z = -1.0 + 10.0 * real(f) / s.settings.fps;  // 10 m/s along +z, crossing z = 0 at frame 3.4
    std::vector<Vec3> x = b.x;
    for (Vec3& p : x) p.z += z;
    c.motion.frames.push_back(x);
  }
  s.colliders.push_back(c);
  s.needs_collisions = true;
  return s;
}

// A five-layer skirt on a body whose hips sway.
Scene skirt(int res) {
  Scene s;
  s.name = "builtin:skirt";
  const int segments = 4 * res, rings = res;
  // Self contacts reach 2.5 thicknesses (1.25 x the two sides'), so the thickness stays below 0.3 of the
  // smallest triangle height (at the waist) and a point never reaches its own layer's next faces; adjacent
  // layers start 2.8 thicknesses apart (radially), outside contact reach.
  const real ring = 0.45 / rings, waist = 2 * pi * 0.16 / segments;
  const real thickness = std::min(0.003, 0.3 * ring * waist / std::sqrt(ring * ring + waist * waist));
  for (int l = 0; l < 5; ++l) {
    const real gap = 2.8 * thickness * l;
    const Mesh t = tube(0.55, 1.0, rings, segments, 0.30 + gap, 0.16 + gap);
    ClothMaterial mat;
    mat.layer = l;
    mat.thickness = thickness;
    const int first = add_cloth_piece(s, t.x, t.tris, mat);
    for (int k = 0; k < segments; ++k) {  // waistband follows the body
      s.kinematic_point.push_back(first + rings * segments + k);
      s.kinematic_target.push_back(int(s.kinematic_target.size()));
    }
  }
  Mesh body = capsule({0, 0.5, 0}, {0, 1.1, 0}, 0.15, 16, 32);
  s.settings.frame_end = 96;
  const int frames = s.settings.frame_end - s.settings.frame_start + 1;
  Collider c = static_collider("body", body, 0.002);
  c.motion.frames.clear();
  s.pin_targets.frames.resize(frames);
  for (int f = 0; f < frames; ++f) {
    const real sway = 0.08 * std::sin(2 * pi * f / 48.0);
    std::vector<Vec3> x = body.x;
    for (Vec3& p : x) p.x += sway * (1.1 - p.y) / 0.6;
    c.motion.frames.push_back(x);
    for (size_t k = 0; k < s.kinematic_point.size(); ++k) {
      Vec3 p = s.points.position[s.kinematic_point[k]];
      p.x += sway * (1.1 - p.y) / 0.6;
      s.pin_targets.frames[f].push_back(p);
    }
  }
  s.colliders.push_back(c);
  s.needs_collisions = true;
  return s;
}

struct Entry { const char* name; Scene (*make)(int); int default_res; };
const Entry kScenes[] = {
    {"hanging-sheet", hanging_sheet, 32}, {"drape-sphere", drape_sphere, 48}, {"layer-stack", layer_stack, 24},
    {"twist", twist, 48},                 {"fast-collider", fast_collider, 32}, {"skirt", skirt, 24},
    {"layer-drop", layer_drop, 12},
    {"demo", demo_scene, 34},  // io/demo_scene.cpp; 56,712 cloth triangles (`weft demo` runs res 20)
};

}  // namespace

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> r;
  for (const Entry& e : kScenes) r.push_back(e.name);
  return r;
}

Scene make_builtin_scene(const std::string& name, const BuiltinOptions& opt) {
  for (const Entry& e : kScenes)
    if (name == e.name) {
      if (opt.res < 0 || opt.res > 4096) throw InputError("builtin:" + name + ": --res must be in 1..4096");
      return e.make(opt.res > 0 ? opt.res : e.default_res);
    }
  std::string known;
  for (const Entry& e : kScenes) known += std::string(known.empty() ? "" : ", ") + e.name;
  throw InputError("unknown built-in scene '" + name + "' (known: " + known + ")");
}

}  // namespace weft::io
