// Jacobi projection of contacts: every contact computes its corrections from the same positions, and each
// point then moves by the average of the corrections it received. Two launches per iteration however many
// contacts meet at a point, and no colouring; Gauss-Seidel (one launch per colour, 90-400 colours where
// contacts pile up) converges faster per iteration. Over-relaxing the average (1.5 or 2 times) left the
// layer-stack less calm. The corrections are summed as 64-bit fixed-point integers (integer atomics add in
// any order to the same sum), so the result is the same on every backend and thread count.
#pragma once
#include "collision/contact.hpp"

#include <Kokkos_Core.hpp>
#include <type_traits>

namespace weft {

namespace jacobi_detail {

using Fixed = unsigned long long;  // two's complement sums of signed fixed-point values
static_assert(std::is_integral_v<Fixed>, "contact sums are integers: atomics add them in any order to the same bits");
constexpr real kFixedScale = 1099511627776.0;  // 2^40: resolution 9e-13 m
constexpr real kFixedLimit = 72057594037927936.0;  // 2^56: 65 km, and 128 of them sum without overflow

KOKKOS_INLINE_FUNCTION Fixed to_fixed(real v) {
  const real s = v * kFixedScale;
  if (!(s == s)) return 0;  // NaN: leave the point alone rather than convert undefined
  return Fixed((long long)(clamp_(s, -kFixedLimit, kFixedLimit)));
}
KOKKOS_INLINE_FUNCTION real from_fixed(Fixed f) { return real((long long)(f)); }

// Per contact: its corrections, added to its points' sums; acc(p, 3) counts the contributions.
template <class Mem>
struct ContactDeltas {
  Kokkos::View<const Contact*, Mem> c;
  Kokkos::View<Vec3*, Mem> x, xs;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<Vec3*, Mem> cx, cxs;
  Kokkos::View<Fixed* [4], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const Contact ci = c(i);
    const real C = contact_value(ci, x, cx);
    if (!(C < 0)) return;
    real wk[4], denom, dl;
    if (!contact_normal_step(ci, C, w, wk, denom, dl)) return;
    // Friction from the positions before the normal step: that step moves the sides along n only, so the
    // tangential displacement is the one Gauss-Seidel sees after it.
    Vec3 corr{};
    const bool fr = (ci.mu_s > 0 || ci.mu_d > 0) &&
                    friction_correction(ci, contact_displacement(ci, x, xs, cx, cxs), -C, corr);
    for (int k = 0; k < 4; ++k) {
      if (!(wk[k] > 0 && ci.b[k] != 0)) continue;
      Vec3 d = (wk[k] * ci.b[k] * dl) * ci.n;
      if (fr) d += (wk[k] * ci.b[k] / denom) * corr;
      const int p = ci.p[k];
      Kokkos::atomic_add(&acc(p, 0), to_fixed(d.x));
      Kokkos::atomic_add(&acc(p, 1), to_fixed(d.y));
      Kokkos::atomic_add(&acc(p, 2), to_fixed(d.z));
      Kokkos::atomic_add(&acc(p, 3), Fixed(1));
    }
  }
};

// Per point: the average of its corrections; the sums are cleared for the next iteration.
template <class Mem>
struct ApplyDeltas {
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<Fixed* [4], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(long p) const {
    const Fixed n = acc(p, 3);
    if (n == 0) return;
    const real s = kFixedScale * real(n);
    x(p) += Vec3{from_fixed(acc(p, 0)) / s, from_fixed(acc(p, 1)) / s, from_fixed(acc(p, 2)) / s};
    for (int k = 0; k < 4; ++k) acc(p, k) = 0;
  }
};

}  // namespace jacobi_detail

template <class Exec>
class JacobiContacts {
 public:
  using Mem = typename Exec::memory_space;

  // One Jacobi iteration over contacts [0, n).
  void project(const Exec& exec, const Kokkos::View<Contact*, Mem>& c, long n, const Kokkos::View<Vec3*, Mem>& x,
               const Kokkos::View<Vec3*, Mem>& xs, const Kokkos::View<real*, Mem>& w,
               const Kokkos::View<Vec3*, Mem>& cx, const Kokkos::View<Vec3*, Mem>& cxs) {
    using namespace jacobi_detail;
    if (n == 0) return;
    const long points = long(x.extent(0));
    if (long(acc_.extent(0)) != points) acc_ = Kokkos::View<Fixed* [4], Mem>("weft::contact_sums", points);
    Kokkos::parallel_for("weft::contact_deltas", Kokkos::RangePolicy<Exec>(exec, 0, n),
                         ContactDeltas<Mem>{c, x, xs, w, cx, cxs, acc_});
    Kokkos::parallel_for("weft::contact_apply", Kokkos::RangePolicy<Exec>(exec, 0, points), ApplyDeltas<Mem>{x, acc_});
  }

 private:
  Kokkos::View<jacobi_detail::Fixed* [4], Mem> acc_{"weft::contact_sums", 0};  // zero between iterations
};

}  // namespace weft
