// Jacobi projection of contacts: every contact computes its corrections from the same positions, and each
// point then moves by the average of the corrections it received. Two launches per iteration however many
// contacts meet at a point, and no colouring; Gauss-Seidel (one launch per colour, 90-400 colours where
// contacts pile up) converges faster per iteration. Over-relaxing the average (1.5 or 2 times) left the
// layer-stack less calm. The corrections are summed as 64-bit fixed-point integers (integer atomics add in
// any order to the same sum), so the result is the same on every backend and thread count.
//
// With merge_contacts, contacts that act on the same two or three points project as one row counted as many:
// where a point of one layer rests on a point or an edge of the next, the vertex-face pairs of the faces
// round it and the edge-edge pairs of the edges round it all measure the same closest points, up to 48
// contacts for one vertex-vertex pair. Counted as many, each keeps its weight in the points' averages,
// which dropping them did not. The rows cost a sort at every pass: a gain on CPUs, a loss on the GPU
// (docs/performance.md, "Merged contacts"), so it is off by default.
#pragma once
#include "collision/contact.hpp"
#include "core/scan.hpp"
#include "core/sort.hpp"

#include <Kokkos_Core.hpp>
#include <string>
#include <type_traits>

namespace weft {

namespace jacobi_detail {

using Fixed = unsigned long long;  // two's complement sums of signed fixed-point values
static_assert(std::is_integral_v<Fixed>, "contact sums are integers: atomics add them in any order to the same bits");
constexpr real kFixedScale = 1099511627776.0;  // 2^40: resolution 9e-13 m
// A point's x sum carries its count of contributions in its low kCountBits: one atomic fewer per point of a
// contact. So a sum holds 2^(63 - kCountBits) units: 128 corrections of up to 2^42 (4 m), and up to 16,383
// contributions to one point in one iteration (a point of the 50-layer drop has about a hundred).
constexpr int kCountBits = 14;
constexpr real kFixedLimit = 4398046511104.0;  // 2^42

KOKKOS_INLINE_FUNCTION Fixed to_fixed(real v) {
  const real s = v * kFixedScale;
  if (!(s == s)) return 0;  // NaN: leave the point alone rather than convert undefined
  return Fixed((long long)(clamp_(s, -kFixedLimit, kFixedLimit)));
}
KOKKOS_INLINE_FUNCTION real from_fixed(Fixed f) { return real((long long)(f)); }

// A contact as the iterations read it, built once per collision pass: the points' weights, the normal,
// the barycentrics and the layer shock stay fixed while the pass's contacts live, so each point's share
// of the multiplier, f = w b / denom, is taken once rather than at every iteration. Passes run within a
// substep (its first at its start), so the contact's point at the substep's start, sum b x_start, is too:
// friction reads no start positions.
struct JacobiRow {
  int p[4];
  real b[4];
  real f[4];  // 0 where the point does not move (collider vertex, pinned, b = 0)
  Vec3 n;
  Vec3 start;  // sum b x_start
  real r, mu_s, mu_d;
  int count;  // the contacts this row stands for
};

template <class WView, class XView, class CView>
KOKKOS_INLINE_FUNCTION JacobiRow row_of(const Contact& ci, const WView& w, const XView& xs, const CView& cxs,
                                        int count) {
  JacobiRow row;
  row.start = Vec3{0, 0, 0};
  for (int k = 0; k < 4; ++k)
    if (ci.b[k] != 0) row.start += ci.b[k] * contact_point_pos(ci.p[k], xs, cxs);
  real wk[4], denom;
  const bool moves = contact_weights(ci, w, wk, denom);
  for (int k = 0; k < 4; ++k) {
    row.p[k] = ci.p[k];
    row.b[k] = ci.b[k];
    row.f[k] = moves && wk[k] > 0 && ci.b[k] != 0 ? wk[k] * ci.b[k] / denom : 0.0;
  }
  row.n = ci.n;
  row.r = ci.r;
  row.mu_s = ci.mu_s;
  row.mu_d = ci.mu_d;
  row.count = count;
  return row;
}

// A contact's points with b != 0, ascending, and the sign that makes the first one's b positive: contacts
// with the same points constrain them alike once their b and n take that sign.
struct ContactPoints {
  int size = 0;
  int slot[4];  // which of the contact's slots, in ascending point order
  real sign = 1;
};

KOKKOS_INLINE_FUNCTION ContactPoints contact_points(const Contact& c) {
  ContactPoints e;
  for (int k = 0; k < 4; ++k) {
    if (c.b[k] == 0) continue;
    int j = e.size++;
    for (; j > 0 && c.p[e.slot[j - 1]] > c.p[k]; --j) e.slot[j] = e.slot[j - 1];
    e.slot[j] = k;
  }
  if (e.size > 0 && c.b[e.slot[0]] < 0) e.sign = -1;
  return e;
}

// Sort keys: the two or three points, `bits` each (collider vertices after the cloth's); contacts on four
// points (or any, when the indices do not fit) get the key kAlone and stay rows of their own.
constexpr uint64_t kAlone = ~uint64_t(0);

// What a merged row averages of each contact, signed alike and in ascending point order: written with the
// keys, so that merging reads one line per contact in the sorted order.
struct SignedContact {
  real b[3];
  Vec3 n;
  real r;
};

template <class Mem>
struct ContactKeys {
  Kokkos::View<const Contact*, Mem> c;
  Kokkos::View<uint64_t*, Mem> keys;
  Kokkos::View<uint32_t*, Mem> order;
  Kokkos::View<SignedContact*, Mem> signed_contacts;
  int bits, points;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const Contact ci = c(i);
    const ContactPoints e = contact_points(ci);
    SignedContact sc;
    for (int j = 0; j < 3; ++j) sc.b[j] = j < e.size ? e.sign * ci.b[e.slot[j]] : 0.0;
    sc.n = e.sign * ci.n;
    sc.r = ci.r;
    signed_contacts(i) = sc;
    uint64_t key = kAlone;
    if (bits > 0 && (e.size == 2 || e.size == 3)) {
      const uint64_t none = (uint64_t(1) << bits) - 1;  // the third point of a pair
      key = 0;
      for (int j = 0; j < 3; ++j) {
        const int p = j < e.size ? ci.p[e.slot[j]] : 0;
        const uint64_t u = j < e.size ? uint64_t(p >= 0 ? p : points - 1 - p) : none;
        key |= u << (j * bits);
      }
    }
    keys(i) = key;
    order(i) = uint32_t(i);
  }
};

// 1 where a row starts in the sorted order.
template <class Mem>
struct RowStarts {
  Kokkos::View<const uint64_t*, Mem> keys;
  Kokkos::View<long*, Mem> start;
  KOKKOS_INLINE_FUNCTION void operator()(long j) const {
    start(j) = j == 0 || keys(j) == kAlone || keys(j) != keys(j - 1) ? 1 : 0;
  }
};

template <class Mem>
struct RowFirst {
  Kokkos::View<const uint64_t*, Mem> keys;
  Kokkos::View<const long*, Mem> row;  // exclusive scan of RowStarts
  Kokkos::View<long*, Mem> first;
  KOKKOS_INLINE_FUNCTION void operator()(long j) const {
    if (j == 0 || keys(j) == kAlone || keys(j) != keys(j - 1)) first(row(j)) = j;
  }
};

// One row per run of equal keys: the members' b and n (signed alike) averaged in contact order, their
// separation the largest, friction and layer shock those of the first.
template <class Mem>
struct MergeRows {
  Kokkos::View<const Contact*, Mem> c;
  Kokkos::View<const SignedContact*, Mem> signed_contacts;
  Kokkos::View<const uint32_t*, Mem> order;
  Kokkos::View<const long*, Mem> first;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<Vec3*, Mem> xs, cxs;
  Kokkos::View<JacobiRow*, Mem> rows;
  long nrows, n;
  KOKKOS_INLINE_FUNCTION void operator()(long g) const {
    const long lo = first(g), hi = g + 1 < nrows ? first(g + 1) : n;
    const Contact c0 = c(order(lo));
    if (hi - lo == 1) {
      rows(g) = row_of(c0, w, xs, cxs, 1);
      return;
    }
    const ContactPoints e0 = contact_points(c0);
    Contact m = c0;
    for (int k = 0; k < 4; ++k) {
      m.p[k] = k < e0.size ? c0.p[e0.slot[k]] : -1;
      m.wscale[k] = k < e0.size ? c0.wscale[e0.slot[k]] : 1;
      m.b[k] = 0;
    }
    Vec3 nsum{};
    for (long j = lo; j < hi; ++j) {
      const SignedContact& cj = signed_contacts(order(j));
      for (int k = 0; k < 3; ++k) m.b[k] += cj.b[k];
      nsum += cj.n;
      m.r = max_(m.r, cj.r);
    }
    const real count = real(hi - lo);
    for (int k = 0; k < e0.size; ++k) m.b[k] /= count;
    const real len = norm(nsum);
    m.n = len > 0 ? nsum / len : e0.sign * c0.n;
    rows(g) = row_of(m, w, xs, cxs, int(hi - lo));
  }
};

template <class Mem>
struct PrepareRows {
  Kokkos::View<const Contact*, Mem> c;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<Vec3*, Mem> xs, cxs;
  Kokkos::View<JacobiRow*, Mem> rows;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { rows(i) = row_of(c(i), w, xs, cxs, 1); }
};

// Per row: its corrections, added to its points' sums; acc(p, 0) counts the contributions in its low bits.
template <class Mem>
struct ContactDeltas {
  Kokkos::View<const JacobiRow*, Mem> rows;
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<Vec3*, Mem> cx;
  Kokkos::View<Fixed* [3], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const JacobiRow& c = rows(i);
    Vec3 xk[4], sum{};
    for (int k = 0; k < 4; ++k)
      if (c.b[k] != 0) {
        xk[k] = contact_point_pos(c.p[k], x, cx);
        sum += c.b[k] * xk[k];
      }
    const real C = dot(c.n, sum) - c.r;
    if (!(C < 0)) return;
    Vec3 v = -C * c.n;
    // Friction from the positions before the normal step: that step moves the sides along n only, so the
    // tangential displacement is the one Gauss-Seidel sees after it.
    if (c.mu_s > 0 || c.mu_d > 0) {
      Vec3 corr;
      if (friction_correction(c.n, c.mu_s, c.mu_d, sum - c.start, -C, corr)) v += corr;
    }
    for (int k = 0; k < 4; ++k) {
      if (c.f[k] == 0) continue;
      const Vec3 dk = c.f[k] * v;
      const int p = c.p[k];
      const Fixed m = Fixed(c.count);  // the row's contacts, each the same correction
      Kokkos::atomic_add(&acc(p, 0), ((to_fixed(dk.x) * m) << kCountBits) + m);
      Kokkos::atomic_add(&acc(p, 1), to_fixed(dk.y) * m);
      Kokkos::atomic_add(&acc(p, 2), to_fixed(dk.z) * m);
    }
  }
};

