// Vellum stitches. A point-to-point stitch (`stitch`, `branchstitch`, glue) is a distance constraint and is
// solved with distance_eval (constraints/distance.hpp); this file adds the point-to-primitive stitch (`ptprim`):
// C = |sum_i w_i t_i - p| - L over the nt = 2..4 points of the target segment, triangle or quad.
#pragma once
#include "constraints/distance.hpp"

namespace weft {

// C and its gradient: g[0] for p, g[1 + i] for t[i] (i < nt), zero for unused slots. Weights summing to 1
// make C translation invariant. The attachment point on p gives C = -L and zero gradient.
KOKKOS_INLINE_FUNCTION real ptprim_eval(Vec3 p, const Vec3 (&t)[4], const real (&w)[4], int nt, real rest,
                                        Vec3 (&g)[5]) {
  Vec3 q;
  for (int i = 0; i < nt; ++i) q += w[i] * t[i];
  const Vec3 d = q - p;
  const real len = norm(d);
  const Vec3 n = len > 0 ? d / len : Vec3{};
  g[0] = -n;
  for (int i = 0; i < 4; ++i) g[1 + i] = i < nt ? w[i] * n : Vec3{};
  return len - rest;
}

}  // namespace weft
