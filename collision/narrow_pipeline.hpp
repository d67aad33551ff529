// The narrow phase over a list of candidate triangle pairs, as kernels: the cheap tests of every pair's
// feature pairs, the CCD of those left open, one feature pair per thread, then the contacts of each pair
// written at its scanned offset. Splitting the CCD out keeps the per-pair kernel small (on the H200 the
// kernel with the CCD inlined ran at 12% occupancy, limited by its registers) and gives the CCD's long,
// uneven searches threads of their own. Masks are combined with an integer atomic
// OR, which is order-free; counts and lists are count-scan-fill: the contacts come out in pair order, and
// the same bits, on every backend.
#pragma once
#include "collision/lbvh.hpp"  // IndexPair
#include "collision/narrow_phase.hpp"
#include "core/scan.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

namespace narrow_detail {

template <class Mem>
struct TestPairs {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<uint32_t*, Mem> masks, open;  // open: CCD bits, touching bits << 15
  Kokkos::View<long*, Mem> counts;           // CCD jobs of each pair
  NarrowSettings ns;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const FeatureTests t = feature_tests(A, pairs(i).first, B, pairs(i).second, ns);
    masks(i) = t.hit;
    open(i) = t.ccd | (t.touching << 15);
    counts(i) = popcount15(t.ccd);
  }
};

// Job j of a list scanned into offsets[0, n) (offsets(i): item i's first job): the item whose range
// [offsets(i), offsets(i + 1)) holds j, found by bisection, so no list of jobs is stored (a list of owners
// measured no faster on the H200 and took memory).
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

// The k-th set bit of o, counting from 0; o has more than k set bits.
KOKKOS_INLINE_FUNCTION int kth_bit(uint32_t o, long k) {
  int bit = 0;
  for (;; ++bit)
    if (((o >> bit) & 1u) && k-- == 0) return bit;
}

// CCD job j: the k-th open feature bit of its pair.
template <class Mem>
struct RunCcdJobs {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<const uint32_t*, Mem> open;
  Kokkos::View<const long*, Mem> offsets;
  long npairs;
  Kokkos::View<uint32_t*, Mem> masks;
  NarrowSettings ns;
  KOKKOS_INLINE_FUNCTION void operator()(long j) const {
    const long i = job_owner(offsets, npairs, j);
    const uint32_t o = open(i);
    const int bit = kth_bit(o, j - offsets(i));
    if (feature_ccd(A, pairs(i).first, B, pairs(i).second, bit, (o >> (15 + bit)) & 1u, ns))
      Kokkos::atomic_fetch_or(&masks(i), 1u << bit);
  }
};

template <class Mem>
struct CountContacts {
  Kokkos::View<const uint32_t*, Mem> masks;
  Kokkos::View<long*, Mem> counts;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { counts(i) = popcount15(masks(i)); }
};

// Writes each pair's contacts at its scanned offset.
template <class Mem>
struct FillContacts {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<const uint32_t*, Mem> masks;
  Kokkos::View<const long*, Mem> offsets;
  NarrowSettings ns;
  Kokkos::View<Contact*, Mem> out;
  long first;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    if (masks(i)) fill_contacts(A, pairs(i).first, B, pairs(i).second, masks(i), ns, out, first + offsets(i));
  }
};

}  // namespace narrow_detail

// The narrow phase's kernels and working memory. Pairs are taken in chunks, so the working memory stays
// bounded however many candidate pairs a pass has (boxes swept over a whole frame give hundreds per
// triangle).
template <class Exec>
class NarrowPipeline {
 public:
  using Mem = typename Exec::memory_space;
  // chunk: pairs per chunk. Chunks run one after another and each CCD launch lasts as long as its slowest
  // search, so fewer chunks are faster; 16M pairs keep the working memory near 270 MB.
  explicit NarrowPipeline(long chunk = 1L << 24) : chunk_(chunk) {}

  // Contacts of pairs [0, npairs) between sides A and B, written to contacts[first...] (grown as needed,
  // keeping contacts[0, first)); returns how many. Reads two counters per chunk back to the host.
  long run(const Exec& exec, const SideMesh<Mem>& A, const SideMesh<Mem>& B, const NarrowSettings& ns,
           const Kokkos::View<IndexPair*, Mem>& pairs, long npairs, Kokkos::View<Contact*, Mem>& contacts, long first) {
    long total = 0;
    for (long lo = 0; lo < npairs; lo += chunk_) {
      const long n = npairs - lo < chunk_ ? npairs - lo : chunk_;
      total += run_chunk(exec, A, B, ns, Kokkos::subview(pairs, std::make_pair(lo, lo + n)), n, contacts, first + total);
    }
    return total;
  }

 private:
  long run_chunk(const Exec& exec, const SideMesh<Mem>& A, const SideMesh<Mem>& B, const NarrowSettings& ns,
                 const Kokkos::View<const IndexPair*, Mem>& pairs, long n, Kokkos::View<Contact*, Mem>& contacts,
                 long first) {
    using namespace narrow_detail;
    grow(masks_, n);
    grow(open_, n);
    grow(counts_, n);
    const auto range = Kokkos::RangePolicy<Exec>(exec, 0, n);
    const auto counts = Kokkos::subview(counts_, std::make_pair(0L, n));
    Kokkos::parallel_for("weft::narrow_tests", range, TestPairs<Mem>{A, B, pairs, masks_, open_, counts_, ns});
    const long njobs = long(exclusive_scan(exec, counts, counts));
    if (njobs > 0)
      Kokkos::parallel_for("weft::narrow_ccd", Kokkos::RangePolicy<Exec>(exec, 0, njobs),
                           RunCcdJobs<Mem>{A, B, pairs, open_, counts_, n, masks_, ns});
    Kokkos::parallel_for("weft::narrow_count", range, CountContacts<Mem>{masks_, counts_});
    const long total = long(exclusive_scan(exec, counts, counts));
    if (long(contacts.extent(0)) < first + total) {
      Kokkos::View<Contact*, Mem> bigger(Kokkos::view_alloc(Kokkos::WithoutInitializing, contacts.label()),
                                         (first + total) * 3 / 2 + 64);
      if (first > 0)
        Kokkos::deep_copy(exec, Kokkos::subview(bigger, std::make_pair(0L, first)),
                          Kokkos::subview(contacts, std::make_pair(0L, first)));
      contacts = bigger;
    }
    Kokkos::parallel_for("weft::narrow_fill", range, FillContacts<Mem>{A, B, pairs, masks_, counts_, ns, contacts, first});
    return total;
  }

  // Grown with slack up to one chunk, never shrunk.
  template <class V>
  void grow(V& v, long n) const {
    if (long(v.extent(0)) < n) {
      const long size = n + n / 2 + 16;
      v = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label()), size < chunk_ ? size : chunk_);
    }
  }

  long chunk_;
  Kokkos::View<uint32_t*, Mem> masks_{"weft::narrow_masks", 0}, open_{"weft::narrow_open", 0};
  Kokkos::View<long*, Mem> counts_{"weft::narrow_counts", 0};
};

}  // namespace weft
