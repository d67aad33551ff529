// One step of the CCD search (collision/ccd.hpp): encloses F over a box of parameters (t, a, b) and decides
// whether the box holds no contact, is narrow enough to report, or which parameter to halve.
//
// Vertices move linearly, x(t) = x0 + t (x1 - x0), t in [0, 1]. F(t, a, b) is the vector between the two
// primitives' points: p - ((1 - a) q0 + a ((1 - b) q1 + b q2)) (vertex-face) or
// (a0 + a (a1 - a0)) - (b0 + b (b1 - b0)) (edge-edge), with a, b in [0, 1]; the vertex-face parameters map
// the unit square onto the triangle, so no box reaches outside it. The pair collides when |F| <= ms at some
// (t, a, b). F is affine in each parameter separately, so over a box it takes values in the convex hull of
// its 8 corner values, which are computed to within a certified rounding bound.
#pragma once
#include "core/vec.hpp"

#include <cstdint>

namespace weft {

enum class CcdKind : uint8_t { VertexFace, EdgeEdge };

namespace ccd_detail {

// Parameter intervals stop halving at this width, so their ends stay exact dyadic numbers.
inline constexpr real kMinWidth = 0x1p-48;

struct Box {
  real lo[3], w[3];  // [lo, lo + w] for t, a, b
};

// examine() results; a split is the parameter index, with kUpperFirst when its upper half should go first.
inline constexpr int kDrop = -2, kReport = -1, kUpperFirst = 8;

// F at one (a, b) corner from the four vertices at one time; Query's rounding bound assumes exactly these
// operations.
template <CcdKind K>
KOKKOS_INLINE_FUNCTION Vec3 corner(const Vec3 (&x)[4], real a, real b) {
  if constexpr (K == CcdKind::VertexFace) {
    return ((x[0] - x[1]) - a * (x[2] - x[1])) - a * (b * (x[3] - x[2]));
  } else {
    return (x[0] + a * (x[1] - x[0])) - (x[2] + b * (x[3] - x[2]));
  }
}

template <CcdKind K>
struct Query {
  Vec3 x0[4], d[4];  // start positions and displacements
  real e[3];         // rounding bound of a corner value, per axis
  real e_norm;       // |e|, added to every upper bound of |F|
  real ms, ms2, tolerance;
  bool euclid;  // ms^2 is safe to compare with

  // False when the input cannot be bounded (non-finite, negative ms, coordinates beyond 2^400, where the
  // squares of corner values could overflow).
  KOKKOS_INLINE_FUNCTION bool init(const Vec3 (&p0)[4], const Vec3 (&p1)[4], real min_sep, real tol) {
    bool ok = min_sep >= 0 && isfinite_(min_sep);
    Vec3 m;  // largest |coordinate| per axis over all eight positions
    for (int k = 0; k < 4; ++k) {
      ok = ok && isfinite_(p0[k]) && isfinite_(p1[k]);
      x0[k] = p0[k];
      d[k] = p1[k] - p0[k];
      m = vmax(m, vmax(Vec3{abs_(p0[k].x), abs_(p0[k].y), abs_(p0[k].z)},
                       Vec3{abs_(p1[k].x), abs_(p1[k].y), abs_(p1[k].z)}));
    }
    // With u = 2^-53 and every |coordinate| <= M, a position x0 + t d is within 5Mu; a corner value
    // (|F| <= 2M) within 46Mu (vertex-face; 42Mu edge-edge); widening a range by it rounds by another 2Mu.
    // 128Mu covers all of that and the higher-order terms; 2^-1000 covers underflow.
    for (int i = 0; i < 3; ++i) e[i] = m[i] * 0x1p-46 + 0x1p-1000;
    e_norm = norm(Vec3{e[0], e[1], e[2]});
    ms = min_sep;
    // The Euclidean test is skipped where ms^2 could underflow or overflow (the per-axis one always runs);
    // the factor absorbs the rounding of the squares and their sum.
    euclid = ms > 1e-100 && ms < 1e100;
    ms2 = ms * ms * (1 + 0x1p-40);
    tolerance = tol;
    return ok && max_(m.x, max_(m.y, m.z)) <= 0x1p400;
  }

