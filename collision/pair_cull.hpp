// A cut of candidate triangle pairs before the narrow phase's and the fail-safe's feature tests: the pairs
// whose swept hulls stay apart along either triangle's normal are dropped and the others compacted, in
// order. Neighbours in one layer are never apart along a normal; the layers above and below, whose tilted
// boxes overlap, make most of a pass's candidate pairs and mostly are (60-67% of the 300K skirt's pairs).
// The cut is its own kernel: inlined at the top of the feature tests it made them 70% slower on the H200
// (their registers, and culled and kept pairs side by side in a warp). The dropped pairs give no contact and
// no crossing, so the results are the same bits; the one exception would be a CCD search of a dropped pair
// running to its cap, which counts as a hit: no pinned or cross-backend hash changed.
#pragma once
#include "collision/lbvh.hpp"  // IndexPair, reserve
#include "collision/mask_jobs.hpp"
#include "collision/narrow_phase.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

namespace pair_cull_detail {

// The interval of dot(n, p - o) over the start and end positions of triangle t's corners; `sum` gathers
// the values so that one finiteness test covers them all.
// A side that stands still (xs is x, as the proximity queries' cloth at X0) has three corners to project.
template <class Mem>
KOKKOS_INLINE_FUNCTION void swept_interval(const SideMesh<Mem>& S, const int (&t)[3], Vec3 n, Vec3 o, real& lo, real& hi,
                                           real& sum) {
  lo = dot(n, S.x(t[0]) - o);
  hi = lo;
  sum += lo;
  const int corners = S.xs.data() == S.x.data() ? 3 : 6;
  for (int k = 1; k < corners; ++k) {
    const real d = dot(n, (k < 3 ? S.x(t[k]) : S.xs(t[k - 3])) - o);
    lo = min_(lo, d);
    hi = max_(hi, d);
    sum += d;
  }
}

// Whether triangles A and B stay farther apart than `reach` over their linear motions from xs to x: a
// separating axis along the normal (at x) of either. At any time of the motion every point of a triangle
// lies in the convex hull of its corners' start and end positions, so hulls whose projections on an axis
// n are more than reach |n| apart keep every feature pair of the two farther apart than reach throughout.
// The pad covers the rounding of the projections (taken from a corner of A, so they stay small) for
// coordinates up to about 1e3; a non-finite position leaves the pair to the full tests.
template <class Mem>
KOKKOS_INLINE_FUNCTION bool swept_apart(const SideMesh<Mem>& SA, const int (&ta)[3], const SideMesh<Mem>& SB,
                                        const int (&tb)[3], real reach) {
  const Vec3 o = SA.x(ta[0]);
  const real limit = reach * (1 + 1e-6) + 1e-9 + 1e-12 * (abs_(o.x) + abs_(o.y) + abs_(o.z));
  for (int side = 0; side < 2; ++side) {
    const Vec3 a = side ? SB.x(tb[0]) : o, b = side ? SB.x(tb[1]) : SA.x(ta[1]), c = side ? SB.x(tb[2]) : SA.x(ta[2]);
    const Vec3 n = cross(b - a, c - a);
    real alo, ahi, blo, bhi, sum = 0;
    swept_interval(SA, ta, n, o, alo, ahi, sum);
    swept_interval(SB, tb, n, o, blo, bhi, sum);
    if (isfinite_(sum) && max_(blo - ahi, alo - bhi) > limit * norm(n)) return true;
  }
  return false;
}

// live(i): 1 when pair i may come within scale * (thA + thB) + pad of each other (thX: the largest point
// thickness of triangle X).
template <class Mem>
struct MarkLive {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<uint32_t*, Mem> live;
  real scale, pad;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int a = pairs(i).first, b = pairs(i).second;
    const int ta[3] = {A.tris(a, 0), A.tris(a, 1), A.tris(a, 2)};
    const int tb[3] = {B.tris(b, 0), B.tris(b, 1), B.tris(b, 2)};
    const real reach = scale * (narrow_detail::face_th(A, a) + narrow_detail::face_th(B, b)) + pad;
    live(i) = swept_apart(A, ta, B, tb, reach) ? 0u : 1u;
  }
};

// live(i): 1 when keep(i) holds.
template <class Mem, class Keep>
struct MarkIf {
  Keep keep;
  Kokkos::View<uint32_t*, Mem> live;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { live(i) = keep(i) ? 1u : 0u; }
};

template <class Mem>
struct GatherLive {
  MaskJobs<Mem> slots;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<IndexPair*, Mem> out;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    if (slots.masks(i)) out(slots.first(i)) = pairs(i);
  }
};

}  // namespace pair_cull_detail

// The cut's working memory, reused from call to call.
template <class Exec>
class PairCull {
 public:
  using Mem = typename Exec::memory_space;

  // The pairs of pairs[0, n) between sides A and B that may come within scale * (thA + thB) + pad, in
  // order, as a view of this object's memory (valid until the next call). Reads one counter back.
  Kokkos::View<const IndexPair*, Mem> keep(const Exec& exec, const SideMesh<Mem>& A, const SideMesh<Mem>& B,
                                           const Kokkos::View<const IndexPair*, Mem>& pairs, long n, real scale, real pad,
                                           long& kept) {
    using namespace pair_cull_detail;
    lbvh_detail::reserve(live_, n, "weft::cull_live");
    Kokkos::parallel_for("weft::cull_pairs", Kokkos::RangePolicy<Exec>(exec, 0, n), MarkLive<Mem>{A, B, pairs, live_, scale, pad});
    return gather(exec, pairs, n, kept);
  }

  // The pairs i of pairs[0, n) for which keep(i) holds, in order, as keep() returns them.
  template <class Keep>
  Kokkos::View<const IndexPair*, Mem> keep_if(const Exec& exec, const Kokkos::View<const IndexPair*, Mem>& pairs, long n,
                                              const Keep& keep, long& kept) {
    lbvh_detail::reserve(live_, n, "weft::cull_live");
    Kokkos::parallel_for("weft::cull_pairs", Kokkos::RangePolicy<Exec>(exec, 0, n), pair_cull_detail::MarkIf<Mem, Keep>{keep, live_});
    return gather(exec, pairs, n, kept);
  }

 private:
  Kokkos::View<const IndexPair*, Mem> gather(const Exec& exec, const Kokkos::View<const IndexPair*, Mem>& pairs, long n,
                                             long& kept) {
    using namespace pair_cull_detail;
    MaskJobs<Mem> slots;
    kept = count_mask_jobs(exec, live_, n, 1u, offsets_, slots);
    lbvh_detail::reserve(out_, kept, "weft::cull_pairs");
    Kokkos::parallel_for("weft::cull_gather", Kokkos::RangePolicy<Exec>(exec, 0, n), GatherLive<Mem>{slots, pairs, out_});
    return Kokkos::subview(out_, std::make_pair(0L, kept));
  }

  Kokkos::View<uint32_t*, Mem> live_;
  Kokkos::View<long*, Mem> offsets_{"weft::cull_offsets", 0};
  Kokkos::View<IndexPair*, Mem> out_;
};

}  // namespace weft
