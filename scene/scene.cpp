#include "scene/scene.hpp"

#include "core/error.hpp"
#include "core/topology.hpp"
#include "scene/mesh_checks.hpp"

#include <cstdio>
#include <sstream>

namespace weft {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}

std::string vec_str(Vec3 v) {
  std::ostringstream o;
  o << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return o.str();
}

void check_index(const std::string& name, long i, size_t n, const std::string& element) {
  if (i < 0 || size_t(i) >= n)
    fail(name, element + " refers to point " + std::to_string(i) + ", out of range [0, " + std::to_string(n) + ")");
}

void check_position(const std::string& name, size_t i, Vec3 x) {
  if (!isfinite_(x)) fail(name, "point " + std::to_string(i) + " has a non-finite position " + vec_str(x));
}

void check_triangles(const std::string& name, const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris) {
  for (size_t t = 0; t < tris.size(); ++t) {
    const auto& tri = tris[t];
    for (int k = 0; k < 3; ++k) check_index(name, tri[k], x.size(), "triangle " + std::to_string(t));
    if (triangle_area(x[tri[0]], x[tri[1]], x[tri[2]]) <= 0)
      fail(name, "triangle " + std::to_string(t) + " (points " + std::to_string(tri[0]) + ", " + std::to_string(tri[1]) +
                     ", " + std::to_string(tri[2]) + ") has zero area");
  }
}

[[noreturn]] void fail(const Scene& s, const std::string& what) { fail(s.name, what); }

void check_index(const Scene& s, long i, size_t n, const std::string& element) { check_index(s.name, i, n, element); }

}  // namespace

void validate_mesh(const std::string& name, const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris) {
  for (size_t i = 0; i < x.size(); ++i) check_position(name, i, x[i]);
  check_triangles(name, x, tris);
}