// Per point: the average of its corrections; the sums are cleared for the next iteration.
template <class Mem>
struct ApplyDeltas {
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<Fixed* [3], Mem> acc;
  KOKKOS_INLINE_FUNCTION void operator()(long p) const {
    const Fixed sx = acc(p, 0), sy = acc(p, 1), sz = acc(p, 2);
    if ((sx | sy | sz) == 0) return;
    for (int k = 0; k < 3; ++k) acc(p, k) = 0;  // even past the count's limit, nothing carries over
    const Fixed n = sx & ((Fixed(1) << kCountBits) - 1);
    if (n == 0) return;
    const real s = kFixedScale * real(n);
    const real vx = real((long long)(sx - n) >> kCountBits);  // arithmetic shift: the sum's sign stays
    x(p) += Vec3{vx / s, from_fixed(sy) / s, from_fixed(sz) / s};
  }
};

// Nothing after a point's corrections.
struct NoPointStep {
  KOKKOS_INLINE_FUNCTION void operator()(long) const {}
};

// A point's corrections, then `then` on the point (the proximity model's cut back to its bound): one launch.
template <class Mem, class Then>
struct ApplyThen {
  ApplyDeltas<Mem> apply;
  Then then;
  KOKKOS_INLINE_FUNCTION void operator()(long p) const {
    apply(p);
    then(p);
  }
};

}  // namespace jacobi_detail

