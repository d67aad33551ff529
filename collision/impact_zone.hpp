// Impact-zone Laplacian smoothing (paper 2.3, Fig. 3/4): after the last collision pass of a substep, the
// velocities of the points of contacts still violating C < -epsilon r are smoothed along those contacts for
// a fixed number of Jacobi sweeps: each contact takes the mean velocity of its points, each point the mean
// of its own velocity and those of its contacts. A zone is a connected set of such contacts; the sweeps
// need no labels for it, since velocity only flows along contacts. Sums run in contact order, so the result
// is the same on every backend.
#pragma once
#include "collision/contact.hpp"
#include "core/scan.hpp"
#include "core/sort.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

struct ImpactZoneStats {
  long points = 0;  // cloth points in impact zones
};

namespace impact_zone_detail {

// The kernels, as named functors (docs/solver.md, "Kernels are functors"). A contact's entries are
// [cnt(i), end(i)): one per movable point of a violating contact.
template <class Mem>
struct Entries {
  Kokkos::View<Contact*, Mem> c;
  Kokkos::View<long*, Mem> cnt;
  long n, entries;
  KOKKOS_INLINE_FUNCTION long end(long i) const { return i + 1 < n ? cnt(i + 1) : entries; }
  KOKKOS_INLINE_FUNCTION bool moves(long i, int s) const { return c(i).p[s] >= 0 && c(i).b[s] != 0; }
};

template <class Mem>
struct CountEntries {
  Kokkos::View<Contact*, Mem> c;
  Kokkos::View<Vec3*, Mem> x, cx;
  Kokkos::View<long*, Mem> cnt;
  real epsilon;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    long k = 0;
    if (contact_value(c(i), x, cx) < -epsilon * c(i).r)
      for (int s = 0; s < 4; ++s) k += (c(i).p[s] >= 0 && c(i).b[s] != 0) ? 1 : 0;
    cnt(i) = k;
  }
};

// Entry keys: the point. Entries are written in contact order, and the sort is stable, so sorting the
// points alone gives the order of the unique keys (point, entry) in the fewest passes: each point's contacts
// grouped, in contact order.
template <class Mem>
struct FillEntries : Entries<Mem> {
  Kokkos::View<uint64_t*, Mem> keys;
  Kokkos::View<uint32_t*, Mem> vals;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    long o = this->cnt(i);
    const long e = this->end(i);
    for (int s = 0; s < 4 && o < e; ++s)
      if (this->moves(i, s)) {
        keys(o) = uint64_t(this->c(i).p[s]);
        vals(o) = uint32_t(i);
        ++o;
      }
  }
};

// first(p) and last(p): point p's entries are [first(p), last(p)).
template <class Mem>
struct FirstEntry {
  Kokkos::View<uint64_t*, Mem> ks;
  Kokkos::View<long*, Mem> first, last;
  long entries;
  KOKKOS_INLINE_FUNCTION void operator()(long e) const {
    const long p = long(ks(e));
    if (e == 0 || long(ks(e - 1)) != p) first(p) = e;
    if (e + 1 == entries || long(ks(e + 1)) != p) last(p) = e + 1;
  }
};

template <class Mem>
struct CountZonePoints {
  Kokkos::View<long*, Mem> first;
  KOKKOS_INLINE_FUNCTION void operator()(long p, long& z) const { z += first(p) >= 0 ? 1 : 0; }
};

// Jacobi sweep, first half: each violating contact takes the mean velocity of its points.
template <class Mem>
struct ContactMean : Entries<Mem> {
  Kokkos::View<Vec3*, Mem> v, cbar;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    if (this->end(i) == this->cnt(i)) return;
    Vec3 s{};
    int k = 0;
    for (int q = 0; q < 4; ++q)
      if (this->moves(i, q)) { s += v(this->c(i).p[q]); ++k; }
    cbar(i) = s / real(k);
  }
};

