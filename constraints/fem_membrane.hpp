// FEM membrane: in-plane stable neo-Hookean elasticity of a triangle, as two XPBD constraints (Macklin & Mueller
// 2021, "A constraint-based formulation of stable neo-Hookean materials", on the 3x2 deformation gradient
// F = [f0, f1] of triarap.hpp, rest data from triarap_rest):
//
//   deviatoric   C_D = |F|_F = sqrt(tr(F^T F))         compliance 1 / (mu     * tau * A)
//   hydrostatic  C_H = J - gamma,  J = |f0 x f1|        compliance 1 / (lambda * tau * A),  gamma = 1 + mu / lambda
//
// Energy per unit rest volume: mu/2 |F|^2 + lambda/2 (J - gamma)^2. At rest (F a rotation) C_D = sqrt(2) and
// J = 1, and the two forces cancel exactly (that is what gamma is for). The shifted form sqrt(tr(F^T F)) - sqrt(2),
// which would vanish at rest, is not used: it has no first-order shear stiffness (simple shear changes neither
// tr(F^T F) nor J to first order).
// mu and lambda come from fem_lame: the shear modulus, and lambda = plane-stress Lame lambda + mu = E / (2 (1 - nu))
// (the 2-D bulk modulus; Smith et al. 2018, sec. 3.4): with it the small-strain limit is exactly linear
// plane-stress elasticity with Young's modulus E and Poisson ratio nu, and nu = 0 needs no special case.
// J = |f0 x f1| cannot go negative (a 3-D triangle has no reference side), so in-plane inversion is not resisted.
//
// Units: E, mu, lambda in Pa; tau (fabric thickness) in m; A (rest area) in m^2; positions in m. tau * A is the
// element's rest volume (m^3), so mu tau A is in joules and the compliances in 1/J, as XPBD expects.
#pragma once
#include "constraints/triarap.hpp"

namespace weft {

// mu = E / (2 (1 + nu)) and the model's lambda = E / (2 (1 - nu)) (see above), for -1 < nu < 1.
KOKKOS_INLINE_FUNCTION void fem_lame(real E, real nu, real& mu, real& lambda) {
  mu = E / (2 * (1 + nu));
  lambda = E / (2 * (1 - nu));
}

// The rest value of J that balances the deviatoric force at rest.
KOKKOS_INLINE_FUNCTION real fem_gamma(real mu, real lambda) { return 1 + mu / lambda; }

// C_D and its gradient (g[i] for p_i); dC/dF = F / |F|. F = 0 gives zero gradient.
KOKKOS_INLINE_FUNCTION real fem_deviatoric_eval(Vec3 p0, Vec3 p1, Vec3 p2, const real (&dm_inv)[4], Vec3 (&g)[3]) {
  Vec3 f0, f1;
  triangle_deformation(p0, p1, p2, dm_inv, f0, f1);
  const real c = sqrt_(norm2(f0) + norm2(f1));
  if (!(c > 0)) {
    for (int i = 0; i < 3; ++i) g[i] = Vec3{};
    return 0;
  }
  triangle_gradients(f0 / c, f1 / c, dm_inv, g);
  return c;
}

// C_H and its gradient (g[i] for p_i); with n the unit normal of f0 x f1, dJ/df0 = f1 x n and dJ/df1 = n x f0.
// A collapsed triangle (J = 0) gives C = -gamma and zero gradient.
KOKKOS_INLINE_FUNCTION real fem_hydrostatic_eval(Vec3 p0, Vec3 p1, Vec3 p2, const real (&dm_inv)[4], real gamma,
                                                 Vec3 (&g)[3]) {
  Vec3 f0, f1;
  triangle_deformation(p0, p1, p2, dm_inv, f0, f1);
  const Vec3 n = cross(f0, f1);
  const real jac = norm(n);
  if (!(jac > 0)) {
    for (int i = 0; i < 3; ++i) g[i] = Vec3{};
    return -gamma;
  }
  const Vec3 nh = n / jac;
  triangle_gradients(cross(f1, nh), cross(nh, f0), dm_inv, g);
  return jac - gamma;
}

}  // namespace weft