template <class Exec>
class JacobiContacts {
 public:
  using Mem = typename Exec::memory_space;

  explicit JacobiContacts(bool merge = true) : merge_(merge) {}

  // The contacts were written anew: the next iteration builds its rows first.
  void contacts_changed() { stale_ = true; }

  // Rows the last iterations ran over (after merging).
  long rows() const { return nrows_; }

  // One Jacobi iteration over contacts [0, n), then then(p) for every point p in the same launch as the
  // corrections (a step of each point's own, which so costs no launch of its own).
  template <class Then = jacobi_detail::NoPointStep>
  void project(const Exec& exec, const Kokkos::View<Contact*, Mem>& c, long n, const Kokkos::View<Vec3*, Mem>& x,
               const Kokkos::View<Vec3*, Mem>& xs, const Kokkos::View<real*, Mem>& w,
               const Kokkos::View<Vec3*, Mem>& cx, const Kokkos::View<Vec3*, Mem>& cxs, const Then& then = Then{}) {
    using namespace jacobi_detail;
    constexpr bool step = !std::is_same_v<Then, NoPointStep>;
    if (n == 0) {
      if (step) Kokkos::parallel_for("weft::bounds_truncate", Kokkos::RangePolicy<Exec>(exec, 0, long(x.extent(0))), then);
      return;
    }
    if (stale_) {
      build_rows(exec, c, n, w, xs, cxs, long(x.extent(0)), long(cx.extent(0)));
      stale_ = false;
    }
    const long points = long(x.extent(0));
    if (long(acc_.extent(0)) != points) acc_ = Kokkos::View<Fixed* [3], Mem>("weft::contact_sums", points);
    Kokkos::parallel_for("weft::contact_deltas", Kokkos::RangePolicy<Exec>(exec, 0, nrows_),
                         ContactDeltas<Mem>{rows_, x, cx, acc_});
    Kokkos::parallel_for("weft::contact_apply", Kokkos::RangePolicy<Exec>(exec, 0, points),
                         ApplyThen<Mem, Then>{ApplyDeltas<Mem>{x, acc_}, then});
  }

