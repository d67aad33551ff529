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

// atan(x) for x in [0, 1]: two half-angle reductions (x -> x / (1 + sqrt(1 + x^2))) bring |x| below
// tan(pi/16) ~ 0.199, where the odd Taylor series to x^27 is accurate to about 1e-19.
KOKKOS_INLINE_FUNCTION real atan_unit_(real x) {
  x = x / (1 + sqrt_(1 + x * x));
  x = x / (1 + sqrt_(1 + x * x));
  const real x2 = x * x;
  real p = 0;
  for (int k = 27; k >= 3; k -= 2) p = (p + ((k / 2) % 2 == 0 ? 1.0 : -1.0) / k) * x2;
  return 4 * (x + x * p);
}

// atan2(y, x) in (-pi, pi], from + - * / and sqrt only.
KOKKOS_INLINE_FUNCTION real atan2_(real y, real x) {
  const real ax = abs_(x), ay = abs_(y);
  if (ax == 0 && ay == 0) return 0;
  real a = ay <= ax ? atan_unit_(ay / ax) : pi / 2 - atan_unit_(ax / ay);
  if (x < 0) a = pi - a;
  return y < 0 ? -a : a;
}

}  // namespace weft