  // kDrop when no point of the box comes within ms; kReport when |F| varies by less than the tolerance over
  // it (or cannot be resolved further); otherwise the parameter to halve. best: the earliest reported time.
  KOKKOS_INLINE_FUNCTION int examine(const Box& b, real best) const {
    Vec3 c[8];  // corner k: t upper if bit 0, a upper if bit 1, b upper if bit 2
    for (int it = 0; it < 2; ++it) {
      const real t = it ? b.lo[0] + b.w[0] : b.lo[0];
      const Vec3 x[4] = {x0[0] + t * d[0], x0[1] + t * d[1], x0[2] + t * d[2], x0[3] + t * d[3]};
      for (int ab = 0; ab < 4; ++ab)
        c[it | ab << 1] = corner<K>(x, ab & 1 ? b.lo[1] + b.w[1] : b.lo[1], ab & 2 ? b.lo[2] + b.w[2] : b.lo[2]);
    }
    // Lower bounds of |F|: the distance from the origin of the corners' range widened by e (per axis, then
    // Euclidean).
    real g2 = 0;
    bool noise = true;  // the corners differ by no more than rounding: halving cannot resolve more
    Vec3 mid;           // centre of the corners' range
    for (int i = 0; i < 3; ++i) {
      real cmin = c[0][i], cmax = cmin;
      for (int k = 1; k < 8; ++k) {
        cmin = min_(cmin, c[k][i]);
        cmax = max_(cmax, c[k][i]);
      }
      mid[i] = 0.5 * cmin + 0.5 * cmax;
      const real g = max_(max_(cmin - e[i], -(cmax + e[i])), real(0));
      if (g > ms) return kDrop;
      g2 += g * g;
      noise = noise && cmax - cmin <= 4 * e[i];
    }
    if (euclid && g2 > ms2) return kDrop;
    real lower = sqrt_(g2);
    // And the distance of the plane through the origin normal to mid, which bounds the convex hull and,
    // unlike the axis-aligned range, stays tight for boxes narrow along mid but wide across it, as near a
    // first contact. The factor 2 on e absorbs the rounding of the dot products; the comparison absorbs
    // that of the normalisation.
    const real rm = norm(mid);
    const Vec3 dir = rm > 0x1p-400 ? mid / rm : Vec3{};
    if (rm > 0x1p-400) {
      real plane = dot(dir, c[0]);
      for (int k = 1; k < 8; ++k) plane = min_(plane, dot(dir, c[k]));
      plane = plane - 2 * (abs_(dir.x) * e[0] + abs_(dir.y) * e[1] + abs_(dir.z) * e[2]);
      if (plane > ms * (1 + 0x1p-40)) return kDrop;
      lower = max_(lower, plane);
    }
    // Narrow: |F| varies by less than the tolerance. Near a first contact |F| grows only quadratically away
    // from the closest point, so this needs far fewer boxes than a narrow F.
    real upper = 0, nearest2 = norm2(c[0]);
    int nearest = 0;  // the corner nearest to contact at the box's start time
    for (int k = 0; k < 8; ++k) {
      const real n2 = norm2(c[k]);
      upper = max_(upper, n2);
      if (!(k & 1) && n2 < nearest2) {
        nearest2 = n2;
        nearest = k;
      }
    }
    upper = sqrt_(upper) + e_norm;
    if (noise || upper - lower <= tolerance) return kReport;
    // Halve the parameter that widens the range of |F| most: a change D of F along a box edge (exact: F is
    // affine along it) widens it by about |D . dir| along dir and |D|^2 / |mid| across. A parameter F does
    // not depend on is never split; with none left, the box is reported.
    int split = kReport;
    real most = 0;
    for (int j = 0; j < 3; ++j) {
      if (!(b.w[j] > kMinWidth)) continue;  // never split: its square roots and divisions are not needed
      real along = 0, across = 0;
      for (int k = 0; k < 8; ++k)
        if (!(k >> j & 1)) {
          const Vec3 diff = c[k | 1 << j] - c[k];
          const real n2 = norm2(diff);
          along = max_(along, abs_(dot(diff, dir)));
          if (n2 > 0) across = max_(across, n2 / max_(rm, sqrt_(n2)));
        }
      if (along + across > most) {
        most = along + across;
        split = j;
      }
    }
    // Cutting t at the best hit first drops the later half unseen, and the earlier half is often excluded
    // whole; halving a or b first could leave a whole line of contacts to refine.
    if (split >= 0 && b.lo[0] + b.w[0] > best && b.w[0] > kMinWidth) split = 0;
    // Of a or b, the half holding the corner nearest to contact goes first: its hits tend to come early.
    if (split > 0 && (nearest >> split & 1)) split |= kUpperFirst;
    return split;
  }
};

}  // namespace ccd_detail
}  // namespace weft