void validate_scene(const Scene& s) {
  const ClothPoints& p = s.points;
  const size_t n = p.size();
  auto same = [&](size_t k, const char* what) {
    if (k != n) fail(s, std::string("point attribute '") + what + "' has " + std::to_string(k) + " values for " +
                            std::to_string(n) + " points");
  };
  same(p.velocity.size(), "v"); same(p.mass.size(), "mass"); same(p.thickness.size(), "thickness");
  same(p.friction.size(), "friction"); same(p.dynamic_friction.size(), "dynamicfriction");
  same(p.layer.size(), "layer"); same(p.stopped.size(), "stopped"); same(p.piece.size(), "piece");
  for (size_t i = 0; i < n; ++i) {
    check_position(s.name, i, p.position[i]);
    if (!isfinite_(p.velocity[i])) fail(s, "point " + std::to_string(i) + " has a non-finite velocity " + vec_str(p.velocity[i]));
    if (!isfinite_(p.mass[i]) || p.mass[i] < 0) fail(s, "point " + std::to_string(i) + " has an invalid mass " + std::to_string(p.mass[i]));
    if (!isfinite_(p.thickness[i]) || p.thickness[i] < 0)
      fail(s, "point " + std::to_string(i) + " has an invalid thickness " + std::to_string(p.thickness[i]));
  }
  check_triangles(s.name, p.position, s.triangles);
  const Constraints& c = s.constraints;
  for (size_t i = 0; i < c.distance.size(); ++i)
    for (int q : {c.distance[i].a, c.distance[i].b}) check_index(s, q, n, "distance constraint " + std::to_string(i));
  for (size_t i = 0; i < c.bend.size(); ++i)
    for (int q : {c.bend[i].o0, c.bend[i].o1, c.bend[i].e0, c.bend[i].e1}) check_index(s, q, n, "bend constraint " + std::to_string(i));
  for (size_t i = 0; i < c.triarap.size(); ++i)
    for (int q : {c.triarap[i].p0, c.triarap[i].p1, c.triarap[i].p2}) check_index(s, q, n, "triarap constraint " + std::to_string(i));
  for (size_t i = 0; i < c.fem.size(); ++i)
    for (int q : {c.fem[i].p0, c.fem[i].p1, c.fem[i].p2}) check_index(s, q, n, "fem constraint " + std::to_string(i));
  const size_t ntargets = s.pin_targets.empty() ? 0 : s.pin_targets.frames[0].size();
  for (size_t i = 0; i < c.pin.size(); ++i) {
    check_index(s, c.pin[i].p, n, "pin constraint " + std::to_string(i));
    if (c.pin[i].target >= long(ntargets)) fail(s, "pin constraint " + std::to_string(i) + " refers to missing target " + std::to_string(c.pin[i].target));
    if (!isfinite_(c.pin[i].goal)) fail(s, "pin constraint " + std::to_string(i) + " has a non-finite goal");
  }
  for (size_t i = 0; i < c.ptprim.size(); ++i) {
    const auto& q = c.ptprim[i];
    check_index(s, q.p, n, "ptprim constraint " + std::to_string(i));
    if (q.nt < 2 || q.nt > 4) fail(s, "ptprim constraint " + std::to_string(i) + " has " + std::to_string(q.nt) + " target points (2 to 4)");
    for (int k = 0; k < q.nt; ++k) check_index(s, q.t[k], n, "ptprim constraint " + std::to_string(i));
  }
  for (size_t i = 0; i < c.attach.size(); ++i) {
    const auto& a = c.attach[i];
    check_index(s, a.p, n, "attach constraint " + std::to_string(i));
    if (a.collider < 0 || size_t(a.collider) >= s.colliders.size())
      fail(s, "attach constraint " + std::to_string(i) + " refers to missing collider " + std::to_string(a.collider));
    if (a.tri < 0 || size_t(a.tri) >= s.colliders[a.collider].triangles.size())
      fail(s, "attach constraint " + std::to_string(i) + " refers to missing collider triangle " + std::to_string(a.tri));
  }
  if (s.kinematic_point.size() != s.kinematic_target.size()) fail(s, "kinematic points and targets differ in count");
  for (size_t i = 0; i < s.kinematic_point.size(); ++i) {
    check_index(s, s.kinematic_point[i], n, "kinematic pin " + std::to_string(i));
    if (s.kinematic_target[i] < 0 || size_t(s.kinematic_target[i]) >= ntargets)
      fail(s, "kinematic pin " + std::to_string(i) + " refers to missing target " + std::to_string(s.kinematic_target[i]));
  }
  for (size_t f = 0; f < s.pin_targets.frames.size(); ++f) {
    if (s.pin_targets.frames[f].size() != ntargets) fail(s, "pin target frame " + std::to_string(f) + " has a different target count");
    for (size_t k = 0; k < ntargets; ++k)
      if (!isfinite_(s.pin_targets.frames[f][k])) fail(s, "pin target " + std::to_string(k) + " is not finite at frame " + std::to_string(f));
  }
  for (const Collider& col : s.colliders) {
    if (col.motion.empty()) fail(s, "collider '" + col.name + "' has no positions");
    const size_t nv = col.motion.frames[0].size();
    for (size_t f = 0; f < col.motion.frames.size(); ++f) {
      if (col.motion.frames[f].size() != nv)
        fail(s, "collider '" + col.name + "' changes its point count at frame " + std::to_string(f) + " (" +
                    std::to_string(col.motion.frames[f].size()) + " instead of " + std::to_string(nv) + ")");
      for (size_t k = 0; k < nv; ++k)
        if (!isfinite_(col.motion.frames[f][k])) fail(s, "collider '" + col.name + "' point " + std::to_string(k) + " is not finite at frame " + std::to_string(f));
    }
    for (size_t t = 0; t < col.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        if (col.triangles[t][k] < 0 || size_t(col.triangles[t][k]) >= nv)
          fail(s, "collider '" + col.name + "' triangle " + std::to_string(t) + " refers to point " +
                      std::to_string(col.triangles[t][k]) + ", out of range [0, " + std::to_string(nv) + ")");
  }
  const SolverSettings& st = s.settings;
  if (!(st.fps > 0) || st.substeps < 1 || st.iterations < 0 || st.collision_passes < 0 || st.smoothing_iterations < 0 ||
      st.frame_end < st.frame_start)
    fail(s, "invalid solver settings (fps > 0, substeps >= 1, iterations/passes >= 0, frame_end >= frame_start)");
  if (!(st.chebyshev_rho >= 0 && st.chebyshev_rho < 1) || st.chebyshev_delay < 1)
    fail(s, "invalid Chebyshev settings (chebyshev_rho in [0, 1), chebyshev_delay >= 1)");
  if (st.stretch_limits < 0 || st.stretch_limits > 3)
    fail(s, "stretch_limits " + std::to_string(st.stretch_limits) + " is not 0 (none) to 3 (limits 4, 16 and 64 hops long)");
  if (st.coarse_levels < 0 || st.coarse_levels > 16 || st.coarse_iterations < 1 || st.coarse_iterations > 1000)
    fail(s, "coarse levels " + std::to_string(st.coarse_levels) + " and coarse iterations " +
                std::to_string(st.coarse_iterations) + ": expected 0 to 16 levels and 1 to 1000 iterations");
  if (!(st.tether_stretch == 0 || (st.tether_stretch >= 1 && st.tether_stretch < 1e6)))
    fail(s, "tether stretch " + std::to_string(st.tether_stretch) + " is neither 0 (no tethers) nor at least 1 "
            "(a tether shorter than the cloth's rest path would fight its edges)");
}

std::vector<std::string> thickness_warnings(const Scene& s) {
  std::vector<std::string> out;
  if (!s.settings.collision.self_collision) return out;
  struct Worst { long tri = -1, count = 0; real ratio = 0, height = 0, thickness = 0; };
  std::vector<Worst> worst;
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tr = s.triangles[t];
    const Vec3 a = s.points.position[tr[0]], b = s.points.position[tr[1]], c = s.points.position[tr[2]];
    const real longest = sqrt_(max_(norm2(b - a), max_(norm2(c - b), norm2(a - c))));
    const real height = norm(cross(b - a, c - a)) / longest;  // 2 x area / longest edge
    const real th = max_(s.points.thickness[tr[0]], max_(s.points.thickness[tr[1]], s.points.thickness[tr[2]]));
    if (!(th > kMaxThicknessPerHeight * height)) continue;
    const size_t piece = size_t(s.points.piece[tr[0]]);
    if (worst.size() <= piece) worst.resize(piece + 1);
    Worst& w = worst[piece];
    ++w.count;
    if (th / height > w.ratio) w = {long(t), w.count, th / height, height, th};
  }
  char buf[512];
  for (size_t p = 0; p < worst.size(); ++p) {
    const Worst& w = worst[p];
    if (w.count == 0) continue;
    std::snprintf(buf, sizeof buf,
                  "cloth piece %zu: thickness %.3g m is more than %.1f of the height of %ld of its triangles (triangle "
                  "%ld is %.3g m high): self contacts reach 2.5 x the thickness and will touch a point's own "
                  "neighbouring faces, which locks the cloth; lower the thickness below %.3g m or coarsen the mesh",
                  p, w.thickness, kMaxThicknessPerHeight, w.count, w.tri, w.height, kMaxThicknessPerHeight * w.height);
    out.push_back(buf);
  }
  return out;
}

}  // namespace weft
