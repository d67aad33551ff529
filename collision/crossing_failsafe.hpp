// The crossing fail-safe: what keeps a cloth that starts a substep free of intersections free of them at its
// end, whatever the contact solve left unresolved (contacts are projected a fixed number of times and, in a
// tangle like `twist`, do not always converge).
//
// After the last constraint iteration, every representative vertex-face and edge-edge pair of the candidate
// triangle pairs is tested by CCD with separation 0 over the substep (x_start -> x, linear). The moving
// points of each pair that may cross go back to their start-of-substep positions (their velocity becomes 0),
// and the pairs touching a point moved back are tested again, until no pair crosses or every point of the
// crossing pairs is already back (or pinned). The start of the substep being free of crossings, so is the
// end: this is the "fail-safe" of Bridson et al. 2002 in its simplest form (the impact zone stops instead of
// moving rigidly). After a few rounds the flags also take the neighbours of flagged points (GrowFlags), so
// a large zone is reached in fewer rounds. Rounds, flags and counts are integers, so the result is the same
// on every backend.
#pragma once
#include "collision/ccd.hpp"
#include "collision/lbvh.hpp"
#include "collision/mask_jobs.hpp"
#include "collision/narrow_phase.hpp"
#include "collision/pair_cull.hpp"

#include <Kokkos_Core.hpp>
#include <utility>

namespace weft {

namespace failsafe_detail {

// Settings of the crossing test: separation 0; pairs that may come within `tolerance_scale` of the pair's
// thickness are treated as crossing (conservative), and a query that exhausts its budget counts as crossing.
// Later rounds test only pairs next to points just moved back, and a launch lasts as long as its longest
// search: there a search that runs out moves one more ring of points back, which on the H200 cost no more
// points moved back than the full budget and took paper-1's fail-safe from 391 to 180 ms per frame (300K skirt).
struct CrossingSettings {
  real tolerance_scale = 0.01;
  int max_iterations = 4000;        // round 0
  int later_max_iterations = 500;   // rounds after the first
  int grow_from = 8;                // rounds from which flags grow by a ring (GrowFlags)
};

KOKKOS_INLINE_FUNCTION CcdSettings ccd_settings(real r, const CrossingSettings& s) {
  return CcdSettings{max_(real(1e-6), s.tolerance_scale * r), s.max_iterations, /*first_hit*/ true};
}

}  // namespace failsafe_detail

// The margin of a triangle's swept box for the fail-safe's broad phase (`thickness`: the largest of its
// points'). Two boxes then overlap whenever their triangles come within the crossing test's tolerance of
// each other, max(1e-6, tolerance_scale * (r_a + r_b)) <= the sum of the margins: a pair the test could
// flag is never left out. Far smaller than the contact margin, so resting contacts add no pairs.
inline real failsafe_box_margin(real thickness) {
  return failsafe_detail::CrossingSettings{}.tolerance_scale * thickness + real(1e-6);
}

namespace failsafe_detail {

// Marks the cloth points of a crossing feature pair (integer flags, idempotent).
template <class Mem>
KOKKOS_INLINE_FUNCTION void mark(const SideMesh<Mem>& S, int v, const Kokkos::View<int*, Mem>& flag) {
  if (!S.collider) Kokkos::atomic_fetch_or(&flag(v), 1);
}

// The cheap part of the crossing tests: false when the pair cannot come within the tolerance over the
// substep (it starts farther apart than the largest relative displacement of its points).
template <class Mem>
KOKKOS_INLINE_FUNCTION bool vf_may_cross(const SideMesh<Mem>& P, int p, const SideMesh<Mem>& F, int f, real r,
                                         const CrossingSettings& s) {
  const int a = F.tris(f, 0), b = F.tris(f, 1), c = F.tris(f, 2);
  const Vec3 dp = P.x(p) - P.xs(p);
  const real D = sqrt_(max_(norm2(dp - (F.x(a) - F.xs(a))), max_(norm2(dp - (F.x(b) - F.xs(b))), norm2(dp - (F.x(c) - F.xs(c))))));
  real u, v, w;
  const real d0 = sqrt_(point_triangle_distance2(P.xs(p), F.xs(a), F.xs(b), F.xs(c), u, v, w));
  return !(d0 - D > 1e-9 * (1 + d0) + max_(real(1e-6), s.tolerance_scale * r));
}

template <class Mem>
KOKKOS_INLINE_FUNCTION bool ee_may_cross(const SideMesh<Mem>& A, int a0, int a1, const SideMesh<Mem>& B, int b0, int b1,
                                         real r, const CrossingSettings& s) {
  const Vec3 da0 = A.x(a0) - A.xs(a0), da1 = A.x(a1) - A.xs(a1), db0 = B.x(b0) - B.xs(b0), db1 = B.x(b1) - B.xs(b1);
  const real D = sqrt_(max_(max_(norm2(da0 - db0), norm2(da0 - db1)), max_(norm2(da1 - db0), norm2(da1 - db1))));
  real sa, tb;
  const real d0 = sqrt_(segment_segment_distance2(A.xs(a0), A.xs(a1), B.xs(b0), B.xs(b1), sa, tb));
  return !(d0 - D > 1e-9 * (1 + d0) + max_(real(1e-6), s.tolerance_scale * r));
}

// Whether a point of side S was moved back in round `round` (collider vertices never are).
template <class Mem>
KOKKOS_INLINE_FUNCTION bool moved_back_in(const SideMesh<Mem>& S, int v, const Kokkos::View<const int*, Mem>& back, int round) {
  return !S.collider && back(v) == round;
}

// One round's cheap tests of a candidate triangle pair: the feature pairs (bits as in the narrow phase)
// whose crossing only the CCD can rule out. From round 1 on, only pairs with a point moved back in the
// previous round can have changed.
template <class Mem>
struct CrossingTests {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<const int*, Mem> back;
  Kokkos::View<uint32_t*, Mem> open;
  int round;
  bool self, all;
  CrossingSettings cs;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int ta_i = pairs(i).first, tb_i = pairs(i).second;
    const int ta[3] = {A.tris(ta_i, 0), A.tris(ta_i, 1), A.tris(ta_i, 2)};
    const int tb[3] = {B.tris(tb_i, 0), B.tris(tb_i, 1), B.tris(tb_i, 2)};
    bool changed = all;
    for (int k = 0; k < 3; ++k)
      changed = changed || moved_back_in(A, ta[k], back, round - 1) || moved_back_in(B, tb[k], back, round - 1);
    open(i) = changed ? open_features(ta_i, ta, tb_i, tb) : 0u;
  }

