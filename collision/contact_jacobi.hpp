// Jacobi projection of contacts: every contact computes its corrections from the same positions, and each
// point then moves by the average of the corrections it received. Two launches per iteration however many
// contacts meet at a point, and no colouring; Gauss-Seidel (one launch per colour, 90-400 colours where
// contacts pile up) converges faster per iteration. Over-relaxing the average (1.5 or 2 times) left the
// layer-stack less calm. The corrections are summed as 64-bit fixed-point integers (integer atomics add in
// any order to the same sum), so the result is the same on every backend and thread count. On the host each
// thread sums into its own copy, without atomics, and the copies are added per point.
#pragma once
#include "collision/contact.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

namespace jacobi_detail {

using Fixed = unsigned long long;  // two's complement sums of signed fixed-point values
constexpr real kFixedScale = 1099511627776.0;  // 2^40: resolution 9e-13 m
constexpr real kFixedLimit = 72057594037927936.0;  // 2^56: 65 km, and 128 of them sum without overflow

KOKKOS_INLINE_FUNCTION Fixed to_fixed(real v) {
  const real s = v * kFixedScale;
  if (!(s == s)) return 0;  // NaN: leave the point alone rather than convert undefined
  return Fixed((long long)(clamp_(s, -kFixedLimit, kFixedLimit)));
}
KOKKOS_INLINE_FUNCTION real from_fixed(Fixed f) { return real((long long)(f)); }

// Contact i's corrections, handed to add(point, dx, dy, dz) in fixed point.
template <class Mem, class Add>
KOKKOS_INLINE_FUNCTION void contact_deltas(const Contact& ci, const Kokkos::View<Vec3*, Mem>& x,
                                           const Kokkos::View<Vec3*, Mem>& xs, const Kokkos::View<real*, Mem>& w,
                                           const Kokkos::View<Vec3*, Mem>& cx, const Kokkos::View<Vec3*, Mem>& cxs,
                                           const Add& add) {
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
    add(ci.p[k], to_fixed(d.x), to_fixed(d.y), to_fixed(d.z));
  }
}

template <class Mem>
struct AtomicAdd {
  Kokkos::View<Fixed* [4], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(int p, Fixed dx, Fixed dy, Fixed dz) const {
    Kokkos::atomic_add(&acc(p, 0), dx);
    Kokkos::atomic_add(&acc(p, 1), dy);
    Kokkos::atomic_add(&acc(p, 2), dz);
    Kokkos::atomic_add(&acc(p, 3), Fixed(1));
  }
};

template <class Mem>
struct PlainAdd {
  Kokkos::View<Fixed** [4], Mem> acc;
  int copy;
  KOKKOS_INLINE_FUNCTION void operator()(int p, Fixed dx, Fixed dy, Fixed dz) const {
    acc(copy, p, 0) += dx;
    acc(copy, p, 1) += dy;
    acc(copy, p, 2) += dz;
    acc(copy, p, 3) += 1;
  }
};

// Per contact (device): its corrections, added to its points' sums by integer atomics; acc(p, 3) counts
// the contributions.
template <class Mem>
struct ContactDeltas {
  Kokkos::View<const Contact*, Mem> c;
  Kokkos::View<Vec3*, Mem> x, xs;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<Vec3*, Mem> cx, cxs;
  Kokkos::View<Fixed* [4], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { contact_deltas(c(i), x, xs, w, cx, cxs, AtomicAdd<Mem>{acc}); }
};

// Per chunk of kHostChunk contacts (host): the corrections added without atomics into the sums of the
// thread's own copy (a locked add per sum made the 6-layer stack spend half its frame here on 2 cores).
// The copies are integer sums, added up in ApplyDeltas: the same bits as the atomics'.
constexpr long kHostChunk = 256;

template <class Exec>
struct ContactDeltasPerCopy {
  using Mem = typename Exec::memory_space;
  Kokkos::View<const Contact*, Mem> c;
  long n;
  Kokkos::View<Vec3*, Mem> x, xs;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<Vec3*, Mem> cx, cxs;
  Kokkos::View<Fixed** [4], Mem> acc;
  Kokkos::Experimental::UniqueToken<Exec> token;
  KOKKOS_INLINE_FUNCTION void operator()(long chunk) const {
    const int copy = token.acquire();
    const long hi = (chunk + 1) * kHostChunk < n ? (chunk + 1) * kHostChunk : n;
    for (long i = chunk * kHostChunk; i < hi; ++i) contact_deltas(c(i), x, xs, w, cx, cxs, PlainAdd<Mem>{acc, copy});
    token.release(copy);
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

// The same from the host's per-thread copies, summed first.
template <class Mem>
struct ApplyCopies {
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<Fixed** [4], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(long p) const {
    Fixed sum[4] = {0, 0, 0, 0};
    for (long copy = 0; copy < long(acc.extent(0)); ++copy)
      for (int k = 0; k < 4; ++k) {
        sum[k] += acc(copy, p, k);
        acc(copy, p, k) = 0;
      }
    if (sum[3] == 0) return;
    const real s = kFixedScale * real(sum[3]);
    x(p) += Vec3{from_fixed(sum[0]) / s, from_fixed(sum[1]) / s, from_fixed(sum[2]) / s};
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
    if constexpr (Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible) {
      const Kokkos::Experimental::UniqueToken<Exec> token(exec);
      if (long(copies_.extent(0)) != long(token.size()) || long(copies_.extent(1)) != points)
        copies_ = Kokkos::View<Fixed** [4], Mem>("weft::contact_sums", token.size(), points);
      Kokkos::parallel_for("weft::contact_deltas", Kokkos::RangePolicy<Exec>(exec, 0, (n + kHostChunk - 1) / kHostChunk),
                           ContactDeltasPerCopy<Exec>{c, n, x, xs, w, cx, cxs, copies_, token});
      Kokkos::parallel_for("weft::contact_apply", Kokkos::RangePolicy<Exec>(exec, 0, points), ApplyCopies<Mem>{x, copies_});
      return;
    }
    if (long(acc_.extent(0)) != points) acc_ = Kokkos::View<Fixed* [4], Mem>("weft::contact_sums", points);
    Kokkos::parallel_for("weft::contact_deltas", Kokkos::RangePolicy<Exec>(exec, 0, n),
                         ContactDeltas<Mem>{c, x, xs, w, cx, cxs, acc_});
    Kokkos::parallel_for("weft::contact_apply", Kokkos::RangePolicy<Exec>(exec, 0, points), ApplyDeltas<Mem>{x, acc_});
  }

 private:
  Kokkos::View<jacobi_detail::Fixed* [4], Mem> acc_{"weft::contact_sums", 0};  // zero between iterations
  Kokkos::View<jacobi_detail::Fixed** [4], Mem> copies_{"weft::contact_sums", 0, 0};  // host: one per thread
};

}  // namespace weft
