// Impact-zone Laplacian smoothing (paper 2.3, Fig. 3/4): after the last collision pass of a substep, the
// contacts still violating C < -epsilon r are grouped into connected components over their cloth points
// (labels: the smallest point index, by integer atomic min until nothing changes), and the velocities of
// their points are smoothed along the contacts for a fixed number of Jacobi sweeps: each contact takes the
// mean velocity of its points, each point the mean of its own velocity and those of its contacts. Sums run
// in contact order, so the result is the same on every backend.
#pragma once
#include "collision/contact.hpp"
#include "core/scan.hpp"
#include "core/sort.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

struct ImpactZoneStats {
  long contacts = 0;  // violating contacts
  long points = 0;    // cloth points in impact zones
  long zones = 0;     // connected components
};

template <class Exec>
class ImpactZones {
 public:
  using Mem = typename Exec::memory_space;

  template <class XView, class CView, class VView>
  ImpactZoneStats smooth(const Exec& exec, const Kokkos::View<Contact*, Mem>& contacts, long n, const XView& x,
                         const CView& cx, const VView& v, real epsilon, int sweeps) {
    ImpactZoneStats st;
    const long np = long(x.extent(0));
    if (n == 0 || sweeps <= 0) return st;
    grow(count_, n + 1);
    auto c = contacts;
    auto cnt = count_;
    // Entries (point, contact) of violating contacts' movable points.
    Kokkos::parallel_for("weft::iz_count", Kokkos::RangePolicy<Exec>(exec, 0, n), KOKKOS_LAMBDA(long i) {
      long k = 0;
      if (contact_value(c(i), x, cx) < -epsilon * c(i).r)
        for (int s = 0; s < 4; ++s) k += (c(i).p[s] >= 0 && c(i).b[s] != 0) ? 1 : 0;
      cnt(i) = k;
    });
    const long entries = long(exclusive_scan(exec, Kokkos::subview(cnt, std::make_pair(0L, n)), cnt));
    if (entries == 0) return st;
    grow(keys_, entries);
    grow(vals_, entries);
    grow(first_, np + 1);
    grow(cbar_, n);
    grow(label_, np);
    auto keys = keys_;
    auto vals = vals_;
    Kokkos::parallel_for("weft::iz_fill", Kokkos::RangePolicy<Exec>(exec, 0, n), KOKKOS_LAMBDA(long i) {
      long o = cnt(i);
      const long end = i + 1 < n ? cnt(i + 1) : entries;
      for (int s = 0; s < 4 && o < end; ++s)
        if (c(i).p[s] >= 0 && c(i).b[s] != 0) { keys(o) = uint64_t(c(i).p[s]) << 32 | uint64_t(o); vals(o) = uint32_t(i); ++o; }
    });
    Kokkos::View<uint64_t*, Mem> ks = Kokkos::subview(keys, std::make_pair(0L, entries));
    Kokkos::View<uint32_t*, Mem> vs = Kokkos::subview(vals, std::make_pair(0L, entries));
    radix_sort_pairs(exec, ks, vs, 64);
    // first(p) = first entry of point p, -1 when p is in no zone; first(np) unused.
    auto first = first_;
    Kokkos::deep_copy(exec, first, -1L);
    Kokkos::parallel_for("weft::iz_first", Kokkos::RangePolicy<Exec>(exec, 0, entries), KOKKOS_LAMBDA(long e) {
      const long p = long(ks(e) >> 32);
      if (e == 0 || long(ks(e - 1) >> 32) != p) first(p) = e;
    });
    // Components, for the statistics.
    auto label = label_;
    Kokkos::parallel_for("weft::iz_label_init", Kokkos::RangePolicy<Exec>(exec, 0, np),
                         KOKKOS_LAMBDA(long p) { label(p) = int(p); });
    for (long changed = 1; changed > 0;) {
      changed = 0;
      Kokkos::parallel_reduce(
          "weft::iz_label", Kokkos::RangePolicy<Exec>(exec, 0, n),
          KOKKOS_LAMBDA(long i, long& acc) {
            const long end = i + 1 < n ? cnt(i + 1) : entries;
            if (end == cnt(i)) return;
            int m = 0x7fffffff;
            for (int s = 0; s < 4; ++s)
              if (c(i).p[s] >= 0 && c(i).b[s] != 0) m = label(c(i).p[s]) < m ? label(c(i).p[s]) : m;
            for (int s = 0; s < 4; ++s)
              if (c(i).p[s] >= 0 && c(i).b[s] != 0 && Kokkos::atomic_fetch_min(&label(c(i).p[s]), m) > m) ++acc;
          },
          changed);
    }
    Kokkos::parallel_reduce(
        "weft::iz_zones", Kokkos::RangePolicy<Exec>(exec, 0, np),
        KOKKOS_LAMBDA(long p, long& z) { z += (first(p) >= 0 && label(p) == int(p)) ? 1 : 0; }, st.zones);
    Kokkos::parallel_reduce(
        "weft::iz_points", Kokkos::RangePolicy<Exec>(exec, 0, np),
        KOKKOS_LAMBDA(long p, long& z) { z += first(p) >= 0 ? 1 : 0; }, st.points);
    Kokkos::parallel_reduce(
        "weft::iz_contacts", Kokkos::RangePolicy<Exec>(exec, 0, n),
        KOKKOS_LAMBDA(long i, long& z) { z += ((i + 1 < n ? cnt(i + 1) : entries) > cnt(i)) ? 1 : 0; }, st.contacts);
    // Jacobi sweeps of Laplacian smoothing.
    auto cbar = cbar_;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      Kokkos::parallel_for("weft::iz_contact_mean", Kokkos::RangePolicy<Exec>(exec, 0, n), KOKKOS_LAMBDA(long i) {
        const long end = i + 1 < n ? cnt(i + 1) : entries;
        if (end == cnt(i)) return;
        Vec3 s{};
        int k = 0;
        for (int q = 0; q < 4; ++q)
          if (c(i).p[q] >= 0 && c(i).b[q] != 0) { s += v(c(i).p[q]); ++k; }
        cbar(i) = s / real(k);
      });
      Kokkos::parallel_for("weft::iz_point_mean", Kokkos::RangePolicy<Exec>(exec, 0, np), KOKKOS_LAMBDA(long p) {
        const long e0 = first(p);
        if (e0 < 0) return;
        Vec3 s = v(p);
        long k = 1;
        for (long e = e0; e < entries && long(ks(e) >> 32) == p; ++e, ++k) s += cbar(vs(e));
        v(p) = s / real(k);
      });
    }
    return st;
  }

 private:
  template <class V>
  static void grow(V& v, long n) {
    if (long(v.extent(0)) < n) v = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label()), n + n / 2 + 16);
  }
  Kokkos::View<long*, Mem> count_{"weft::iz_count", 0}, first_{"weft::iz_first", 0};
  Kokkos::View<uint64_t*, Mem> keys_{"weft::iz_keys", 0};
  Kokkos::View<uint32_t*, Mem> vals_{"weft::iz_vals", 0};
  Kokkos::View<Vec3*, Mem> cbar_{"weft::iz_cbar", 0};
  Kokkos::View<int*, Mem> label_{"weft::iz_label", 0};
};

}  // namespace weft
