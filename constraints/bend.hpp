// Vellum "Bend Across Triangles": C = signed dihedral angle - rest, in radians.
//
// Points: e0-e1 is the shared edge, o0 and o1 the opposite points of the triangles (o0, e0, e1) and (o1, e1, e0).
// Normals n0 = (e0 - o0) x (e1 - o0) and n1 = (e1 - o1) x (e0 - o1): the two triangles traverse the edge in
// opposite directions, so a flat pair (o0, o1 on opposite sides) has n0 = n1 and angle 0.
// Sign: the angle is positive when o1 lies on the side that n0 points to (the pair folds toward the front of
// triangle (o0, e0, e1)), i.e. it has the sign of n0 . (o1 - e0). Range (-pi, pi].
// Vellum stores the rest angle in degrees (`restlength`); callers pass rest_rad = restlength * pi / 180.
#pragma once
#include "core/vec.hpp"

namespace weft {

// The signed angle from the normals; atan2 of unnormalised sine and cosine (both scaled by L |n0| |n1|)
// stays accurate near 0 and near +-pi, where acos / asin of a dot product would not.
KOKKOS_INLINE_FUNCTION real bend_angle_(Vec3 n0, Vec3 n1, Vec3 e, real len) {
  return atan2_(dot(cross(n1, n0), e), len * dot(n0, n1));
}

// Signed dihedral angle (radians) of a configuration, to set rest data. Degenerate triangles give 0.
KOKKOS_INLINE_FUNCTION real bend_rest_angle(Vec3 o0, Vec3 o1, Vec3 e0, Vec3 e1) {
  const Vec3 e = e1 - e0;
  return bend_angle_(cross(e0 - o0, e1 - o0), cross(e1 - o1, e0 - o1), e, norm(e));
}

// C and its gradient (g[0] o0, g[1] o1, g[2] e0, g[3] e1); rest_rad in (-pi, pi]. C is wrapped into (-pi, pi]
// so a pair folded near +-pi is driven the short way to its rest angle, not the long way round.
// Gradient (Bridson et al. 2003): d angle / d o = L n / |n|^2 for each opposite point, the edge points get the
// rest so that the four sum to zero and the angle is invariant to rotation about the edge. A zero-length edge or
// a zero-area triangle gives zero gradient.
KOKKOS_INLINE_FUNCTION real bend_eval(Vec3 o0, Vec3 o1, Vec3 e0, Vec3 e1, real rest_rad, Vec3 (&g)[4]) {
  const Vec3 e = e1 - e0;
  const real len = norm(e);
  const Vec3 n0 = cross(e0 - o0, e1 - o0), n1 = cross(e1 - o1, e0 - o1);
  const real a0 = norm2(n0), a1 = norm2(n1);
  real c = bend_angle_(n0, n1, e, len) - rest_rad;
  if (c > pi) c -= 2 * pi;
  else if (c <= -pi) c += 2 * pi;
  if (!(len > 0 && a0 > 0 && a1 > 0)) {
    for (int i = 0; i < 4; ++i) g[i] = Vec3{};
    return c;
  }
  // Reciprocals once, then products: on the GPU a row's time is its chain of dependent instructions, and a
  // double division is some thirty of them.
  const real inv_len = 1 / len;
  const Vec3 u0 = n0 * (1 / a0), u1 = n1 * (1 / a1);
  g[0] = len * u0;
  g[1] = len * u1;
  g[2] = (dot(o0 - e1, e) * inv_len) * u0 + (dot(o1 - e1, e) * inv_len) * u1;
  g[3] = (dot(o0 - e0, e) * -inv_len) * u0 + (dot(o1 - e0, e) * -inv_len) * u1;
  return c;
}

}  // namespace weft