  // The feature pairs of triangles ta_i and tb_i that may cross.
  KOKKOS_INLINE_FUNCTION uint32_t open_features(int ta_i, const int (&ta)[3], int tb_i, const int (&tb)[3]) const {
    const real fa = narrow_detail::face_th(A, ta_i), fb = narrow_detail::face_th(B, tb_i);
    uint32_t o = 0;
    const uint8_t ra = A.rmask(ta_i), rb = B.rmask(tb_i);
    for (int k = 0; k < 3; ++k) {
      const int p = ta[k], q = tb[k];
      if (((ra >> k) & 1) && !(self && (p == tb[0] || p == tb[1] || p == tb[2])) && vf_may_cross(A, p, B, tb_i, A.th(p) + fb, cs))
        o |= 1u << k;
      if (((rb >> k) & 1) && !(self && (q == ta[0] || q == ta[1] || q == ta[2])) && vf_may_cross(B, q, A, ta_i, B.th(q) + fa, cs))
        o |= 1u << (3 + k);
    }
    for (int ka = 0; ka < 3; ++ka) {
      if (!((ra >> (3 + ka)) & 1)) continue;
      const int a0 = ta[ka], a1 = ta[(ka + 1) % 3];
      for (int kb = 0; kb < 3; ++kb) {
        if (!((rb >> (3 + kb)) & 1)) continue;
        const int b0 = tb[kb], b1 = tb[(kb + 1) % 3];
        if (self && narrow_detail::shares(a0, a1, b0, b1)) continue;
        const real r = max_(A.th(a0), A.th(a1)) + max_(B.th(b0), B.th(b1));
        if (ee_may_cross(A, a0, a1, B, b0, b1, r, cs)) o |= 1u << (6 + 3 * ka + kb);
      }
    }
    return o;
  }
};

// The crossing CCD of one open feature pair (job j, as in the narrow phase); a crossing flags the cloth
// points of both features.
template <class Mem>
struct CrossingCcd {
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  MaskJobs<Mem> jobs;  // over the open bits
  Kokkos::View<int*, Mem> flag;
  CrossingSettings cs;
  KOKKOS_INLINE_FUNCTION void operator()(long j) const {
    int bit = 0;
    const long i = jobs.item(j, bit);
    const int fa = pairs(i).first, fb = pairs(i).second;
    if (bit < 6) {  // vertex p of side P against face f of side F
      const bool a_vertex = bit < 3;
      const SideMesh<Mem>& P = a_vertex ? A : B;
      const SideMesh<Mem>& F = a_vertex ? B : A;
      const int f = a_vertex ? fb : fa, p = P.tris(a_vertex ? fa : fb, bit % 3);
      const int a = F.tris(f, 0), b = F.tris(f, 1), c = F.tris(f, 2);
      const real r = P.th(p) + narrow_detail::face_th(F, f);
      if (ccd_vertex_face(P.xs(p), F.xs(a), F.xs(b), F.xs(c), P.x(p), F.x(a), F.x(b), F.x(c), 0, ccd_settings(r, cs)).hit) {
        mark(P, p, flag);
        mark(F, a, flag); mark(F, b, flag); mark(F, c, flag);
      }
      return;
    }
    const int ka = (bit - 6) / 3, kb = (bit - 6) % 3;
    const int a0 = A.tris(fa, ka), a1 = A.tris(fa, (ka + 1) % 3), b0 = B.tris(fb, kb), b1 = B.tris(fb, (kb + 1) % 3);
    const real r = max_(A.th(a0), A.th(a1)) + max_(B.th(b0), B.th(b1));
    if (ccd_edge_edge(A.xs(a0), A.xs(a1), B.xs(b0), B.xs(b1), A.x(a0), A.x(a1), B.x(b0), B.x(b1), 0, ccd_settings(r, cs)).hit) {
      mark(A, a0, flag); mark(A, a1, flag);
      mark(B, b0, flag); mark(B, b1, flag);
    }
  }
};

// From round `grow_from` on, the points flagged in a round are joined by the other corners of their
// triangles (`grown` starts as a copy of `flag`; pinned points are never added). A tangle the contacts left
// spreads to the next ring of points each round; growing the flags takes two rings a round, and took the
// worst frame of the 300K skirt at one substep a frame from hundreds of rounds to 89, with about as many
// points moved back (measured on the H200 at commit 9c25ad4). The copy keeps the result independent of the order
// in which triangles run. Integer flags set idempotently: the same on every backend.
template <class Mem>
struct GrowFlags {
  Kokkos::View<const int* [3], Mem> tris;
  Kokkos::View<const int*, Mem> flag;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<int*, Mem> grown;
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const int v[3] = {tris(t, 0), tris(t, 1), tris(t, 2)};
    if (!(flag(v[0]) | flag(v[1]) | flag(v[2]))) return;
    for (int k = 0; k < 3; ++k)
      if (!flag(v[k]) && w(v[k]) > 0) Kokkos::atomic_fetch_or(&grown(v[k]), 1);
  }
};

