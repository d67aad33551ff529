// The narrow phase over a list of candidate triangle pairs, as kernels: the pairs whose hulls stay apart
// dropped (collision/pair_cull.hpp), the cheap tests of every other pair's feature pairs, the CCD of those
// left open, one feature pair per thread, then the contacts of each pair written at its scanned offset.
// Splitting the CCD out keeps the per-pair kernel small (on the H200 the kernel with the CCD inlined ran at
// 12% occupancy, limited by its registers) and gives the CCD's long, uneven searches threads of their own.
// Masks are combined with an integer atomic OR, which is order-free; the CCD jobs and the contacts are
// numbered by scanning their bits per block of pairs (collision/mask_jobs.hpp): the contacts come out in
// pair order, and the same bits, on every backend.
#pragma once
#include "collision/lbvh.hpp"  // IndexPair
#include "collision/mask_jobs.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/pair_cull.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

namespace narrow_detail {

// Bits of `open` per pair: the feature pairs left to the CCD, and those of them whose CCD runs with
// separation 0 (touching) shifted by 15.
constexpr uint32_t kFeatureBits = 0x7FFFu;

template <class Mem>
struct TestPairs {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<uint32_t*, Mem> masks, open;
  NarrowSettings ns;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const FeatureTests t = feature_tests(A, pairs(i).first, B, pairs(i).second, ns);
    masks(i) = t.hit;
    open(i) = t.ccd | (t.touching << 15);
  }
};

// CCD job j: an open feature bit of its pair.
template <class Mem>
struct RunCcdJobs {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  MaskJobs<Mem> jobs;  // over `open`
  Kokkos::View<uint32_t*, Mem> masks;
  NarrowSettings ns;
  KOKKOS_INLINE_FUNCTION void operator()(long j) const {
    int bit = 0;
    const long i = jobs.item(j, bit);
    if (feature_ccd(A, pairs(i).first, B, pairs(i).second, bit, (jobs.masks(i) >> (15 + bit)) & 1u, ns))
      Kokkos::atomic_fetch_or(&masks(i), 1u << bit);
  }
};

// Writes each pair's contacts from its first slot on.
template <class Mem>
struct FillContacts {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  MaskJobs<Mem> slots;  // over the contact masks
  NarrowSettings ns;
  Kokkos::View<Contact*, Mem> out;
  long first;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const uint32_t m = slots.masks(i);
    if (m) fill_contacts(A, pairs(i).first, B, pairs(i).second, m, ns, out, first + slots.first(i));
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

  // The pair cut's working memory, which the crossing fail-safe borrows (it runs between passes).
  PairCull<Exec>& pair_cull() { return cull_; }

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
                 const Kokkos::View<const IndexPair*, Mem>& candidates, long ncandidates,
                 Kokkos::View<Contact*, Mem>& contacts, long first) {
    using namespace narrow_detail;
    // A contact needs its features within detect_scale r (vertex-face), ee_detect_scale r, or within r plus
    // the CCD's tolerance; r is at most the sum of the two triangles' thicknesses.
    long n = 0;
    const auto pairs = cull_.keep(exec, A, B, candidates, ncandidates,
                                  max_(max_(ns.detect_scale, ns.ee_detect_scale), 1 + ns.ccd_tolerance_scale),
                                  ns.ccd.tolerance, n);
    if (n == 0) return 0;
    grow(masks_, n);
    grow(open_, n);
    const auto range = Kokkos::RangePolicy<Exec>(exec, 0, n);
    Kokkos::parallel_for("weft::narrow_tests", range, TestPairs<Mem>{A, B, pairs, masks_, open_, ns});
    MaskJobs<Mem> jobs;
    const long njobs = count_mask_jobs(exec, open_, n, kFeatureBits, offsets_, jobs);
    if (njobs > 0)
      Kokkos::parallel_for("weft::narrow_ccd", Kokkos::RangePolicy<Exec>(exec, 0, njobs),
                           RunCcdJobs<Mem>{A, B, pairs, jobs, masks_, ns});
    return fill(exec, A, B, ns, pairs, n, masks_, contacts, first);
  }

 public:
  // The contacts of pairs[0, n) whose bits `masks` holds (bits as in collision/narrow_phase.hpp), written
  // in pair order to contacts[first...] (grown as needed); returns how many. Reads one counter back.
  long fill(const Exec& exec, const SideMesh<Mem>& A, const SideMesh<Mem>& B, const NarrowSettings& ns,
            const Kokkos::View<const IndexPair*, Mem>& pairs, long n, const Kokkos::View<uint32_t*, Mem>& masks,
            Kokkos::View<Contact*, Mem>& contacts, long first) {
    using namespace narrow_detail;
    MaskJobs<Mem> slots;
    const long total = count_mask_jobs(exec, masks, n, kFeatureBits, offsets_, slots);
    if (total == 0) return 0;
    if (long(contacts.extent(0)) < first + total) {
      Kokkos::View<Contact*, Mem> bigger(Kokkos::view_alloc(Kokkos::WithoutInitializing, contacts.label()),
                                         (first + total) * 3 / 2 + 64);
      if (first > 0)
        Kokkos::deep_copy(exec, Kokkos::subview(bigger, std::make_pair(0L, first)),
                          Kokkos::subview(contacts, std::make_pair(0L, first)));
      contacts = bigger;
    }
    Kokkos::parallel_for("weft::narrow_fill", Kokkos::RangePolicy<Exec>(exec, 0, n),
                         FillContacts<Mem>{A, B, pairs, slots, ns, contacts, first});
    return total;
  }

 private:

  // Grown with slack up to one chunk, never shrunk.
  template <class V>
  void grow(V& v, long n) const {
    if (long(v.extent(0)) < n) {
      const long size = n + n / 2 + 16;
      v = V(Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label()), size < chunk_ ? size : chunk_);
    }
  }

  long chunk_;
  PairCull<Exec> cull_;
  Kokkos::View<uint32_t*, Mem> masks_{"weft::narrow_masks", 0}, open_{"weft::narrow_open", 0};
  Kokkos::View<long*, Mem> offsets_{"weft::narrow_offsets", 0};  // per block of pairs
};

}  // namespace weft
