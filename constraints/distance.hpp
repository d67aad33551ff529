// Distance along an edge: C = |b - a| - L.
#pragma once
#include "core/vec.hpp"

namespace weft {

// C and its gradient (g[0] for a, g[1] for b). Coincident points give C = -L and zero gradient.
KOKKOS_INLINE_FUNCTION real distance_eval(Vec3 a, Vec3 b, real rest, Vec3 (&g)[2]) {
  const Vec3 d = b - a;
  const real len = norm(d);
  const Vec3 n = len > 0 ? d * (1 / len) : Vec3{};  // one division, not three
  g[0] = -n;
  g[1] = n;
  return len - rest;
}

}  // namespace weft
