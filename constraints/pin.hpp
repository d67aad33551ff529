// Vellum pin and attach: C = |p - goal| - L; only p moves (the goal is data, not a particle).
#pragma once
#include "core/vec.hpp"

namespace weft {

// C and its gradient for p. p at the goal gives C = -L and zero gradient.
KOKKOS_INLINE_FUNCTION real pin_eval(Vec3 p, Vec3 goal, real rest, Vec3 (&g)[1]) {
  const Vec3 d = p - goal;
  const real len = norm(d);
  g[0] = len > 0 ? d / len : Vec3{};
  return len - rest;
}

// Attach goal on a triangle (t0, t1, t2) of the animated target, re-evaluated every substep from Vellum's
// `target_uv` = (u, v): Houdini's triangle parametric coordinates, weights (1 - u - v, u, v), so (0, 0) is t0,
// (1, 0) is t1 and (0, 1) is t2.
KOKKOS_INLINE_FUNCTION Vec3 attach_goal(Vec3 t0, Vec3 t1, Vec3 t2, real u, real v) {
  return (1 - u - v) * t0 + u * t1 + v * t2;
}

}  // namespace weft
