// Ray against triangle (Möller and Trumbore 1997, "Fast, minimum storage ray-triangle intersection"), with
// + - * / only, so every backend finds the same hits at the same distances.
#pragma once
#include "collision/aabb.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

struct RayHit {
  real t = 0;     // distance along the (unit) direction
  real u = 0, v = 0;  // barycentric: hit = (1 - u - v) a + u b + v c
};

// The ray o + t d, 0 < t <= t_max, meets the closed triangle abc; a ray in the triangle's plane never does.
KOKKOS_INLINE_FUNCTION bool ray_meets_triangle(Vec3 o, Vec3 d, real t_max, Vec3 a, Vec3 b, Vec3 c, RayHit& hit) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = cross(d, e2);
  const real det = dot(e1, p);
  if (det == 0) return false;
  const Vec3 s = o - a;
  const real u = dot(s, p) / det;
  if (u < 0 || u > 1) return false;
  const Vec3 q = cross(s, e1);
  const real v = dot(d, q) / det;
  if (v < 0 || u + v > 1) return false;
  const real t = dot(e2, q) / det;
  if (!(t > 0 && t <= t_max)) return false;
  hit = {t, u, v};
  return true;
}

// The box of the segment o .. o + t_max d, for a broad-phase query.
KOKKOS_INLINE_FUNCTION Aabb ray_box(Vec3 o, Vec3 d, real t_max) { return expand(Aabb{o, o}, o + t_max * d); }

}  // namespace weft