// Counts of one round, packed into one integer sum: points moved back + kPinnedUnit * pinned points that
// are flagged and still where their animation put them.
constexpr long kPinnedUnit = 1L << 32;

// Moves flagged points that are not back yet to their start positions and counts them. Pinned points go back
// only when `pinned` is set (the last resort); until then their flags stay up and they are counted.
template <class Mem>
struct MoveBack {
  Kokkos::View<Vec3*, Mem> x, xs;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<int*, Mem> back, flag;
  int round;
  bool pinned;
  KOKKOS_INLINE_FUNCTION void operator()(long i, long& counts) const {
    if (!flag(i)) return;
    if (back(i) >= 0) { flag(i) = 0; return; }
    if (!(w(i) > 0) && !pinned) { counts += kPinnedUnit; return; }
    flag(i) = 0;
    x(i) = xs(i);
    back(i) = round;
    counts += 1;
  }
};

}  // namespace failsafe_detail

struct FailsafeStats {
  long points = 0;  // points moved back to their start positions
  long pinned = 0;  // of which pinned points (they trail their animation for the substep)
  int rounds = 0;
};

// The fail-safe's working memory: per-point round of moving back (-1: not moved) and crossing flags.
template <class Exec>
class CrossingFailsafe {
 public:
  using Mem = typename Exec::memory_space;
  using Pairs = Kokkos::View<IndexPair*, Mem>;