// Second half: each point takes the mean of its own velocity and its contacts', in contact order. Four
// contacts' means are loaded before they are added, in order: a point of a jammed rope has a hundred or
// more, and one dependent load after another made this the longest kernel of the twist's substep.
template <class Mem>
struct PointMean {
  Kokkos::View<long*, Mem> first, last;
  Kokkos::View<uint32_t*, Mem> vs;
  Kokkos::View<Vec3*, Mem> v, cbar;
  KOKKOS_INLINE_FUNCTION void operator()(long p) const {
    const long e0 = first(p);
    if (e0 < 0) return;
    const long e1 = last(p);
    Vec3 s = v(p);
    long e = e0;
    for (; e + 4 <= e1; e += 4) {
      const Vec3 a = cbar(vs(e)), b = cbar(vs(e + 1)), c = cbar(vs(e + 2)), d = cbar(vs(e + 3));
      s += a;
      s += b;
      s += c;
      s += d;
    }
    for (; e < e1; ++e) s += cbar(vs(e));
    v(p) = s / real(1 + e1 - e0);
  }
};

}  // namespace impact_zone_detail

template <class Exec>
class ImpactZones {
 public:
  using Mem = typename Exec::memory_space;
  using Points = Kokkos::View<Vec3*, Mem>;

  ImpactZoneStats smooth(const Exec& exec, const Kokkos::View<Contact*, Mem>& c, long n, const Points& x,
                         const Points& cx, const Points& v, real epsilon, int sweeps) {
    using namespace impact_zone_detail;
    using Range = Kokkos::RangePolicy<Exec>;
    ImpactZoneStats st;
    const long np = long(x.extent(0));
    if (n == 0 || sweeps <= 0) return st;
    grow(count_, n + 1);
    const auto cnt = count_;
    Kokkos::parallel_for("weft::iz_count", Range(exec, 0, n), CountEntries<Mem>{c, x, cx, cnt, epsilon});
    const long entries = long(exclusive_scan(exec, Kokkos::subview(cnt, std::make_pair(0L, n)), cnt));
    if (entries == 0) return st;
    grow(keys_, entries);
    grow(vals_, entries);
    grow(first_, np + 1);
    grow(last_, np + 1);
    grow(cbar_, n);
    const Entries<Mem> en{c, cnt, n, entries};
    Kokkos::parallel_for("weft::iz_fill", Range(exec, 0, n), FillEntries<Mem>{en, keys_, vals_});
    Kokkos::View<uint64_t*, Mem> ks = Kokkos::subview(keys_, std::make_pair(0L, entries));
    Kokkos::View<uint32_t*, Mem> vs = Kokkos::subview(vals_, std::make_pair(0L, entries));
    int point_bits = 1;
    while ((long(1) << point_bits) < np) ++point_bits;
    radix_sort_pairs(exec, ks, vs, point_bits, sort_scratch_);
    // first(p) = first entry of point p, -1 when p is in no zone; first(np) unused.
    Kokkos::deep_copy(exec, first_, -1L);
    Kokkos::parallel_for("weft::iz_first", Range(exec, 0, entries), FirstEntry<Mem>{ks, first_, last_, entries});
    Kokkos::parallel_reduce("weft::iz_points", Range(exec, 0, np), CountZonePoints<Mem>{first_}, st.points);
    // Jacobi sweeps of Laplacian smoothing.
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      Kokkos::parallel_for("weft::iz_contact_mean", Range(exec, 0, n), ContactMean<Mem>{en, v, cbar_});
      Kokkos::parallel_for("weft::iz_point_mean", Range(exec, 0, np), PointMean<Mem>{first_, last_, vs, v, cbar_});
    }
    return st;
  }

 private:
  template <class V>
  static void grow(V& v, long n) {
    if (long(v.extent(0)) < n) v = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label()), n + n / 2 + 16);
  }
  Kokkos::View<long*, Mem> count_{"weft::iz_count", 0}, first_{"weft::iz_first", 0}, last_{"weft::iz_last", 0};
  Kokkos::View<uint64_t*, Mem> keys_{"weft::iz_keys", 0};
  Kokkos::View<uint32_t*, Mem> vals_{"weft::iz_vals", 0};
  Kokkos::View<Vec3*, Mem> cbar_{"weft::iz_cbar", 0};
  RadixScratch<Mem> sort_scratch_;
};

}  // namespace weft
