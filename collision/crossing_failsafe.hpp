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
// moving rigidly). Rounds, flags and counts are integers, so the result is the same on every backend.
#pragma once
#include "collision/ccd.hpp"
#include "collision/lbvh.hpp"
#include "collision/narrow_phase.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

namespace failsafe_detail {

// Settings of the crossing test: separation 0; pairs that may come within `tolerance_scale` of the pair's
// thickness are treated as crossing (conservative), and a query that exhausts its budget counts as crossing.
struct CrossingSettings {
  real tolerance_scale = 0.01;
  int max_iterations = 4000;
};

KOKKOS_INLINE_FUNCTION CcdSettings ccd_settings(real r, const CrossingSettings& s) {
  return CcdSettings{max_(real(1e-6), s.tolerance_scale * r), s.max_iterations};
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

template <class Mem>
KOKKOS_INLINE_FUNCTION bool vf_crosses(const SideMesh<Mem>& P, int p, const SideMesh<Mem>& F, int f, real r,
                                       const CrossingSettings& s) {
  const int a = F.tris(f, 0), b = F.tris(f, 1), c = F.tris(f, 2);
  const Vec3 dp = P.x(p) - P.xs(p);
  const real D = sqrt_(max_(norm2(dp - (F.x(a) - F.xs(a))), max_(norm2(dp - (F.x(b) - F.xs(b))), norm2(dp - (F.x(c) - F.xs(c))))));
  real u, v, w;
  const real d0 = sqrt_(point_triangle_distance2(P.xs(p), F.xs(a), F.xs(b), F.xs(c), u, v, w));
  if (d0 - D > 1e-9 * (1 + d0) + max_(real(1e-6), s.tolerance_scale * r)) return false;
  return ccd_vertex_face(P.xs(p), F.xs(a), F.xs(b), F.xs(c), P.x(p), F.x(a), F.x(b), F.x(c), 0, ccd_settings(r, s)).hit;
}

template <class Mem>
KOKKOS_INLINE_FUNCTION bool ee_crosses(const SideMesh<Mem>& A, int a0, int a1, const SideMesh<Mem>& B, int b0, int b1,
                                       real r, const CrossingSettings& s) {
  const Vec3 da0 = A.x(a0) - A.xs(a0), da1 = A.x(a1) - A.xs(a1), db0 = B.x(b0) - B.xs(b0), db1 = B.x(b1) - B.xs(b1);
  const real D = sqrt_(max_(max_(norm2(da0 - db0), norm2(da0 - db1)), max_(norm2(da1 - db0), norm2(da1 - db1))));
  real sa, tb;
  const real d0 = sqrt_(segment_segment_distance2(A.xs(a0), A.xs(a1), B.xs(b0), B.xs(b1), sa, tb));
  if (d0 - D > 1e-9 * (1 + d0) + max_(real(1e-6), s.tolerance_scale * r)) return false;
  return ccd_edge_edge(A.xs(a0), A.xs(a1), B.xs(b0), B.xs(b1), A.x(a0), A.x(a1), B.x(b0), B.x(b1), 0, ccd_settings(r, s)).hit;
}

// Whether a point of side S was moved back in round `round` (collider vertices never are).
template <class Mem>
KOKKOS_INLINE_FUNCTION bool moved_back_in(const SideMesh<Mem>& S, int v, const Kokkos::View<int*, Mem>& back, int round) {
  return !S.collider && back(v) == round;
}

// One round over the candidate triangle pairs: flags the cloth points of every crossing feature pair. From
// round 1 on, only pairs with a point moved back in the previous round can have changed.
template <class Mem>
struct MarkCrossings {
  SideMesh<Mem> A, B;
  Kokkos::View<IndexPair*, Mem> pairs;
  Kokkos::View<int*, Mem> back, flag;
  int round;
  bool self, all;
  CrossingSettings cs;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int ta_i = pairs(i).first, tb_i = pairs(i).second;
    const int ta[3] = {A.tris(ta_i, 0), A.tris(ta_i, 1), A.tris(ta_i, 2)};
    const int tb[3] = {B.tris(tb_i, 0), B.tris(tb_i, 1), B.tris(tb_i, 2)};
    if (!all) {
      bool changed = false;
      for (int k = 0; k < 3; ++k)
        changed = changed || moved_back_in(A, ta[k], back, round - 1) || moved_back_in(B, tb[k], back, round - 1);
      if (!changed) return;
    }
    const uint8_t ra = A.rmask(ta_i), rb = B.rmask(tb_i);
    const real fa = narrow_detail::face_th(A, ta_i), fb = narrow_detail::face_th(B, tb_i);
    for (int k = 0; k < 3; ++k) {
      if ((ra >> k) & 1) {
        const int p = ta[k];
        if (!(self && (p == tb[0] || p == tb[1] || p == tb[2])) && vf_crosses(A, p, B, tb_i, A.th(p) + fb, cs)) {
          mark(A, p, flag);
          for (int j = 0; j < 3; ++j) mark(B, tb[j], flag);
        }
      }
      if ((rb >> k) & 1) {
        const int p = tb[k];
        if (!(self && (p == ta[0] || p == ta[1] || p == ta[2])) && vf_crosses(B, p, A, ta_i, B.th(p) + fa, cs)) {
          mark(B, p, flag);
          for (int j = 0; j < 3; ++j) mark(A, ta[j], flag);
        }
      }
    }
    for (int ka = 0; ka < 3; ++ka) {
      if (!((ra >> (3 + ka)) & 1)) continue;
      const int a0 = ta[ka], a1 = ta[(ka + 1) % 3];
      for (int kb = 0; kb < 3; ++kb) {
        if (!((rb >> (3 + kb)) & 1)) continue;
        const int b0 = tb[kb], b1 = tb[(kb + 1) % 3];
        if (self && narrow_detail::shares(a0, a1, b0, b1)) continue;
        const real r = max_(A.th(a0), A.th(a1)) + max_(B.th(b0), B.th(b1));
        if (ee_crosses(A, a0, a1, B, b0, b1, r, cs)) {
          mark(A, a0, flag); mark(A, a1, flag);
          mark(B, b0, flag); mark(B, b1, flag);
        }
      }
    }
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
  // every position between x_start and x, so they stay valid while points move back.
  FailsafeStats run(const Exec& exec, const SideMesh<Mem>& cloth, const SideMesh<Mem>& collider,
                    const Pairs& self_pairs, long nself, const Pairs& collider_pairs, long ncollider,
                    const Kokkos::View<Vec3*, Mem>& x, const Kokkos::View<Vec3*, Mem>& xs,
                    const Kokkos::View<real*, Mem>& w) {
    using namespace failsafe_detail;
    const long n = long(x.extent(0));
    if (long(back_.extent(0)) != n) {
      back_ = Kokkos::View<int*, Mem>("weft::failsafe_back", n);
      flag_ = Kokkos::View<int*, Mem>("weft::failsafe_flag", n);
    }
    Kokkos::deep_copy(exec, back_, -1);
    Kokkos::deep_copy(exec, flag_, 0);
    FailsafeStats st;
    // Every round moves at least one more point back, so there are at most n + 2.
    bool pinned = false;
    for (int round = 0;; ++round) {
      const bool all = round == 0 || pinned;
      if (nself > 0)
        Kokkos::parallel_for("weft::failsafe_self", Kokkos::RangePolicy<Exec>(exec, 0, nself),
                             MarkCrossings<Mem>{cloth, cloth, self_pairs, back_, flag_, round, true, all, cs_});
      if (ncollider > 0)
        Kokkos::parallel_for("weft::failsafe_collider", Kokkos::RangePolicy<Exec>(exec, 0, ncollider),
                             MarkCrossings<Mem>{cloth, collider, collider_pairs, back_, flag_, round, false, all, cs_});
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

 private:
  Kokkos::View<int*, Mem> back_, flag_;
  failsafe_detail::CrossingSettings cs_;
};

}  // namespace weft