 private:
  template <class T>
  static void grow(Kokkos::View<T*, Mem>& v, long n, const char* label) {
    if (long(v.extent(0)) < n)
      v = Kokkos::View<T*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)), n + n / 2);
  }

  void build_rows(const Exec& exec, const Kokkos::View<Contact*, Mem>& c, long n, const Kokkos::View<real*, Mem>& w,
                  const Kokkos::View<Vec3*, Mem>& xs, const Kokkos::View<Vec3*, Mem>& cxs, long points,
                  long collider_points) {
    using namespace jacobi_detail;
    grow(rows_, n, "weft::contact_rows");
    int bits = 1;
    while ((long(1) << bits) <= points + collider_points) ++bits;  // and one value more: a pair's third point
    if (!merge_ || 3 * bits > 63) {
      Kokkos::parallel_for("weft::contact_rows", Kokkos::RangePolicy<Exec>(exec, 0, n), PrepareRows<Mem>{c, w, xs, cxs, rows_});
      nrows_ = n;
      return;
    }
    grow(keys_, n, "weft::contact_keys");
    grow(order_, n, "weft::contact_order");
    grow(start_, n, "weft::contact_row_start");
    grow(first_, n, "weft::contact_row_first");
    grow(signed_, n, "weft::contact_signed");
    const auto range = std::make_pair(0L, n);
    const auto keys = Kokkos::subview(keys_, range);
    const auto order = Kokkos::subview(order_, range);
    const auto start = Kokkos::subview(start_, range);
    Kokkos::parallel_for("weft::contact_keys", Kokkos::RangePolicy<Exec>(exec, 0, n),
                         ContactKeys<Mem>{c, keys_, order_, signed_, bits, int(points)});
    radix_sort_pairs(exec, keys, order, 3 * bits, sort_scratch_);
    Kokkos::parallel_for("weft::contact_row_starts", Kokkos::RangePolicy<Exec>(exec, 0, n), RowStarts<Mem>{keys_, start_});
    nrows_ = long(exclusive_scan(exec, start, start));
    Kokkos::parallel_for("weft::contact_row_first", Kokkos::RangePolicy<Exec>(exec, 0, n), RowFirst<Mem>{keys_, start_, first_});
    Kokkos::parallel_for("weft::contact_merge", Kokkos::RangePolicy<Exec>(exec, 0, nrows_),
                         MergeRows<Mem>{c, signed_, order_, first_, w, xs, cxs, rows_, nrows_, n});
  }

  bool merge_;
  bool stale_ = true;
  long nrows_ = 0;
  Kokkos::View<jacobi_detail::JacobiRow*, Mem> rows_{"weft::contact_rows", 0};
  Kokkos::View<uint64_t*, Mem> keys_{"weft::contact_keys", 0};
  Kokkos::View<uint32_t*, Mem> order_{"weft::contact_order", 0};
  Kokkos::View<long*, Mem> start_{"weft::contact_row_start", 0}, first_{"weft::contact_row_first", 0};
  Kokkos::View<jacobi_detail::SignedContact*, Mem> signed_{"weft::contact_signed", 0};
  RadixScratch<Mem> sort_scratch_;
  Kokkos::View<jacobi_detail::Fixed* [3], Mem> acc_{"weft::contact_sums", 0};  // zero between iterations
};

}  // namespace weft
