// Exclusive scans of integers (exact, so any parallel order gives the same result).
#pragma once
#include <Kokkos_Core.hpp>

namespace weft {

template <class In, class Out, class T>
struct ExclusiveScan {
  In in;
  Out out;
  KOKKOS_INLINE_FUNCTION void operator()(long i, T& acc, bool final) const {
    const T v = in(i);
    if (final) out(i) = acc;
    acc += v;
  }
};

// out[i] = sum of in[0..i); returns the total. in and out may be the same View.
template <class Exec, class InView, class OutView>
typename OutView::non_const_value_type exclusive_scan(const Exec& exec, const InView& in, const OutView& out) {
  using T = typename OutView::non_const_value_type;
  const long n = static_cast<long>(in.extent(0));
  T total = 0;
  Kokkos::parallel_scan("weft::exclusive_scan", Kokkos::RangePolicy<Exec>(exec, 0, n),
                        ExclusiveScan<InView, OutView, T>{in, out}, total);
  return total;
}

// out[i] = sum of in[0..i), without reading the total back: for callers that know it already.
template <class Exec, class InView, class OutView>
void exclusive_scan_on_device(const Exec& exec, const InView& in, const OutView& out) {
  using T = typename OutView::non_const_value_type;
  Kokkos::parallel_scan("weft::exclusive_scan", Kokkos::RangePolicy<Exec>(exec, 0, static_cast<long>(in.extent(0))),
                        ExclusiveScan<InView, OutView, T>{in, out});
}

}  // namespace weft
