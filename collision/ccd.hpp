// Conservative continuous collision detection of a vertex against a triangle and of two edges, with a
// minimum separation (ms), after the inclusion-based bisection of Wang et al. 2021 ("Tight Inclusion").
// The parameter boxes of collision/ccd_box.hpp whose enclosure of F keeps |F| > ms are dropped; the others
// are halved, depth first and earlier time first, until |F| varies by less than the tolerance over them,
// and the earliest such box gives the time of impact. Nothing that comes within ms is ever dropped, so there
// are no false negatives; pairs that come within ms + tolerance may be reported.
#pragma once
#include "collision/ccd_box.hpp"

namespace weft {

struct CcdSettings {
  // A box that may hold a contact is reported once the distance |F| varies by less than this over it, so
  // pairs that come within ms + tolerance may be reported (false positives).
  real tolerance = 1e-6;
  // Boxes examined before giving up; a query that runs out reports a hit at the earliest time not excluded.
  int max_iterations = 1000000;
  // Stop at the first box reported: the answer's `hit` is the same (a report is a hit whatever follows),
  // only `toi` is no longer the earliest. For callers that read `hit` alone, it spares the search for
  // earlier boxes, which is what long searches spend their iterations on.
  bool first_hit = false;
};

struct CcdResult {
  bool hit = false;
  real toi = 1;  // hit: a lower bound on the first time the distance is <= ms; otherwise 1
};

namespace ccd_detail {

inline constexpr int kMaxDepth = 3 * 48;  // halvings before every parameter is down to kMinWidth

// The earliest start time among the current box, the boxes still waiting on the search path and best.
// path[k]: bits 0-1 the parameter halved at depth k, bit 2 set once its second half is the one on the
// path, kUpperFirst when the upper half came first (never for t).
KOKKOS_INLINE_FUNCTION real earliest_open(const uint8_t* path, int depth, real t_lo, real t_w, real best) {
  real r = min_(best, t_lo);
  for (int k = depth - 1; k >= 0; --k) {
    const bool second = path[k] & 4;
    if ((path[k] & 3) == 0) {
      if (second) t_lo -= t_w;
      else r = min_(r, t_lo + t_w);
      t_w *= 2;
    } else if (!second) {
      r = min_(r, t_lo);
    }
  }
  return r;
}

// Depth first from the unit box, earlier half of t first, skipping boxes that start no earlier than the
// best report so far; the memory is one step per depth.
template <CcdKind K>
KOKKOS_INLINE_FUNCTION CcdResult search(const Query<K>& q, int max_iterations, bool first_hit) {
  Box b{{0, 0, 0}, {1, 1, 1}};
  uint8_t path[kMaxDepth];
  int depth = 0;
  real best = 2;  // start of the earliest box reported (> 1: none)
  for (int iterations = 0;; ++iterations) {
    if (iterations == max_iterations) return {true, earliest_open(path, depth, b.lo[0], b.w[0], best)};
    const int r = q.examine(b, best);
    if (r >= 0) {
      const int j = r & 3;
      path[depth++] = uint8_t(r);
      b.w[j] *= 0.5;
      if (r & kUpperFirst) b.lo[j] += b.w[j];
      continue;
    }
    if (r == kReport) {
      if (first_hit) return {true, b.lo[0]};
      best = b.lo[0];
    }
    // Next: the other half of the deepest split still on its first half.
    for (;;) {
      if (depth == 0) return best <= 1 ? CcdResult{true, best} : CcdResult{false, 1};
      uint8_t& step = path[depth - 1];
      const int j = step & 3;
      const bool upper_first = step & kUpperFirst;
      if (!(step & 4)) {
        step |= 4;
        b.lo[j] += upper_first ? -b.w[j] : b.w[j];
        if (b.lo[0] < best) break;
      }
      if (!upper_first) b.lo[j] -= b.w[j];
      b.w[j] *= 2;
      --depth;
    }
  }
}

template <CcdKind K>
KOKKOS_INLINE_FUNCTION CcdResult solve(const Vec3 (&x0)[4], const Vec3 (&x1)[4], real ms, const CcdSettings& s) {
  Query<K> q;
  if (!q.init(x0, x1, ms, s.tolerance)) return {true, 0};  // unbounded input: a hit at once, conservatively
  return search(q, s.max_iterations, s.first_hit);
}

}  // namespace ccd_detail

// Vertex p against triangle (q0, q1, q2); suffix 0 = start of the step, 1 = end.
KOKKOS_INLINE_FUNCTION CcdResult ccd_vertex_face(Vec3 p0, Vec3 q00, Vec3 q10, Vec3 q20, Vec3 p1, Vec3 q01, Vec3 q11,
                                                 Vec3 q21, real ms, const CcdSettings& s) {
  const Vec3 x0[4] = {p0, q00, q10, q20}, x1[4] = {p1, q01, q11, q21};
  return ccd_detail::solve<CcdKind::VertexFace>(x0, x1, ms, s);
}

// Edge (a0, a1) against edge (b0, b1); suffix 0 = start of the step, 1 = end.
KOKKOS_INLINE_FUNCTION CcdResult ccd_edge_edge(Vec3 a00, Vec3 a10, Vec3 b00, Vec3 b10, Vec3 a01, Vec3 a11, Vec3 b01,
                                               Vec3 b11, real ms, const CcdSettings& s) {
  const Vec3 x0[4] = {a00, a10, b00, b10}, x1[4] = {a01, a11, b01, b11};
  return ccd_detail::solve<CcdKind::EdgeEdge>(x0, x1, ms, s);
}

}  // namespace weft
