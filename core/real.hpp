// Scalar arithmetic for solver code: + - * / and sqrt only, so every backend rounds identically.
#pragma once
#include <Kokkos_Core.hpp>

#include <math.h>

namespace weft {

using real = double;

KOKKOS_INLINE_FUNCTION real sqrt_(real x) { return ::sqrt(x); }  // IEEE correctly rounded on host and device
KOKKOS_INLINE_FUNCTION real min_(real a, real b) { return b < a ? b : a; }
KOKKOS_INLINE_FUNCTION real max_(real a, real b) { return a < b ? b : a; }
KOKKOS_INLINE_FUNCTION real abs_(real a) { return a < 0 ? -a : a; }
KOKKOS_INLINE_FUNCTION real clamp_(real x, real lo, real hi) { return min_(max_(x, lo), hi); }
KOKKOS_INLINE_FUNCTION bool isfinite_(real x) { return x - x == 0; }  // false for NaN and +-Inf

inline constexpr real pi = 3.14159265358979323846;

// atan(y / x) for 0 <= y <= x, x > 0: two half-angle reductions, each (y, x) -> (y, x + sqrt(x^2 + y^2)),
// bring the angle below pi/16 (tan ~ 0.199), where the odd Taylor series to t^27 is accurate to about 1e-19.
// The reductions keep the pair unnormalised, so the whole costs one division (its squares bound x and y to
// about 1e-150..1e150; a bend angle's pair scales as an edge length to the fifth). Within 4 ulp of atan2.
KOKKOS_INLINE_FUNCTION real atan_ratio_(real y, real x) {
  x = x + sqrt_(x * x + y * y);
  x = x + sqrt_(x * x + y * y);
  const real t = y / x, t2 = t * t;
  real p = 0;
  for (int k = 27; k >= 3; k -= 2) p = (p + ((k / 2) % 2 == 0 ? 1.0 : -1.0) / k) * t2;
  return 4 * (t + t * p);
}

// atan2(y, x) in (-pi, pi], from + - * / and sqrt only.
KOKKOS_INLINE_FUNCTION real atan2_(real y, real x) {
  const real ax = abs_(x), ay = abs_(y);
  if (ax == 0 && ay == 0) return 0;
  real a = ay <= ax ? atan_ratio_(ay, ax) : pi / 2 - atan_ratio_(ax, ay);
  if (x < 0) a = pi - a;
  return y < 0 ? -a : a;
}

}  // namespace weft
