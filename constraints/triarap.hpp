// Vellum "Triangle Stretch" (triarap): C = |F - R|_F, the distance of a triangle's deformation gradient from
// its closest rotation.
//
// Rest data: the inverse 2x2 rest shape matrix Dm^-1 stored row-major as (xx, xy, yx, yy), Vellum's
// `restvector`, in the triangle's own 2-D frame. F = [p1 - p0, p2 - p0] Dm^-1 is 3x2 with columns f0, f1.
// C depends only on F^T F, so any orthonormal 2-D rest frame gives the same C. The triangle_* helpers (F and
// its chain rule) are shared with fem_membrane.hpp.
#pragma once
#include "core/vec.hpp"

namespace weft {

// Rest data from a rest triangle: 2-D frame with x along p1 - p0 and y in the plane toward p2, so
// Dm = [[|p1 - p0|, (p2 - p0).x^], [0, h]] is upper triangular. A degenerate triangle gives area 0 and
// Dm^-1 = 0 (callers skip it).
KOKKOS_INLINE_FUNCTION void triarap_rest(Vec3 p0, Vec3 p1, Vec3 p2, real (&dm_inv)[4], real& area) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const real a = norm(e1);
  const real twice_area = norm(cross(e1, e2));
  for (int i = 0; i < 4; ++i) dm_inv[i] = 0;
  area = 0;
  if (!(a > 0 && twice_area > 0)) return;
  const real b = dot(e2, e1) / a;  // x of p2 - p0
  const real h = twice_area / a;   // y of p2 - p0
  dm_inv[0] = 1 / a;
  dm_inv[1] = -b / (a * h);
  dm_inv[3] = 1 / h;
  area = twice_area / 2;
}

// Columns of F = [p1 - p0, p2 - p0] Dm^-1.
KOKKOS_INLINE_FUNCTION void triangle_deformation(Vec3 p0, Vec3 p1, Vec3 p2, const real (&dm_inv)[4], Vec3& f0,
                                                 Vec3& f1) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  f0 = dm_inv[0] * e1 + dm_inv[2] * e2;
  f1 = dm_inv[1] * e1 + dm_inv[3] * e2;
}

// Chain rule from dC/dF (columns d0, d1) to the three positions; g[0] = -(g[1] + g[2]) since F sees only edges.
KOKKOS_INLINE_FUNCTION void triangle_gradients(Vec3 d0, Vec3 d1, const real (&dm_inv)[4], Vec3 (&g)[3]) {
  g[1] = dm_inv[0] * d0 + dm_inv[1] * d1;
  g[2] = dm_inv[2] * d0 + dm_inv[3] * d1;
  g[0] = -(g[1] + g[2]);
}

// C and its gradient (g[i] for p_i).
// Closest rotation in closed form: with J = |f0 x f1| > 0, n = (f0 x f1) / J and s = sqrt(|F|^2 + 2 J)
// (= sigma0 + sigma1, the sum of singular values), R = [f0 + f1 x n, f1 + n x f0] / s has orthonormal columns
// and equals the polar factor F (F^T F)^-1/2. Since d s / d F = R, dC/dF = (F - R) / C.
// A flat-collapsed F (J = 0) has C = sqrt((|F| - 1)^2 + 1) and zero gradient; so has C = 0 (at rest).
KOKKOS_INLINE_FUNCTION real triarap_eval(Vec3 p0, Vec3 p1, Vec3 p2, const real (&dm_inv)[4], Vec3 (&g)[3]) {
  Vec3 f0, f1;
  triangle_deformation(p0, p1, p2, dm_inv, f0, f1);
  const Vec3 n = cross(f0, f1);
  const real jac = norm(n);
  const real ff = norm2(f0) + norm2(f1);
  if (!(jac > 0)) {
    for (int i = 0; i < 3; ++i) g[i] = Vec3{};
    const real fn = sqrt_(ff);
    return sqrt_((fn - 1) * (fn - 1) + 1);
  }
  const Vec3 nh = n / jac;
  const real s = sqrt_(ff + 2 * jac);
  // F - R, computed directly (not from invariants) so that C near 0 keeps full relative precision.
  const Vec3 d0 = f0 - (f0 + cross(f1, nh)) / s;
  const Vec3 d1 = f1 - (f1 + cross(nh, f0)) / s;
  const real c = sqrt_(norm2(d0) + norm2(d1));
  if (!(c > 0)) {
    for (int i = 0; i < 3; ++i) g[i] = Vec3{};
    return 0;
  }
  triangle_gradients(d0 / c, d1 / c, dm_inv, g);
  return c;
}

}  // namespace weft
