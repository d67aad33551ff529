// The XPBD update shared by every constraint kind (see docs/solver.md and the Vellum spec):
//   alpha~  = compliance / h^2            compliance = 1 / stiffness
//   gamma   = dampingratio / h
//   dlambda = (-C - alpha~ lambda - gamma sum_i g_i.(x_i - x_i^start)) / ((1 + gamma) sum_i w_i |g_i|^2 + alpha~)
//   x_i    += w_i g_i dlambda
// A row whose compress compliance is +inf only pulls (a stretch limit, constraints/build_stretch_limits.hpp):
// it uses its compliance throughout, and its multiplier never turns positive (the XPBD form of an
// inequality), so a compressed limit leaves its points alone and gives back no more than it had pulled.
#pragma once
#include "core/vec.hpp"
#include "scene/material.hpp"

namespace weft {

// dlambda for one constraint with N particles. g: gradients; w: inverse masses; dx: x_i - x_i^start.
// Returns 0 when no particle can move.
template <int N>
KOKKOS_INLINE_FUNCTION real xpbd_delta_lambda(real C, const Vec3 (&g)[N], const real (&w)[N], const Vec3 (&dx)[N],
                                              real lambda, const XpbdMaterial& m, real h) {
  const bool pulls = pulls_only(m);
  const real inv_h = 1 / h;  // one division for both
  const real alpha = (C < 0 && !pulls ? m.compress_compliance : m.compliance) * (inv_h * inv_h);
  const real gamma = m.damping_ratio * inv_h;
  real wg = 0, gdx = 0;
  for (int i = 0; i < N; ++i) {
    wg += w[i] * dot(g[i], g[i]);
    gdx += dot(g[i], dx[i]);
  }
  const real denom = (1 + gamma) * wg + alpha;
  if (!(wg > 0) || !(denom > 0)) return 0;
  const real dl = (-C - alpha * lambda - gamma * gdx) / denom;
  return pulls && lambda + dl > 0 ? -lambda : dl;
}

}  // namespace weft
