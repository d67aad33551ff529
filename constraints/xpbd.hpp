// The XPBD update shared by every constraint kind (see docs/solver.md and the Vellum spec):
//   alpha~  = compliance / h^2            compliance = 1 / stiffness
//   gamma   = dampingratio / h
//   dlambda = (-C - alpha~ lambda - gamma sum_i g_i.(x_i - x_i^start)) / ((1 + gamma) sum_i w_i |g_i|^2 + alpha~)
//   x_i    += w_i g_i dlambda
#pragma once
#include "core/vec.hpp"
#include "scene/material.hpp"

namespace weft {

// dlambda for one constraint with N particles. g: gradients; w: inverse masses; dx: x_i - x_i^start.
// Returns 0 when no particle can move.
template <int N>
KOKKOS_INLINE_FUNCTION real xpbd_delta_lambda(real C, const Vec3 (&g)[N], const real (&w)[N], const Vec3 (&dx)[N],
                                              real lambda, const XpbdMaterial& m, real h) {
  const real alpha = (C < 0 ? m.compress_compliance : m.compliance) / (h * h);
  const real gamma = m.damping_ratio / h;
  real wg = 0, gdx = 0;
  for (int i = 0; i < N; ++i) {
    wg += w[i] * dot(g[i], g[i]);
    gdx += dot(g[i], dx[i]);
  }
  const real denom = (1 + gamma) * wg + alpha;
  if (!(wg > 0) || !(denom > 0)) return 0;
  return (-C - alpha * lambda - gamma * gdx) / denom;
}

}  // namespace weft
