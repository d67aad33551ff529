// Discrete proximity: closest points and squared distances between a point and a triangle and between two
// segments, with the parameters the solver needs to build contacts. Every candidate (interior critical point
// and each boundary feature) is measured directly and the nearest kept, so degenerate triangles and
// parallel or zero-length segments need no special case.
#pragma once
#include "core/vec.hpp"

namespace weft {

// Squared distance from p to the segment a + s (b - a), s in [0, 1]; s of the closest point.
KOKKOS_INLINE_FUNCTION real point_segment_distance2(Vec3 p, Vec3 a, Vec3 b, real& s) {
  const Vec3 ab = b - a;
  const real l2 = norm2(ab);
  s = l2 > 0 ? clamp_(dot(p - a, ab) / l2, 0, 1) : 0;
  return norm2(p - (a + s * ab));
}

// Squared distance from p to the triangle abc; the closest point is u a + v b + w c (u + v + w = 1).
KOKKOS_INLINE_FUNCTION real point_triangle_distance2(Vec3 p, Vec3 a, Vec3 b, Vec3 c, real& u, real& v, real& w) {
  real s;
  real best = point_segment_distance2(p, a, b, s);
  u = 1 - s;
  v = s;
  w = 0;
  real d = point_segment_distance2(p, b, c, s);
  if (d < best) { best = d; u = 0; v = 1 - s; w = s; }
  d = point_segment_distance2(p, c, a, s);
  if (d < best) { best = d; u = s; v = 0; w = 1 - s; }
  // The orthogonal projection, when it falls inside a triangle of non-zero area.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const real d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac), d20 = dot(ap, ab), d21 = dot(ap, ac);
  const real den = d00 * d11 - d01 * d01;
  if (den > 0) {
    const real bv = (d11 * d20 - d01 * d21) / den, bw = (d00 * d21 - d01 * d20) / den;
    if (bv >= 0 && bw >= 0 && bv + bw <= 1) {
      d = norm2(p - (a + bv * ab + bw * ac));
      if (d < best) { best = d; u = 1 - bv - bw; v = bv; w = bw; }
    }
  }
  return best;
}

// Squared distance between the segments a0 + s (a1 - a0) and b0 + t (b1 - b0); s, t of the closest points.
KOKKOS_INLINE_FUNCTION real segment_segment_distance2(Vec3 a0, Vec3 a1, Vec3 b0, Vec3 b1, real& s, real& t) {
  real r;
  real best = point_segment_distance2(a0, b0, b1, r);
  s = 0;
  t = r;
  real d = point_segment_distance2(a1, b0, b1, r);
  if (d < best) { best = d; s = 1; t = r; }
  d = point_segment_distance2(b0, a0, a1, r);
  if (d < best) { best = d; s = r; t = 0; }
  d = point_segment_distance2(b1, a0, a1, r);
  if (d < best) { best = d; s = r; t = 1; }
  // The common perpendicular of non-parallel lines, when its feet lie on both segments.
  const Vec3 da = a1 - a0, db = b1 - b0, w0 = a0 - b0;
  const real aa = dot(da, da), ab = dot(da, db), bb = dot(db, db), ad = dot(da, w0), bd = dot(db, w0);
  const real den = aa * bb - ab * ab;
  if (den > 0) {
    const real si = (ab * bd - bb * ad) / den, ti = (aa * bd - ab * ad) / den;
    if (si >= 0 && si <= 1 && ti >= 0 && ti <= 1) {
      d = norm2((a0 + si * da) - (b0 + ti * db));
      if (d < best) { best = d; s = si; t = ti; }
    }
  }
  return best;
}

}  // namespace weft
