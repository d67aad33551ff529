// Conservative continuous collision detection of a vertex against a triangle and of two edges, with a minimum
// separation, after the inclusion-based bisection of Wang et al. 2021 ("Tight Inclusion").
//
// Vertices move linearly, x(t) = x0 + t (x1 - x0), t in [0, 1]. F(t, a, b) is the vector between the two
// primitives' points: p - ((1 - a - b) q0 + a q1 + b q2) (vertex-face, a + b <= 1) or
// (a0 + a (a1 - a0)) - (b0 + b (b1 - b0)) (edge-edge, a, b in [0, 1]). The pair collides when |F| <= ms at
// some (t, a, b). F is affine in each parameter separately, so over a box of parameters it takes values in
// the convex hull of its 8 corner values, which are computed to within a certified rounding bound. Boxes
// where that enclosure keeps |F| > ms are dropped; the others are bisected depth first, earliest time
// first, until |F| varies by less than the tolerance over them, and the earliest such box gives the time of
// impact. Nothing that comes within ms is ever dropped, so there are no false negatives; pairs that come
// within ms + tolerance may be reported.
#pragma once
#include "core/vec.hpp"

#include <cstdint>

namespace weft {

enum class CcdKind : uint8_t { VertexFace, EdgeEdge };

struct CcdSettings {
  // A box that may hold a contact is reported once the distance |F| varies by less than this over it, so
  // pairs that come within ms + tolerance may be reported (false positives), and toi is that precise.
  real tolerance = 1e-6;
  // Boxes examined before giving up; a query that runs out reports a hit at the earliest time not excluded.
  int max_iterations = 1000000;
};

struct CcdResult {
  bool hit = false;
  real toi = 1;  // hit: a lower bound on the first time the distance is <= ms; otherwise 1
};

namespace ccd_detail {

// Parameter intervals stop halving at this width, so their ends stay exact dyadic numbers.
inline constexpr real kMinWidth = 0x1p-48;
inline constexpr int kMaxDepth = 3 * 48;

// F at one (a, b) corner from the four vertices at one time; the error bound in solve() assumes exactly
// these operations.
template <CcdKind K>
KOKKOS_INLINE_FUNCTION Vec3 corner(const Vec3 (&x)[4], real a, real b) {
  if constexpr (K == CcdKind::VertexFace) {
    return ((x[0] - x[1]) - a * (x[2] - x[1])) - b * (x[3] - x[1]);
  } else {
    return (x[0] + a * (x[1] - x[0])) - (x[2] + b * (x[3] - x[2]));
  }
}

// The earliest start time among the current box, the boxes still waiting on the path and the best hit.
// path[k]: bits 0-1 the parameter split at depth k, bit 2 set once its second half is the one on the path,
// bit 3 set when the upper half came first (never for t).
KOKKOS_INLINE_FUNCTION real earliest_open(const uint8_t* path, int depth, real t_lo, real t_w, real best) {
  real r = min_(best, t_lo);
  for (int k = depth - 1; k >= 0; --k) {
    const bool upper = path[k] & 4;
    if ((path[k] & 3) == 0) {
      if (upper) t_lo -= t_w;
      else r = min_(r, t_lo + t_w);
      t_w *= 2;
    } else if (!upper) {
      r = min_(r, t_lo);
    }
  }
  return r;
}

template <CcdKind K>
KOKKOS_INLINE_FUNCTION CcdResult solve(const Vec3 (&x0)[4], const Vec3 (&x1)[4], real ms, const CcdSettings& s) {
  const CcdResult unsure{true, 0};
  Vec3 d[4], m;  // m: largest |coordinate| per axis over all eight positions
  bool finite = ms >= 0 && isfinite_(ms);
  for (int k = 0; k < 4; ++k) {
    finite = finite && isfinite_(x0[k]) && isfinite_(x1[k]);
    d[k] = x1[k] - x0[k];
    m = vmax(m, vmax(Vec3{abs_(x0[k].x), abs_(x0[k].y), abs_(x0[k].z)},
                     Vec3{abs_(x1[k].x), abs_(x1[k].y), abs_(x1[k].z)}));
  }
  // Beyond 2^400 the squares of corner values could overflow.
  if (!finite || !(max_(m.x, max_(m.y, m.z)) <= 0x1p400)) return unsure;

  // Rounding bound per axis. With u = 2^-53 and every |coordinate| <= M, a position x0 + t d is within 5Mu;
  // a corner value (|F| <= 4M) within 46Mu (vertex-face; 42Mu edge-edge); widening the range by it rounds
  // by another 4Mu. 128Mu covers all of that and the higher-order terms; 2^-1000 covers underflow.
  real e[3];
  for (int i = 0; i < 3; ++i) e[i] = m[i] * 0x1p-46 + 0x1p-1000;
  // The Euclidean test is skipped where ms^2 could underflow or overflow; the per-axis test always runs.
  // The factor absorbs the rounding of the squares and their sum.
  const bool euclid = ms > 1e-100 && ms < 1e100;
  const real ms2 = ms * ms * (1 + 0x1p-40);

  real lo[3] = {0, 0, 0}, w[3] = {1, 1, 1};  // the box over (t, a, b)
  uint8_t path[kMaxDepth];
  int depth = 0, iterations = 0;
  real best = 2;  // start of the earliest box reported so far (> 1: none)
  for (;;) {
    // Vertex-face boxes lying wholly outside the triangle (a + b > 1) hold no contact.
    bool drop = K == CcdKind::VertexFace && lo[1] + lo[2] > 1;
    int split = -1, nearest = 0;  // nearest: the corner nearest to contact
    if (!drop) {
      if (iterations++ == s.max_iterations) return {true, earliest_open(path, depth, lo[0], w[0], best)};
      Vec3 c[8];  // corner k: t upper if bit 0, a upper if bit 1, b upper if bit 2
      for (int it = 0; it < 2; ++it) {
        const real t = it ? lo[0] + w[0] : lo[0];
        const Vec3 x[4] = {x0[0] + t * d[0], x0[1] + t * d[1], x0[2] + t * d[2], x0[3] + t * d[3]};
        for (int ab = 0; ab < 4; ++ab)
          c[it | ab << 1] = corner<K>(x, ab & 1 ? lo[1] + w[1] : lo[1], ab & 2 ? lo[2] + w[2] : lo[2]);
      }
      // Lower bounds of |F| on the box: the distance of the corners' range, widened by e, from the origin;
      // per axis it must stay <= ms. Corner values are exact to within e.
      real g2 = 0;
      bool noise = true;  // the corners differ by no more than rounding: splitting cannot resolve more
      Vec3 mid;           // centre of the corners' range
      for (int i = 0; i < 3; ++i) {
        real cmin = c[0][i], cmax = cmin;
        for (int k = 1; k < 8; ++k) {
          cmin = min_(cmin, c[k][i]);
          cmax = max_(cmax, c[k][i]);
        }
        mid[i] = 0.5 * cmin + 0.5 * cmax;
        const real g = max_(max_(cmin - e[i], -(cmax + e[i])), real(0));
        drop = drop || g > ms;
        g2 += g * g;
        noise = noise && cmax - cmin <= 4 * e[i];
      }
      drop = drop || (euclid && g2 > ms2);
      real lower = sqrt_(g2);
      // F on the box is a convex combination of its corner values (F is multilinear), so the plane through
      // the origin normal to mid bounds |F| too, and, unlike the axis-aligned range, stays tight for boxes
      // that are narrow along mid but wide across it, as near a first contact. The factor 2 on e absorbs
      // the rounding of the dot products; the comparison absorbs that of the normalisation.
      const real rm = norm(mid);
      const Vec3 dir = rm > 0x1p-400 ? mid / rm : Vec3{};
      if (rm > 0x1p-400) {
        real plane = dot(dir, c[0]);
        for (int k = 1; k < 8; ++k) plane = min_(plane, dot(dir, c[k]));
        plane = plane - 2 * (abs_(dir.x) * e[0] + abs_(dir.y) * e[1] + abs_(dir.z) * e[2]);
        drop = drop || plane > ms * (1 + 0x1p-40);
        lower = max_(lower, plane);
      }
      // Narrow: |F| varies by less than the tolerance over the box. Near a first contact |F| grows only
      // quadratically away from the closest point, so this needs far fewer boxes than narrow F itself.
      real upper = 0, nearest2 = norm2(c[0]);
      for (int k = 0; k < 8; ++k) {
        const real n2 = norm2(c[k]);
        upper = max_(upper, n2);
        if (n2 < nearest2) { nearest2 = n2; nearest = k; }
      }
      upper = sqrt_(upper) + norm(Vec3{e[0], e[1], e[2]});
      if (!drop && !noise && upper - lower > s.tolerance) {
        // Halve the parameter that widens the range of |F| most: a change D of F along a box edge (exact:
        // F is affine along it) widens it by about |D . dir| along dir and |D|^2 / |mid| across.
        // A parameter F does not depend on is never split.
        real most = 0;
        for (int j = 0; j < 3; ++j) {
          real along = 0, across = 0;
          for (int k = 0; k < 8; ++k)
            if (!(k >> j & 1)) {
              const Vec3 diff = c[k | 1 << j] - c[k];
              const real n2 = norm2(diff);
              along = max_(along, abs_(dot(diff, dir)));
              if (n2 > 0) across = max_(across, n2 / max_(rm, sqrt_(n2)));
            }
          if (w[j] > kMinWidth && along + across > most) {
            most = along + across;
            split = j;
          }
        }
        // Cutting t at the best hit first drops the later half unseen, and the earlier half is often
        // excluded whole; splitting a or b first could leave a whole line of contacts to be refined.
        if (split >= 0 && lo[0] + w[0] > best && w[0] > kMinWidth) split = 0;
      }
      if (!drop && split < 0) best = lo[0];  // narrow enough, or nothing left to split: report it
    }
    if (split >= 0) {
      // Earlier half of t first; of a or b, the half holding the corner nearest to contact, so that the
      // first hits found are early and prune the rest.
      const bool upper_first = split > 0 && (nearest >> split & 1);
      path[depth++] = uint8_t(split | (upper_first ? 8 : 0));
      w[split] *= 0.5;
      if (upper_first) lo[split] += w[split];
      continue;
    }
    // Next box: the other half of the deepest split still on its first half, unless it starts no earlier
    // than the best hit.
    for (;;) {
      if (depth == 0) return best <= 1 ? CcdResult{true, best} : CcdResult{false, 1};
      uint8_t& step = path[depth - 1];
      const int j = step & 3;
      const bool upper_first = step & 8;
      if (!(step & 4)) {
        step |= 4;
        lo[j] += upper_first ? -w[j] : w[j];
        if (lo[0] < best) break;
      }
      if (!upper_first) lo[j] -= w[j];
      w[j] *= 2;
      --depth;
    }
  }
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
