// Compaction without atomics: count per item, exclusive scan, then each item fills its own range.
// The output order is the item order, whatever the backend.
#pragma once
#include "core/scan.hpp"

namespace weft {

template <class Offsets, class Count>
struct CountInto {
  Offsets offsets;
  Count count;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { offsets(i) = count(i); }
};

template <class Offsets, class Fill>
struct FillFrom {
  Offsets offsets;
  Fill fill;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { fill(i, offsets(i)); }
};

// count(i) -> number of outputs of item i; fill(i, first) writes them at [first, first + count(i)).
// Returns the total. offsets must hold at least n entries; the first n are overwritten.
template <class Exec, class Count, class Fill, class OffsetView>
long count_scan_fill(const Exec& exec, long n, const OffsetView& offsets, Count count, Fill fill) {
  Kokkos::parallel_for("weft::count", Kokkos::RangePolicy<Exec>(exec, 0, n), CountInto<OffsetView, Count>{offsets, count});
  const auto head = Kokkos::subview(offsets, std::make_pair(0L, n));
  const long total = static_cast<long>(exclusive_scan(exec, head, head));
  Kokkos::parallel_for("weft::fill", Kokkos::RangePolicy<Exec>(exec, 0, n), FillFrom<OffsetView, Fill>{offsets, fill});
  return total;
}

}  // namespace weft
