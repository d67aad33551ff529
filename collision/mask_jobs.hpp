// Work lists over per-item bit masks without a list: job j is the j-th set bit of masks[0, n) in item order.
// The bits are counted per block of kMaskBlock items and the counts scanned over the blocks, so the scan
// runs over n / 32 numbers instead of n. A job finds its item by bisecting the block offsets and walking
// its block; an item finds its first job from its block's offset and the bits of the items before it in
// the block. Integer counts only: the numbering is the same on every backend.
#pragma once
#include "core/scan.hpp"

#include <Kokkos_Core.hpp>
#include <cstdint>

namespace weft {

constexpr long kMaskBlock = 32;

KOKKOS_INLINE_FUNCTION int popcount32(uint32_t m) {
  int c = 0;
  for (; m; m &= m - 1) ++c;
  return c;
}

// The k-th set bit of o, counting from 0; o has more than k set bits.
KOKKOS_INLINE_FUNCTION int kth_bit(uint32_t o, long k) {
  int bit = 0;
  for (;; ++bit)
    if (((o >> bit) & 1u) && k-- == 0) return bit;
}

// Job j of a list scanned into offsets[0, n) (offsets(i): item i's first job): the item whose range
// [offsets(i), offsets(i + 1)) holds j, found by bisection.
template <class Offsets>
KOKKOS_INLINE_FUNCTION long job_owner(const Offsets& offsets, long n, long j) {
  long lo = 0, hi = n;  // offsets(lo) <= j, and j < offsets(hi) when hi < n
  while (hi - lo > 1) {
    const long mid = lo + (hi - lo) / 2;
    if (offsets(mid) <= j) lo = mid;
    else hi = mid;
  }
  return lo;
}

// The bits `select` keeps of masks[0, n), with their per-block offsets (after count_mask_jobs).
template <class Mem>
struct MaskJobs {
  Kokkos::View<const uint32_t*, Mem> masks;
  Kokkos::View<const long*, Mem> offsets;  // per block
  long n;
  uint32_t select;

  KOKKOS_INLINE_FUNCTION uint32_t bits(long i) const { return masks(i) & select; }

  // Job j: its item, and the bit it stands for.
  KOKKOS_INLINE_FUNCTION long item(long j, int& bit) const {
    const long nb = (n + kMaskBlock - 1) / kMaskBlock;
    const long b = job_owner(offsets, nb, j);
    long r = j - offsets(b);
    for (long i = b * kMaskBlock;; ++i) {
      const uint32_t m = bits(i);
      const int c = popcount32(m);
      if (r < c) {
        bit = kth_bit(m, r);
        return i;
      }
      r -= c;
    }
  }

  // The first job of item i.
  KOKKOS_INLINE_FUNCTION long first(long i) const {
    long o = offsets(i / kMaskBlock);
    for (long t = i - i % kMaskBlock; t < i; ++t) o += popcount32(bits(t));
    return o;
  }
};

namespace mask_jobs_detail {

template <class Mem>
struct BlockBits {
  Kokkos::View<const uint32_t*, Mem> masks;
  Kokkos::View<long*, Mem> counts;
  long n;
  uint32_t select;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kMaskBlock, hi = lo + kMaskBlock < n ? lo + kMaskBlock : n;
    long c = 0;
    for (long i = lo; i < hi; ++i) c += popcount32(masks(i) & select);
    counts(b) = c;
  }
};

}  // namespace mask_jobs_detail

// Counts and scans the selected bits of masks[0, n) per block into offsets (grown to n / 32 + 1 as needed);
// returns the jobs and their lookup. Reads the total back to the host.
template <class Exec>
long count_mask_jobs(const Exec& exec, const Kokkos::View<uint32_t*, typename Exec::memory_space>& masks, long n,
                     uint32_t select, Kokkos::View<long*, typename Exec::memory_space>& offsets,
                     MaskJobs<typename Exec::memory_space>& jobs) {
  using Mem = typename Exec::memory_space;
  const long nb = (n + kMaskBlock - 1) / kMaskBlock;
  if (long(offsets.extent(0)) < nb)
    offsets = Kokkos::View<long*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, offsets.label()), nb + nb / 2 + 16);
  Kokkos::parallel_for("weft::mask_job_blocks", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                       mask_jobs_detail::BlockBits<Mem>{masks, offsets, n, select});
  const auto blocks = Kokkos::subview(offsets, std::make_pair(0L, nb));
  const long total = long(exclusive_scan(exec, blocks, blocks));
  jobs = MaskJobs<Mem>{masks, offsets, n, select};
  return total;
}

}  // namespace weft