  // `self_pairs` (cloth triangle pairs) and `collider_pairs` (cloth, collider) came from boxes that contain
  // every position between x_start and x, so they stay valid while points move back. `cull`: working
  // memory for the pair cut of full rounds (the narrow phase's, NarrowPipeline::pair_cull()).
  FailsafeStats run(const Exec& exec, const SideMesh<Mem>& cloth, const SideMesh<Mem>& collider,
                    const Pairs& self_pairs, long nself, const Pairs& collider_pairs, long ncollider,
                    const Kokkos::View<Vec3*, Mem>& x, const Kokkos::View<Vec3*, Mem>& xs,
                    const Kokkos::View<real*, Mem>& w, PairCull<Exec>& cull) {
    using namespace failsafe_detail;
    const long n = long(x.extent(0));
    if (long(back_.extent(0)) != n) {
      back_ = Kokkos::View<int*, Mem>("weft::failsafe_back", n);
      flag_ = Kokkos::View<int*, Mem>("weft::failsafe_flag", n);
      grown_ = Kokkos::View<int*, Mem>("weft::failsafe_grown", n);
    }
    Kokkos::deep_copy(exec, back_, -1);
    Kokkos::deep_copy(exec, flag_, 0);
    FailsafeStats st;
    // Every round moves at least one more point back, so there are at most n + 2.
    bool pinned = false;
    for (int round = 0;; ++round) {
      const bool all = round == 0 || pinned;
      mark_crossings(exec, cloth, cloth, self_pairs, nself, round, true, all, cull);
      mark_crossings(exec, cloth, collider, collider_pairs, ncollider, round, false, all, cull);
      if (round >= cs_.grow_from && !pinned) {
        Kokkos::deep_copy(exec, grown_, flag_);
        Kokkos::parallel_for("weft::failsafe_grow", Kokkos::RangePolicy<Exec>(exec, 0, cloth.tris.extent(0)),
                             GrowFlags<Mem>{cloth.tris, flag_, w, grown_});
        std::swap(flag_, grown_);
      }
      long counts = 0;
      Kokkos::parallel_reduce("weft::failsafe_move_back", Kokkos::RangePolicy<Exec>(exec, 0, n),
                              MoveBack<Mem>{x, xs, w, back_, flag_, round, pinned}, counts);
      const long moved = counts % kPinnedUnit, waiting = counts / kPinnedUnit;
      st.rounds = round + 1;
      st.points += moved;
      if (pinned) st.pinned += moved;
      if (moved > 0) { pinned = false; continue; }
      if (pinned || waiting == 0) return st;
      // Only pinned points are left to undo a crossing: test every pair afresh (earlier flags may be stale)
      // and let the pinned points of those still crossing trail their animation for this substep.
      Kokkos::deep_copy(exec, flag_, 0);
      pinned = true;
    }
  }

  // Flags the cloth points of every crossing feature pair of pairs [0, n) between sides A and B: cheap
  // tests per triangle pair, then the CCD of the feature pairs they leave open, one per thread (as in the
  // narrow phase), in chunks of bounded working memory; with `all`, after the pair cut. Reads one counter
  // per chunk back.
  void mark_crossings(const Exec& exec, const SideMesh<Mem>& A, const SideMesh<Mem>& B, const Pairs& pairs, long n,
                      int round, bool self, bool all, PairCull<Exec>& cull) {
    using namespace failsafe_detail;
    CrossingSettings cs = cs_;
    if (round > 0) cs.max_iterations = cs.later_max_iterations;
    for (long lo = 0; lo < n; lo += kChunk) {
      const long m = n - lo < kChunk ? n - lo : kChunk;
      if (long(open_.extent(0)) < m) {
        const long size = m + m / 2 + 16 < kChunk ? m + m / 2 + 16 : kChunk;
        open_ = Kokkos::View<uint32_t*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::failsafe_open"), size);
      }
      Kokkos::View<const IndexPair*, Mem> chunk = Kokkos::subview(pairs, std::make_pair(lo, lo + m));
      // A round that tests every pair tests only those that may come within the crossing test's tolerance
      // (later rounds test few pairs, and those cheaply).
      long live = m;
      if (all) chunk = cull.keep(exec, A, B, chunk, m, cs.tolerance_scale, real(1e-6), live);
      // Full rounds are named apart from later ones: their costs differ by orders of magnitude.
      const char* tests = self ? (all ? "weft::failsafe_self_full" : "weft::failsafe_self")
                               : (all ? "weft::failsafe_collider_full" : "weft::failsafe_collider");
      Kokkos::parallel_for(tests, Kokkos::RangePolicy<Exec>(exec, 0, live),
                           CrossingTests<Mem>{A, B, chunk, back_, open_, round, self, all, cs});
      MaskJobs<Mem> jobs;
      const long njobs = count_mask_jobs(exec, open_, live, 0x7FFFu, offsets_, jobs);
      if (njobs > 0)
        Kokkos::parallel_for(all ? "weft::failsafe_ccd_full" : "weft::failsafe_ccd",
                             Kokkos::RangePolicy<Exec>(exec, 0, njobs), CrossingCcd<Mem>{A, B, chunk, jobs, flag_, cs});
    }
  }

 private:
  static constexpr long kChunk = 1L << 24;  // pairs per chunk, as in the narrow phase
  Kokkos::View<int*, Mem> back_, flag_, grown_;
  Kokkos::View<uint32_t*, Mem> open_{"weft::failsafe_open", 0};
  Kokkos::View<long*, Mem> offsets_{"weft::failsafe_offsets", 0};  // per block of pairs
  failsafe_detail::CrossingSettings cs_;
};

}  // namespace weft
