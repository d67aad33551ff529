// Stable LSD radix sort of (uint64 key, uint32 value) pairs, kSortBits bits a pass. Each block of kSortBlock
// items counts its digits, an integer scan over (digit, block) gives every block its output ranges, and
// each block scatters its items in order. The result is the unique stable order, on every backend.
// A block is one thread's serial work: 4-bit digits in blocks of 64 make it 96 steps (16 counters cleared
// and written out, 64 items), where 8-bit digits in blocks of 256 made it 768, which left the device
// waiting on a few long threads (an impact-zone sort of 30K entries took 0.4 ms on an H200).
#pragma once
#include "core/scan.hpp"

#include <Kokkos_Core.hpp>
#include <cstdint>

namespace weft {

inline constexpr int kSortBlock = 64;
inline constexpr int kSortBits = 4;
inline constexpr int kSortDigits = 1 << kSortBits;

template <class Mem>
struct RadixCount {
  Kokkos::View<uint64_t*, Mem> ksrc;
  Kokkos::View<long*, Mem> hist;
  long n, nb;
  int shift;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    long c[kSortDigits];
    for (int d = 0; d < kSortDigits; ++d) c[d] = 0;
    const long lo = b * kSortBlock, hi = lo + kSortBlock < n ? lo + kSortBlock : n;
    for (long i = lo; i < hi; ++i) ++c[(ksrc(i) >> shift) & (kSortDigits - 1u)];
    for (int d = 0; d < kSortDigits; ++d) hist(d * nb + b) = c[d];
  }
};

template <class Mem>
struct RadixScatter {
  Kokkos::View<uint64_t*, Mem> ksrc, kdst;
  Kokkos::View<uint32_t*, Mem> vsrc, vdst;
  Kokkos::View<long*, Mem> hist;
  long n, nb;
  int shift;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    long o[kSortDigits];
    for (int d = 0; d < kSortDigits; ++d) o[d] = hist(d * nb + b);
    const long lo = b * kSortBlock, hi = lo + kSortBlock < n ? lo + kSortBlock : n;
    for (long i = lo; i < hi; ++i) {
      const long dst = o[(ksrc(i) >> shift) & (kSortDigits - 1u)]++;
      kdst(dst) = ksrc(i);
      vdst(dst) = vsrc(i);
    }
  }
};

// Working memory of a sort, kept by callers that sort every pass so that no pass allocates.
template <class Mem>
struct RadixScratch {
  Kokkos::View<uint64_t*, Mem> keys{"weft::sort_keys", 0};
  Kokkos::View<uint32_t*, Mem> vals{"weft::sort_vals", 0};
  Kokkos::View<long*, Mem> hist{"weft::sort_hist", 0};
};

// Sorts keys (and values alongside) ascending; only the low key_bits bits of each key are compared.
template <class Exec, class KeyView, class ValView>
void radix_sort_pairs(const Exec& exec, const KeyView& keys, const ValView& vals, int key_bits,
                      RadixScratch<typename Exec::memory_space>& scratch) {
  using Mem = typename Exec::memory_space;
  const long n = static_cast<long>(keys.extent(0));
  if (n < 2) return;
  const long nb = (n + kSortBlock - 1) / kSortBlock;
  if (long(scratch.keys.extent(0)) < n) {
    scratch.keys = Kokkos::View<uint64_t*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::sort_keys"), n);
    scratch.vals = Kokkos::View<uint32_t*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::sort_vals"), n);
  }
  if (long(scratch.hist.extent(0)) < kSortDigits * nb)
    scratch.hist = Kokkos::View<long*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::sort_hist"), kSortDigits * nb);
  const Kokkos::View<uint64_t*, Mem> k2 = Kokkos::subview(scratch.keys, std::make_pair(0L, n));
  const Kokkos::View<uint32_t*, Mem> v2 = Kokkos::subview(scratch.vals, std::make_pair(0L, n));
  const Kokkos::View<long*, Mem> hist = Kokkos::subview(scratch.hist, std::make_pair(0L, kSortDigits * nb));
  Kokkos::View<uint64_t*, Mem> ksrc = keys, kdst = k2;
  Kokkos::View<uint32_t*, Mem> vsrc = vals, vdst = v2;
  int passes = 0;
  for (int shift = 0; shift < key_bits; shift += kSortBits, ++passes) {
    Kokkos::parallel_for("weft::sort_count", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                         RadixCount<Mem>{ksrc, hist, n, nb, shift});
    exclusive_scan(exec, hist, hist);
    Kokkos::parallel_for("weft::sort_scatter", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                         RadixScatter<Mem>{ksrc, kdst, vsrc, vdst, hist, n, nb, shift});
    auto kt = ksrc; ksrc = kdst; kdst = kt;
    auto vt = vsrc; vsrc = vdst; vdst = vt;
  }
  if (passes % 2 == 1) {  // the sorted data sits in the scratch buffers
    Kokkos::deep_copy(exec, keys, ksrc);
    Kokkos::deep_copy(exec, vals, vsrc);
  }
}

template <class Exec, class KeyView, class ValView>
void radix_sort_pairs(const Exec& exec, const KeyView& keys, const ValView& vals, int key_bits = 64) {
  RadixScratch<typename Exec::memory_space> scratch;
  radix_sort_pairs(exec, keys, vals, key_bits, scratch);
}

}  // namespace weft
