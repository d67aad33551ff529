// Per-point displacement bounds (docs/collisions.md, "Proximity contacts and displacement bounds"): at each
// query every cloth point gets a distance b it may move from where the query saw it (X0), small enough that
// no vertex-face or edge-edge pair can cross before the next query; every position update is then cut back
// to it. With b = gamma min(d, Q) (gamma < 1/2, d the nearest feature pair the point belongs to, Q the
// query reach of its triangles), a found pair at distance d keeps at least (1 - 2 gamma) d, and a pair the
// query did not find (farther than m_A + m_B, its triangles' margins) keeps more than
// (1 - gamma)(m_A + m_B), which the margins make at least the contact reach.
//
// Distances are folded per point by integer atomic min on fixed-point values (2^-40 m), so the bounds are
// the same bits on every backend and thread count; the truncation counts the points it cut back. No bound
// closes a pair past a separation floor (apart()), and the animated pins of a group take one share of their
// moves (PinShares).
#pragma once
#include "collision/ccd_proximity.hpp"
#include "collision/lbvh.hpp"  // IndexPair
#include "collision/narrow_phase.hpp"
#include "collision/pair_cull.hpp"
#include "core/reduce.hpp"

#include <Kokkos_Core.hpp>
#include <limits>

namespace weft {

namespace bounds_detail {

using Fixed = unsigned long long;
constexpr real kScale = 1099511627776.0;  // 2^40 per metre
constexpr real kLimit = 1.0e6;            // metres: farther counts as this far (2^40 1e6 < 2^64)
constexpr Fixed kFar = Fixed(kLimit * kScale);

// Rounds down, so a folded distance is never larger than the true one.
KOKKOS_INLINE_FUNCTION Fixed to_fixed(real d) { return d < kLimit ? Fixed(max_(d, real(0)) * kScale) : kFar; }
KOKKOS_INLINE_FUNCTION real from_fixed(Fixed f) { return real(f) / kScale; }

// Where point i wants to go: where it stands, plus (at a later query of the substep, `resume`) the
// deficit the last query left a free point, or a pinned point's target while it is short of it.
template <class Points, class Deficit, class Pending, class Weights>
KOKKOS_INLINE_FUNCTION Vec3 wanted_position(const Points& x, const Deficit& deficit, const Pending& pending,
                                            const Weights& w, long i, bool resume) {
  if (!resume) return x(i);
  if (w(i) > 0) return x(i) + deficit(i);
  return pending(i) ? deficit(i) : x(i);
}

// Per point, the move it wants from X0 (its prediction, or the deficit left by the last query; a pinned
// point's, to its target), 0 for the points not averaged: summed, the common translation t. `pinned`: the
// pinned points are averaged, else the free points.
template <class Mem>
struct WantedMove {
  Kokkos::View<const Vec3*, Mem> x, x0, deficit;
  Kokkos::View<const int*, Mem> pending;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<Vec3*, Mem> out;
  bool resume, pinned;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const bool free = w(i) > 0;
    out(i) = free == pinned ? Vec3{0, 0, 0} : wanted_position(x, deficit, pending, w, i, resume) - x0(i);
  }
};

// Per point: the largest move wanted since the last query beside the common translation t, and two
// position sets for the boxes: `xrel`, where the point goes seen from the translating frame (X0; a pinned
// point's target less t), and `xb`, where it goes (X0 + t; a pinned point's target).
// With `reference` (predicted_reference), a bounded point's reference move r is its whole wanted move
// beside t where the query `sweep`s references (0 at a refresh, whose kept pairs were not swept for new
// moves, and once references are off for the frame), and xrel, xb follow it (X0 + r, X0 + t + r).
template <class Mem>
struct PreparePoints {
  Kokkos::View<const Vec3*, Mem> x, x0, deficit;
  Kokkos::View<const int*, Mem> pending;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<real*, Mem> want;
  Kokkos::View<Vec3*, Mem> xrel, xb, ref;
  Kokkos::View<int*, Mem> anchor;
  Kokkos::View<Fixed*, Mem> dmin, qmin;
  Vec3 t;
  bool resume, pins, refresh, reference, sweep;
  Kokkos::View<int*, Mem> touch;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const bool free = pins || w(i) > 0;
    const Vec3 target = wanted_position(x, deficit, pending, w, i, resume);
    dmin(i) = kFar;
    touch(i) = 0;
    if (!refresh) qmin(i) = kFar;  // a refresh keeps the last full query's margins
    // Margins grow with the whole wanted move, with references too: a point's bound beside its reference
    // is gamma Q, and a free sheet held to the floor's Q stretched twice as far (the 100K hanging sheet's
    // p99 strain 0.13 -> 0.29).
    if (free) want(i) = max_(want(i), norm(target - x0(i) - t));
    Vec3 rel = x0(i), go = x0(i) + t;
    if (reference) {
      const Vec3 r = free && sweep ? target - x0(i) - t : Vec3{0, 0, 0};
      ref(i) = r;
      anchor(i) = 0;
      rel += r;
      go += r;
    }
    xrel(i) = free ? rel : x(i) - t;
    xb(i) = free ? go : x(i);
  }
};

// Per point, after a round of the pairs with reference moves: a bounded point newly anchored (2) by a pair
// whose corners want moves too far apart for its distance goes back to the common translation (r = 0).
// Every point's nearest distance starts again for the next round. `all`: every bounded point is anchored
// (the last round, the bounds without references).
template <class Mem>
struct AnchorPoints {
  Kokkos::View<const Vec3*, Mem> x0;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<Vec3*, Mem> xrel, xb, ref;
  Kokkos::View<int*, Mem> anchor;
  Kokkos::View<Fixed*, Mem> dmin;
  Vec3 t;
  bool all, pins;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    dmin(i) = kFar;
    if (!(pins || w(i) > 0) || !(anchor(i) == 2 || (all && anchor(i) == 0))) return;
    anchor(i) = 1;
    ref(i) = Vec3{0, 0, 0};
    xrel(i) = x0(i);
    xb(i) = x0(i) + t;
  }
};

// Per point (full queries with references): the reference move held to the smallest query margin Q of the
// point's triangles, so that the swept boxes grow by at most about their margins (a frame's prediction at
// one substep swept boxes so wide that a 300K skirt's pass took 60 ms, not 8). What is held back is left
// to the bound beside the reference, as without references.
template <class Mem>
struct HoldReference {
  Kokkos::View<const Vec3*, Mem> x0;
  Kokkos::View<const Fixed*, Mem> qmin;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<Vec3*, Mem> ref, xrel, xb;
  Vec3 t;
  bool pins;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    if (!(pins || w(i) > 0)) return;
    const real l2 = norm2(ref(i)), q = from_fixed(qmin(i));
    if (!(l2 > q * q)) return;
    const Vec3 r = (q / sqrt_(l2)) * ref(i);
    ref(i) = r;
    xrel(i) = x0(i) + r;
    xb(i) = x0(i) + t + r;
  }
};

// Per point: where a refresh measures its move from, the end of its reference move at the full query.
template <class Mem>
struct ReferenceEnd {
  Kokkos::View<const Vec3*, Mem> x0, ref;
  Kokkos::View<Vec3*, Mem> xq;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { xq(i) = x0(i) + ref(i); }
};

template <class Mem>
struct MarkAnchored {
  Kokkos::View<const int*, Mem> anchor;
  Kokkos::View<int*, Mem> flag;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { flag(i) = anchor(i) == 2 ? 1 : 0; }
};

// Per triangle: its query margin, from what its corners want to move (a point may move gamma times its
// triangles' margin), between the contact-reach floor and a ceiling (the triangle's longest edge, at
// most twice the floor: a point's bound is held to gamma times its distance to its own mesh's next
// features or the next layer, about that far, so a wider query would only add pairs); each corner keeps
// the smallest margin of its triangles. With `nearest`, nor does the margin grow past the farthest of its
// corners' nearest features at the last query: a bound held by a nearer feature gains nothing from a wider
// query, which only adds pairs (docs/collisions.md, "Margins"; docs/performance.md, "Query margins").
template <class Mem>
struct TriangleMargins {
  Kokkos::View<const int* [3], Mem> tris;
  Kokkos::View<const real*, Mem> floor, ceiling, want, near;
  Kokkos::View<real*, Mem> margin;
  Kokkos::View<Fixed*, Mem> qmin;
  real gamma;
  bool nearest;
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const int a = tris(t, 0), b = tris(t, 1), c = tris(t, 2);
    const real wanted = max_(want(a), max_(want(b), want(c))) / gamma;
    const real cap = nearest ? min_(ceiling(t), max_(near(a), max_(near(b), near(c)))) : ceiling(t);
    const real m = max_(floor(t), min_(wanted, cap));
    margin(t) = m;
    const Fixed f = to_fixed(m);
    Kokkos::atomic_fetch_min(&qmin(a), f);
    Kokkos::atomic_fetch_min(&qmin(b), f);
    Kokkos::atomic_fetch_min(&qmin(c), f);
  }
};

// Per candidate triangle pair: every vertex-face and edge-edge pair of its representative features that
// shares no point, measured at X0, folded into the free points' nearest distances. A pinned (or stopped)
// corner moves to its target whatever the bounds say, so its move is taken off the pair's distance first.
// Collider pairs count only while farther than contact reach: a point in contact with a collider is held
// on its side by the contact, and must stay free to be pushed out.
//
// With `hits` (self pairs, where the cloth stands still at X0), the same distances also decide the pair's
// contacts, as the narrow phase's bits (collision/narrow_phase.hpp): vf_test and ee_test on a pair that
// does not move, whose CCD could only report a pair already touching. One pass over the pairs then gives
// the bounds and the contacts, where the narrow phase measured every feature pair again (twice).
//
// With Ref (predicted_reference; self pairs), each point moves by its reference move r on top of t,
// xend = X0 + r: a feature pair's distance is taken as d - D, D the largest difference of its corners'
// reference moves (a point of a feature moves by a convex combination of its corners' moves, so the pair
// closes by at most D over the reference motion), and a pair with D > (1 - kCoherence) d anchors its
// corners (anchor 2; the caller then runs the pairs again with them on t alone). The swept hulls and the
// reach test follow the reference motion.
template <class Mem, bool Ref = false>
struct PairDistances {
  // Self pairs: A and B the cloth at X0, and `xend` where its points go seen from the translating frame
  // (pinned points move, the others not). Collider pairs: A the cloth where it goes (X0 + t, pinned points
  // at their targets; xend the same), B the colliders at the end of the substep.
  SideMesh<Mem> A, B;
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<const Vec3*, Mem> xend;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<const real*, Mem> margin;
  Kokkos::View<Fixed*, Mem> dmin;
  real detect_scale;
  bool pins;                           // pinned points are bounded too
  Kokkos::View<uint32_t*, Mem> hits;  // empty, or per pair its contact bits
  NarrowSettings ns;
  SideMesh<Mem> As, Bs;               // Ref: the sides swept from X0 (xs) to xend (x)
  Kokkos::View<int*, Mem> anchor;     // Ref: per point, 2 once a pair anchors it
  // Without Ref: a pair whose triangles' boxes are farther apart than every corner's query margin Q (qmin)
  // plus `past` is done before its features are measured (past_bounds; on the device in the cut before
  // this kernel, DisplacementBounds::add_self_pairs). Empty qmin: every pair is measured.
  Kokkos::View<const Fixed*, Mem> qmin;
  Fixed past = 0;
  bool culled = false;  // the pairs are those measures() kept (on the device): no test left to run
  // Empty, or per point 1 once a collider pair is within its contact reach and the collider moves more than
  // that reach over the substep (it pushes the point).
  Kokkos::View<int*, Mem> touch;

  static constexpr real kCoherence = 0.5;  // a pair keeps its corners' references while D <= (1 - this) d
  KOKKOS_INLINE_FUNCTION Vec3 ref_move(const SideMesh<Mem>& S, int v) const {
    return S.collider ? Vec3{0, 0, 0} : xend(v) - S.x(v);
  }

  KOKKOS_INLINE_FUNCTION real pinned_move(const SideMesh<Mem>& S, int v) const {
    return S.collider || pins || w(v) > 0 ? real(0) : norm(xend(v) - S.x(v));
  }
  // How far a collider feature's corners move over the substep (0 on the cloth's side).
  template <int N>
  KOKKOS_INLINE_FUNCTION static real collider_move(const SideMesh<Mem>& S, const int (&p)[N]) {
    real m2 = 0;
    if (S.collider)
      for (int k = 0; k < N; ++k) m2 = max_(m2, norm2(S.x(p[k]) - S.xs(p[k])));
    return sqrt_(m2);
  }
  KOKKOS_INLINE_FUNCTION void fold(const SideMesh<Mem>& S, int v, Fixed f) const {
    if (!S.collider && (pins || w(v) > 0)) Kokkos::atomic_fetch_min(&dmin(v), f);
  }
  // Feature pair of points pa[0..na) on side SA and pb[0..nb) on side SB at distance d, within `reach`
  // (the sum of the two triangles' margins: farther pairs cannot lower any bound).
  template <int NA, int NB>
  KOKKOS_INLINE_FUNCTION void record(const SideMesh<Mem>& SA, const int (&pa)[NA], const SideMesh<Mem>& SB,
                                     const int (&pb)[NB], real d, real reach, real contact) const {
    if constexpr (Ref) {
      real D2 = 0;
      for (int i = 0; i < NA; ++i)
        for (int j = 0; j < NB; ++j) D2 = max_(D2, norm2(ref_move(SA, pa[i]) - ref_move(SB, pb[j])));
      const real D = sqrt_(D2);
      if (!(d - D < reach)) return;
      if (D > (1 - kCoherence) * d) {  // only bounded points have references to give up
        for (int k = 0; k < NA; ++k)
          if (!SA.collider && (pins || w(pa[k]) > 0) && anchor(pa[k]) == 0) anchor(pa[k]) = 2;
        for (int k = 0; k < NB; ++k)
          if (!SB.collider && (pins || w(pb[k]) > 0) && anchor(pb[k]) == 0) anchor(pb[k]) = 2;
      }
      const Fixed f = to_fixed(d - D);
      for (int k = 0; k < NA; ++k) fold(SA, pa[k], f);
      for (int k = 0; k < NB; ++k) fold(SB, pb[k], f);
      return;
    }
    if (!(d < reach)) return;
    if ((SA.collider || SB.collider) && d < contact) {
      if (touch.extent(0) > 0 && (collider_move(SA, pa) > contact || collider_move(SB, pb) > contact)) {
        for (int k = 0; k < NA; ++k)
          if (!SA.collider) touch(pa[k]) = 1;
        for (int k = 0; k < NB; ++k)
          if (!SB.collider) touch(pb[k]) = 1;
      }
      return;
    }
    real ma = 0, mb = 0;
    for (int k = 0; k < NA; ++k) ma = max_(ma, pinned_move(SA, pa[k]));
    for (int k = 0; k < NB; ++k) mb = max_(mb, pinned_move(SB, pb[k]));
    const Fixed f = to_fixed(d - ma - mb);
    for (int k = 0; k < NA; ++k) fold(SA, pa[k], f);
    for (int k = 0; k < NB; ++k) fold(SB, pb[k], f);
  }
  // On the host, a feature pair whose boxes are farther apart on some axis than both its reach and its
  // contact limit is skipped before its distance: its result would be dropped (the pad covers the
  // rounding, as narrow_detail::feature_reach's). On the GPU the extra registers cost more than the
  // distances they spare (as in the narrow phase's feature_tests).
  static constexpr bool kBoxes = Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
  KOKKOS_INLINE_FUNCTION static bool beyond(const Aabb& a, const Aabb& b, real reach, real lim) {
    return narrow_detail::apart(a, b, max_(reach, lim) * (1 + 1e-6) + 1e-9);
  }
  // A lower bound on the distance of any two points of boxes a and b, less the rounding of a distance
  // measured between them (the pads of narrow_detail::feature_reach).
  KOKKOS_INLINE_FUNCTION static real gap(const Aabb& a, const Aabb& b) {
    real g2 = 0;
    for (int i = 0; i < 3; ++i) {
      const real g = max_(real(0), max_(a.lo[i] - b.hi[i], b.lo[i] - a.hi[i]));
      g2 += g * g;
    }
    return sqrt_(g2) * (1 - 1e-6) - 1e-9;
  }
  // A pair that can neither lower a bound nor make a contact. A point's bound reads its nearest distance d
  // only as min(d, Q) (FinishBounds; at a still pass d - 4R against gamma Q less its move, R at most the
  // still distance, which `past` covers), so feature pairs at least Q + past apart change no bound, and
  // none of a pair's features are nearer than its triangles' boxes. Its distances would still lower the
  // points' nearest distance, which only nearest margins read: they measure every pair. In a stack of
  // layers a quarter to a third of the candidate pairs are past every bound (the query reaches two margins).
  // With Ref each feature pair is measured at d - D, and D is at most D' (the two triangles' largest
  // reference moves added), so g - D' stands for g; D' <= g / 2 besides, so the pair anchors nothing.
  // References only shrink over the rounds (anchored points go back to t), so a pair past every bound at
  // the first round stays so at the later ones.
  KOKKOS_INLINE_FUNCTION real largest_reference(const SideMesh<Mem>& S, const int (&p)[3]) const {
    real r2 = 0;
    for (int k = 0; k < 3; ++k) r2 = max_(r2, norm2(ref_move(S, p[k])));
    return sqrt_(r2);
  }
  // Boxes a gap g apart, beyond the contact limit lim: whether f = to_fixed(g - D) is at least every cloth
  // corner's Q plus `past`, corners p of side S (colliders' skipped).
  KOKKOS_INLINE_FUNCTION static bool beyond_contact(real g, real lim) { return g > lim * (1 + 1e-6) + 1e-8; }
  template <int N>
  KOKKOS_INLINE_FUNCTION bool past_every_q(Fixed f, const SideMesh<Mem>& S, const int (&p)[N]) const {
    for (int k = 0; k < N; ++k)
      if (!S.collider && !(f >= qmin(p[k]) + past)) return false;
    return true;
  }
  KOKKOS_INLINE_FUNCTION bool past_bounds(int ta, const int (&ia)[3], int tb, const int (&ib)[3]) const {
    const Aabb ab = expand(expand(Aabb{A.x(ia[0]), A.x(ia[0])}, A.x(ia[1])), A.x(ia[2]));
    const Aabb bb = expand(expand(Aabb{B.x(ib[0]), B.x(ib[0])}, B.x(ib[1])), B.x(ib[2]));
    const real g = gap(ab, bb);
    const real lim = max_(ns.detect_scale, ns.ee_detect_scale) * (narrow_detail::face_th(A, ta) + narrow_detail::face_th(B, tb));
    if (!beyond_contact(g, lim)) return false;
    real D = 0;
    if constexpr (Ref) {
      D = (largest_reference(A, ia) + largest_reference(B, ib)) * (1 + 1e-6) + 1e-9;
      if (!(D <= (1 - kCoherence) * g * (1 - 1e-6))) return false;
    }
    const Fixed f = to_fixed(g - D);
    return past_every_q(f, A, ia) && past_every_q(f, B, ib);
  }
  // On the host, past_bounds per self feature pair (corners pts of the cloth, boxes a and b, contact limit
  // lim): a triangle pair next to another shares a corner and is never past every bound, yet most of its
  // feature pairs are: a sheet's neighbours lie about an edge apart, where Q is under an edge.
  KOKKOS_INLINE_FUNCTION bool past_feature(const Aabb& a, const Aabb& b, const int (&pts)[4], real lim) const {
    if (qmin.extent(0) == 0) return false;
    const real g = gap(a, b);
    return beyond_contact(g, lim) && past_every_q(to_fixed(g), A, pts);
  }
  KOKKOS_INLINE_FUNCTION real margin_of(const SideMesh<Mem>& S, int t) const {
    return S.collider ? detect_scale * narrow_detail::face_th(S, t) : margin(t);
  }
  // A static pair's CCD with separation 0 (narrow_detail::touching) can only find features already touching.
  KOKKOS_INLINE_FUNCTION static bool touches(real d) { return !(d > real(1e-9) * (1 + d)); }
  // Vertex k of triangle TP on side P against triangle TF on side F; whether it is a contact.
  KOKKOS_INLINE_FUNCTION bool vertex_face(const SideMesh<Mem>& P, int TP, int k, const SideMesh<Mem>& F, int TF,
                                          real reach) const {
    const int p = P.tris(TP, k), f[3] = {F.tris(TF, 0), F.tris(TF, 1), F.tris(TF, 2)};
    if (!P.collider && !F.collider && (p == f[0] || p == f[1] || p == f[2])) return false;
    const real r = P.th(p) + narrow_detail::face_th(F, TF);
    const real lim = ns.detect_scale * r;
    if (kBoxes && !Ref) {
      const Aabb pb{P.x(p), P.x(p)}, fb = expand(expand(Aabb{F.x(f[0]), F.x(f[0])}, F.x(f[1])), F.x(f[2]));
      if (beyond(pb, fb, reach, lim)) return false;
      const int pts[4] = {p, f[0], f[1], f[2]};
      if (!P.collider && !F.collider && past_feature(pb, fb, pts, lim)) return false;
    }
    real u, v, s;
    const real d2 = point_triangle_distance2(P.x(p), F.x(f[0]), F.x(f[1]), F.x(f[2]), u, v, s);
    const real d = sqrt_(d2);
    const int pp[1] = {p};
    record(P, pp, F, f, d, reach, detect_scale * r);
    return (d2 < lim * lim && narrow_detail::owns_closest_feature(F, TF, u, v, s)) || touches(d);
  }
  // Whether a pair has no feature pair to measure: past every bound (with `past`), or its triangles (with
  // Ref, swept over their reference moves) apart along either normal by more than the reach (wider than any
  // contact's).
  KOKKOS_INLINE_FUNCTION bool skipped(int ta, const int (&ia)[3], int tb, const int (&ib)[3], real reach,
                                      bool past) const {
    if (past && qmin.extent(0) > 0 && past_bounds(ta, ia, tb, ib)) return true;
    return Ref ? pair_cull_detail::swept_apart(As, ia, Bs, ib, reach) : pair_cull_detail::swept_apart(A, ia, B, ib, reach);
  }
  KOKKOS_INLINE_FUNCTION bool measures(long i) const {
    const int ta = pairs(i).first, tb = pairs(i).second;
    const int ia[3] = {A.tris(ta, 0), A.tris(ta, 1), A.tris(ta, 2)}, ib[3] = {B.tris(tb, 0), B.tris(tb, 1), B.tris(tb, 2)};
    return !skipped(ta, ia, tb, ib, margin_of(A, ta) + margin_of(B, tb), true);
  }
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int ta = pairs(i).first, tb = pairs(i).second;
    const real reach = margin_of(A, ta) + margin_of(B, tb);
    const bool contacts = hits.extent(0) > 0;
    const int ia[3] = {A.tris(ta, 0), A.tris(ta, 1), A.tris(ta, 2)}, ib[3] = {B.tris(tb, 0), B.tris(tb, 1), B.tris(tb, 2)};
    // Inline, the test past every bound pays on the host only (add_self_pairs).
    if (!culled && skipped(ta, ia, tb, ib, reach, kBoxes)) {
      if (contacts) hits(i) = 0;
      return;
    }
    uint32_t hit = 0;
    const uint8_t ra = A.rmask(ta), rb = B.rmask(tb);
    for (int k = 0; k < 3; ++k) {
      if (((ra >> k) & 1) && vertex_face(A, ta, k, B, tb, reach)) hit |= 1u << k;
      if (((rb >> k) & 1) && vertex_face(B, tb, k, A, ta, reach)) hit |= 1u << (3 + k);
    }
    for (int ka = 0; ka < 3; ++ka) {
      if (!((ra >> (3 + ka)) & 1)) continue;
      const int ea[2] = {ia[ka], ia[(ka + 1) % 3]};
      for (int kb = 0; kb < 3; ++kb) {
        if (!((rb >> (3 + kb)) & 1)) continue;
        const int eb[2] = {ib[kb], ib[(kb + 1) % 3]};
        if (!B.collider && narrow_detail::shares(ea[0], ea[1], eb[0], eb[1])) continue;
        const real th = max_(A.th(ea[0]), A.th(ea[1])) + max_(B.th(eb[0]), B.th(eb[1]));
        const real lim = ns.ee_detect_scale * th;
        if (kBoxes && !Ref) {
          const Aabb ab = expand(Aabb{A.x(ea[0]), A.x(ea[0])}, A.x(ea[1])), bb = expand(Aabb{B.x(eb[0]), B.x(eb[0])}, B.x(eb[1]));
          if (beyond(ab, bb, reach, lim)) continue;
          const int pts[4] = {ea[0], ea[1], eb[0], eb[1]};
          if (!B.collider && past_feature(ab, bb, pts, lim)) continue;
        }
        real s, t;
        const real d2 = segment_segment_distance2(A.x(ea[0]), A.x(ea[1]), B.x(eb[0]), B.x(eb[1]), s, t);
        const real d = sqrt_(d2);
        record(A, ea, B, eb, d, reach, detect_scale * th);
        if (!contacts) continue;
        const bool crossing_ok = !ns.self || narrow_detail::not_parallel(A.x(ea[1]) - A.x(ea[0]), B.x(eb[1]) - B.x(eb[0]),
                                                                          ns.min_sin_angle);
        if (crossing_ok && (d2 < lim * lim || touches(d))) hit |= 1u << (6 + 3 * ka + kb);
      }
    }
    if (contacts) hits(i) = hit;
  }
};

// Whether a pair has a feature pair to measure: PairDistances::measures, as a predicate for PairCull::keep_if.
template <class Mem, bool Ref = false>
struct MeasuredPairs {
  PairDistances<Mem, Ref> distances;
  KOKKOS_INLINE_FUNCTION bool operator()(long i) const { return distances.measures(i); }
};

// Beside gamma d, at most (d - sep) / 2: a pair that cannot part (pinned corners driven together, a jam)
// keeps (1 - 2 gamma) of its distance per query, which left alone shrinks towards 0 until rounding decides
// which side a point lies on (the twist crossed itself at 1e-13 m); held back here it never closes past
// sep. Where gamma d is the smaller, as for every pair farther than sep / (1 - 2 gamma), the same bits.
KOKKOS_INLINE_FUNCTION real apart(real b, Fixed d, real sep) {
  return min_(b, max_(real(0), real(0.5) * (from_fixed(d) - sep)));
}

// Per point: b = gamma min(d, Q) for points that move (never closing a pair past sep: apart()); the wanted
// move starts again from 0. On a refresh (pairs kept from the last full query, at xq), the point's move
// since then beside the translations since then (tq) is spent from gamma Q: however many refreshes follow,
// a point stays within gamma Q of where the full query saw it, so a pair that query did not find still
// keeps its (1 - gamma)(m_A + m_B).
template <class Mem>
struct FinishBounds {
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<const Fixed*, Mem> dmin, qmin;
  Kokkos::View<real*, Mem> bound, want, near;
  Kokkos::View<const Vec3*, Mem> x0, xq;
  Vec3 tq;
  real gamma, sep;
  bool pins, refresh;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    near(i) = from_fixed(dmin(i));
    if (!(pins || w(i) > 0)) {
      bound(i) = from_fixed(kFar);
      if (!refresh) want(i) = 0;
      return;
    }
    if (!refresh) {
      const Fixed f = dmin(i) < qmin(i) ? dmin(i) : qmin(i);
      bound(i) = apart(gamma * from_fixed(f), dmin(i), sep);
      want(i) = 0;
      return;
    }
    const real left = gamma * from_fixed(qmin(i)) - norm(x0(i) - xq(i) - tq);
    bound(i) = max_(real(0), min_(apart(gamma * from_fixed(dmin(i)), dmin(i), sep), left));
  }
};

// Per point (that moves): whether it has spent more than half of what a refresh would leave it (gamma Q
// since the last full query).
template <class Mem>
struct MarkSpent {
  Kokkos::View<const Vec3*, Mem> x, xq;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<const Fixed*, Mem> qmin;
  Kokkos::View<int*, Mem> flag;
  Vec3 tq;
  real gamma;
  bool pins;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    flag(i) = (pins || w(i) > 0) && norm(x(i) - xq(i) - tq) > real(0.5) * gamma * from_fixed(qmin(i)) ? 1 : 0;
  }
};

constexpr Fixed kWhole = Fixed(kScale);  // a share of 1

// Per pin of a group (at a query's truncation): the fraction of its move beside its base that its bound
// allows, folded by integer atomic min (rounded down) into its group's share: every pin of the group then
// takes that share of its move, within its own bound, and a jammed handle stalls as a whole.
template <class Mem>
struct PinShares {
  Kokkos::View<const Vec3*, Mem> x, x0, deficit, ref;
  Kokkos::View<const int*, Mem> pending, group;
  Kokkos::View<const real*, Mem> w, bound;
  Kokkos::View<Fixed*, Mem> share;
  Vec3 t;
  bool resume, reference;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const int g = group(i);
    if (g < 0) return;
    Vec3 base = x0(i) + t;
    if (reference) base += ref(i);
    const real l2 = norm2(wanted_position(x, deficit, pending, w, i, resume) - base), b = bound(i);
    if (l2 > b * b) Kokkos::atomic_fetch_min(&share(g), Fixed(b / sqrt_(l2) * kScale));
  }
};

// A point cut back counts 1, and kPushed more while a moving collider is within its contact reach (pushing
// it): one sum of the marks gives both counts.
constexpr long kPushed = 1L << 32;
KOKKOS_INLINE_FUNCTION long cut_mark(int touch) { return touch ? 1 + kPushed : 1; }

// Per point (that moves: bounds of the others are far): cut its move from X0 + t back to its bound; counts the points cut back and keeps the largest
// move wanted (the next query's margins grow to let it through). With `carry`, the part cut off is kept
// as the point's deficit (the prediction's motion, handed on to the next query); first adds the deficit
// kept so far.
template <class Mem>
struct Truncate {
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<const Vec3*, Mem> x0;
  Kokkos::View<const real*, Mem> w, bound;
  Kokkos::View<real*, Mem> want;
  Kokkos::View<Vec3*, Mem> deficit;  // a free point's move still to hand on; a pinned point's target
  Kokkos::View<int*, Mem> pending;   // a pinned point still short of its target
  Kokkos::View<long*, Mem> cut;       // per point: cut back by this truncation (cut_mark)
  Kokkos::View<long*, Mem> tally;     // per point: truncations that cut it back since the last take
  Kokkos::View<const int*, Mem> touch;  // per point: a moving collider within its contact reach at the query
  Kokkos::View<const Vec3*, Mem> ref;  // with `reference`, the point's reference move beside t
  Vec3 t;
  bool carry, resume, reference;
  Kokkos::View<const int*, Mem> group;     // empty, or per point its pin group (-1: none)
  Kokkos::View<const Fixed*, Mem> share;   // per pin group, the fraction of their moves its pins take
  real excess = 0;  // a point cut back counts (cut) when it wanted more than (1 + excess) times its bound
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const bool pinned = !(w(i) > 0);
    // A pinned point goes on to its target itself, so it lands on it exactly.
    const Vec3 xi = wanted_position(x, deficit, pending, w, i, resume);
    Vec3 base = x0(i) + t;
    if (reference) base += ref(i);
    const Vec3 d = xi - base;
    const real l2 = norm2(d), b = bound(i);
    // A pin of a group some pin of which is held short: the group's share of its move (PinShares).
    const Fixed f = group.extent(0) > 0 && group(i) >= 0 ? share(group(i)) : kWhole;
    if (f < kWhole) {
      want(i) = max_(want(i), sqrt_(l2));
      x(i) = base + from_fixed(f) * d;
      deficit(i) = xi;
      pending(i) = 1;
      cut(i) = cut_mark(touch(i));
      ++tally(i);
      return;
    }
    if (!(l2 > b * b)) {
      if (resume) x(i) = xi;
      if (carry) {
        deficit(i) = Vec3{0, 0, 0};
        pending(i) = 0;
      }
      cut(i) = 0;
      return;
    }
    const real l = sqrt_(l2);
    want(i) = max_(want(i), l);
    const Vec3 kept = base + (b / l) * d;
    x(i) = kept;
    if (carry) {
      deficit(i) = pinned ? xi : xi - kept;
      pending(i) = pinned ? 1 : 0;
    }
    cut(i) = touch(i) || !(excess > 0) || l > (1 + excess) * b ? cut_mark(touch(i)) : 0;
    ++tally(i);
  }
};

// Per bounded point (at a refresh that may be still): how far it has moved, beside the translations since,
// from where the last measured pass saw it (xm); a pinned point also the move it still wants beside t.
// The largest of these, R, bounds how much any measured pair has closed since and can close by its pinned
// corners: a still pass takes its distances as d - 4R (StillDistances).
template <class Mem>
struct StillMoves {
  Kokkos::View<const Vec3*, Mem> x, x0, xm, deficit;
  Kokkos::View<const int*, Mem> pending;
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<real*, Mem> moved;
  Vec3 tm, t;
  bool resume, pins;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const bool free = w(i) > 0;
    if (!(pins || free)) {
      moved(i) = 0;
      return;
    }
    real m = norm(x0(i) - xm(i) - tm);
    if (!free) m += norm(wanted_position(x, deficit, pending, w, i, resume) - x0(i) - t);
    moved(i) = m;
  }
};

// Per point, at a still pass: the nearest self distance of the last measured pass less `less` (4R rounded
// up), never below 0.
template <class Mem>
struct StillDistances {
  Kokkos::View<const Fixed*, Mem> dself;
  Kokkos::View<Fixed*, Mem> dmin;
  Fixed less;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const Fixed d = dself(i);
    dmin(i) = d > less ? d - less : Fixed(0);
  }
};

template <class Mem>
struct MarkMovable {
  Kokkos::View<const real*, Mem> w;
  Kokkos::View<int*, Mem> flag;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { flag(i) = w(i) > 0 ? 1 : 0; }
};

}  // namespace bounds_detail

struct BoundSettings {
  real gamma = 0.4;          // a point moves at most gamma times its nearest distance (< 1/2)
  real detect_scale = 1.25;  // the contact reach, as the narrow phase's (times the two thicknesses)
  bool bound_pins = true;    // pinned points reach their targets within their bounds too (else they jump)
  bool nearest_margins = false;  // margins grow no further than their corners' nearest features (TriangleMargins)
  bool predicted_reference = false;  // each point bounded beside its own wanted move (PairDistances' Ref)
  int max_anchor_rounds = 3;     // then every point is anchored to t, and references rest until the next frame
  real still_distance = 0;       // a refresh is still while no point moved more than this since the last measured pass (0: never)
  real separation = 0;           // no pair is closed past this (FinishBounds, apart())
  real early_excess = 0;         // a point cut back counts towards an early pass when it wanted more than
                                 // (1 + this) times its bound (Truncate)
};

// The bounds' working memory and kernels. Usage per query: prepare() (the common translation and the
// margins for the boxes), then the caller builds boxes and queries pairs, add_pairs() for each pair list,
// finish(), truncate_prediction(); truncate() after every position update.
//
// Bounds hold a point's move beside the common translation t of the query (the mean move the cloth's
// pins want, or with no pins its free points'): a rigid translation changes no distance between cloth
// features, so cloth that falls or sways as a whole is not held to its mesh's spacing per query. Colliders
// do not translate with it; their pairs are met where the cloth goes (X0 + t), with the narrow phase's CCD
// over the way there.
template <class Exec>
class DisplacementBounds {
 public:
  using Mem = typename Exec::memory_space;
  template <class T>
  using View = Kokkos::View<T, Mem>;

  // floor(t): triangle t's smallest query margin, the reach an unfound pair must stay beyond; ceiling(t):
  // its largest.
  DisplacementBounds(long points, const View<real*>& floor, const View<real*>& ceiling, const BoundSettings& s)
      : s_(s), floor_(floor), ceiling_(ceiling), x0_("weft::bounds_x0", points),
        xrel_("weft::bounds_xrel", points), xb_("weft::bounds_xb", points), bound_("weft::bounds", points),
        want_("weft::bounds_want", points), margin_("weft::bounds_margin", floor.extent(0)),
        scratch_("weft::bounds_scratch", points), dmin_("weft::bounds_dmin", points),
        qmin_("weft::bounds_qmin", points), deficit_("weft::bounds_deficit", points), pending_("weft::bounds_pending", points),
        cut_("weft::bounds_cut", points), tally_("weft::bounds_tally", points), flag_("weft::bounds_flag", points), xq_("weft::bounds_xq", points),
        sum_("weft::bounds_sum"), near_("weft::bounds_near", points), touch_("weft::bounds_touch", points),
        ref_("weft::bounds_ref", s.predicted_reference ? points : 0),
        anchor_("weft::bounds_anchor", s.predicted_reference ? points : 0) {
    Kokkos::deep_copy(near_, bounds_detail::from_fixed(bounds_detail::kFar));
  }

  // Whether a full query now sweeps reference moves: from each frame's start (retry_references()) until a
  // query has had to anchor every point. Where the cloth's motion is not its prediction (a stack falling
  // onto itself, a frame's motion in one substep) the rounds spread anchors over the whole cloth at every
  // query, and each round costs as much as the pairs' distances without references.
  bool references() const { return s_.predicted_reference && active_; }
  void retry_references() { active_ = true; }
  // Pins that hold back together: per point its group (-1: none), `groups` of them.
  void set_pin_groups(const View<int*>& group, long groups) {
    pin_group_ = group;
    pin_share_ = View<bounds_detail::Fixed*>("weft::bounds_pin_share", groups);
  }
  bool sweeps() const { return sweep_; }  // the last prepare()'s query sweeps reference moves

  long movable() const { return movable_ > 0 ? movable_ : 0; }  // counted at the first prepare()
  const View<Vec3*>& x0() const { return x0_; }
  const View<Vec3*>& relative_end() const { return xrel_; }  // seen from the translating frame
  const View<Vec3*>& end() const { return xb_; }             // X0 + t, pinned points at their targets
  const View<real*>& margins() const { return margin_; }
  const View<real*>& bounds() const { return bound_; }
  Vec3 translation() const { return t_; }

  // How many of the points that move have spent more than half of what a refresh at positions x would
  // leave them; more than all of them before the first full query. Reads one sum back.
  long spent(const Exec& exec, const View<Vec3*>& x, const View<real*>& w) const {
    if (!queried_) return std::numeric_limits<long>::max();
    Kokkos::parallel_for("weft::bounds_spent", Kokkos::RangePolicy<Exec>(exec, 0, x.extent(0)),
                         bounds_detail::MarkSpent<Mem>{x, xq_, w, qmin_, flag_, tq_, s_.gamma, s_.bound_pins});
    return sum_counts(exec, flag_);
  }

  // A new query from positions `from` (X0) while the cloth is at x; `first`: the substep's first query
  // (the prediction is what the points want), else they want the deficit the last query left. A full
  // query sets the triangles' margins; a `refresh` keeps them, and the pairs (the caller's), from the last
  // full one. Reads three sums back, in one copy.
  // `free_frame`: t is the free points' mean even where the cloth has pins.
  void prepare(const Exec& exec, const View<Vec3*>& from, const View<Vec3*>& x, const View<real*>& w,
               const View<int* [3]>& tris, bool first, bool refresh = false, bool free_frame = false) {
    using namespace bounds_detail;
    if (from.data() != x0_.data()) Kokkos::deep_copy(exec, x0_, from);
    const long n = long(x.extent(0));
    resume_ = !first;
    refresh_ = refresh && queried_ && s_.bound_pins;  // unbounded pins sweep their boxes to their targets
    if (movable_ < 0) {  // the points that move (w > 0), counted once from the solver's inverse masses
      Kokkos::parallel_for("weft::bounds_movable", Kokkos::RangePolicy<Exec>(exec, 0, n),
                           bounds_detail::MarkMovable<Mem>{w, flag_});
      movable_ = sum_counts(exec, flag_);
    }
    // The cloth's reference motion: with pins, theirs (what it hangs from; on still pins t = 0, so they
    // stay where they stand). With the free points' mean the jammed twist drifted off, pins and all, to
    // 20 m/s, and a sheet hanging from two still corners dragged them along as it swung and fell away.
    // With no pins, or with `free_frame`, the free points'. Its sum is one reduction of vectors, read
    // back once.
    const long pinned = n - movable_;
    const bool by_pins = s_.bound_pins && pinned > 0 && !free_frame;
    const long averaged = by_pins ? pinned : movable_;
    t_ = Vec3{0, 0, 0};
    if (movable_ > 0) {
      Kokkos::parallel_for("weft::bounds_wanted", Kokkos::RangePolicy<Exec>(exec, 0, n),
                           WantedMove<Mem>{x, x0_, deficit_, pending_, w, scratch_, resume_, by_pins});
      reduce_fixed_into(exec, scratch_, sum_, SumOp{});
      Vec3 sum;
      Kokkos::deep_copy(exec, sum, sum_);
      exec.fence();
      t_ = sum / real(averaged);
    }
    sweep_ = references() && !refresh_;
    Kokkos::parallel_for("weft::bounds_prepare", Kokkos::RangePolicy<Exec>(exec, 0, n),
                         PreparePoints<Mem>{x, x0_, deficit_, pending_, w, want_, xrel_, xb_, ref_, anchor_, dmin_,
                                            qmin_, t_, resume_, s_.bound_pins, refresh_, s_.predicted_reference,
                                            sweep_, touch_});
    still_ = refresh_ && measured_ && s_.still_distance > 0 && still_moves(exec, x, w) <= s_.still_distance;
    if (still_)
      Kokkos::parallel_for("weft::bounds_still", Kokkos::RangePolicy<Exec>(exec, 0, n),
                           StillDistances<Mem>{dself_, dmin_, to_fixed(4 * moved_max_) + 1});
    if (refresh_) return;
    Kokkos::parallel_for("weft::bounds_margins", Kokkos::RangePolicy<Exec>(exec, 0, tris.extent(0)),
                         TriangleMargins<Mem>{tris, floor_, ceiling_, want_, near_, margin_, qmin_, s_.gamma,
                                               s_.nearest_margins});
    if (sweep_)
      Kokkos::parallel_for("weft::bounds_hold_reference", Kokkos::RangePolicy<Exec>(exec, 0, n),
                           HoldReference<Mem>{x0_, qmin_, w, ref_, xrel_, xb_, t_, s_.bound_pins});
    Kokkos::deep_copy(exec, xq_, x0_);
    tq_ = Vec3{0, 0, 0};
    queried_ = true;
  }

  // The feature pairs of candidate triangle pairs [0, n) between the cloth (A) and side B; xend as
  // PairDistances says.
  // With `hits` (self pairs, A and B the cloth standing at X0), also each pair's contact bits under `ns`.
  void add_pairs(const Exec& exec, const SideMesh<Mem>& A, const SideMesh<Mem>& B, const View<IndexPair*>& pairs,
                 long n, const View<Vec3*>& xend, const View<real*>& w, const View<uint32_t*>& hits = {},
                 const NarrowSettings& ns = {}) {
    if (n == 0) return;
    Kokkos::parallel_for("weft::bounds_pairs", Kokkos::RangePolicy<Exec>(exec, 0, n), distances(A, B, pairs, xend, w, hits, ns));
  }

  // Whether add_self_pairs cuts the pairs first: on the device. Inside the distances' kernel, skipped and
  // measured pairs side by side in a warp saved nothing (the 50-layer drop 661 -> 700 ms a frame; cut
  // first, 658 -> 477 ms); on the host the tests inline are faster.
  static constexpr bool kCutSelfPairs = !Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;

  // Self pairs without references (A and B the cloth at X0), as add_pairs. With `cut_first` the pairs that
  // measure nothing (PairDistances::measures) are cut by a kernel of their own and the rest compacted in
  // order, into `cull`'s memory (one count read back). Sets `measured` and `nm` to the pairs measured,
  // which `hits` follows; the contacts come out in the same order, so the bits are the same either way.
  void add_self_pairs(const Exec& exec, const SideMesh<Mem>& cloth, const View<IndexPair*>& pairs, long n,
                      const View<Vec3*>& xend, const View<real*>& w, const View<uint32_t*>& hits,
                      const NarrowSettings& ns, PairCull<Exec>& cull, View<const IndexPair*>& measured, long& nm,
                      bool cut_first = kCutSelfPairs) {
    measured = pairs;
    nm = n;
    if (n == 0) return;
    bounds_detail::PairDistances<Mem> pd = distances(cloth, cloth, pairs, xend, w, hits, ns);
    if (cut_first) {
      measured = cull.keep_if(exec, View<const IndexPair*>(pairs), n, bounds_detail::MeasuredPairs<Mem>{pd}, nm);
      if (nm == 0) return;
      pd.pairs = measured;
      pd.culled = true;
    }
    Kokkos::parallel_for("weft::bounds_pairs", Kokkos::RangePolicy<Exec>(exec, 0, nm), pd);
  }

  // A still pass (prepare() decided): the caller keeps the last measured pass's self contacts, and its
  // nearest self distances, less what the cloth can have closed since, bound the points (docs/collisions.md,
  // "Still passes"). Where still passes are on, a pass that measured its self pairs records them here: their
  // distances (the points' nearest so far, before any collider pair) and where it stood.
  bool still() const { return still_; }
  void measured_self(const Exec& exec) {
    if (!(s_.still_distance > 0)) return;
    const long n = long(x0_.extent(0));
    if (long(dself_.extent(0)) != n) {
      dself_ = View<bounds_detail::Fixed*>("weft::bounds_dself", n);
      xm_ = View<Vec3*>("weft::bounds_xm", n);
      moved_ = View<real*>("weft::bounds_moved", n);
    }
    Kokkos::deep_copy(exec, dself_, dmin_);
    Kokkos::deep_copy(exec, xm_, x0_);
    tm_ = Vec3{0, 0, 0};
    measured_ = true;
  }

  // Self pairs (A the cloth at X0) with reference moves: the pairs run in rounds until no pair anchors a
  // point it had not (each round reads one count back); after max_anchor_rounds every point is anchored
  // and a last round gives the bounds without references. The first round also writes `hits` (the
  // contacts stand at X0 whatever the references). As add_self_pairs, with `cut_first` the pairs that
  // measure nothing are cut first (once: references only shrink over the rounds), `measured` and `nm` the
  // rest, which `hits` follows. Returns the rounds run.
  int add_self_pairs_with_references(const Exec& exec, const SideMesh<Mem>& cloth, const View<IndexPair*>& pairs,
                                     long n, const View<real*>& w, const View<uint32_t*>& hits,
                                     const NarrowSettings& ns, PairCull<Exec>& cull, View<const IndexPair*>& measured,
                                     long& nm, bool cut_first = kCutSelfPairs) {
    using namespace bounds_detail;
    measured = pairs;
    nm = n;
    if (n == 0) return 0;
    SideMesh<Mem> swept = cloth;
    swept.x = xrel_;
    const long points = long(x0_.extent(0));
    PairDistances<Mem, true> pd{cloth, cloth, pairs, xrel_, w, margin_, dmin_, s_.detect_scale,
                                s_.bound_pins, hits, ns, swept, swept, anchor_};
    skip_past_bounds(pd);
    if (cut_first) {
      measured = cull.keep_if(exec, View<const IndexPair*>(pairs), n, MeasuredPairs<Mem, true>{pd}, nm);
      if (nm == 0) return 0;
      pd.pairs = measured;
      pd.culled = true;
    }
    n = nm;
    for (int round = 0;; ++round) {
      pd.hits = round == 0 ? hits : View<uint32_t*>();
      Kokkos::parallel_for("weft::bounds_pairs", Kokkos::RangePolicy<Exec>(exec, 0, n), pd);
      Kokkos::parallel_for("weft::bounds_anchored", Kokkos::RangePolicy<Exec>(exec, 0, points),
                           MarkAnchored<Mem>{anchor_, flag_});
      const long anchored = sum_counts(exec, flag_);
      stats_anchored_ += anchored;
      if (anchored == 0) return round + 1;
      const bool all = round + 1 >= s_.max_anchor_rounds;
      if (all) active_ = false;
      Kokkos::parallel_for("weft::bounds_anchor", Kokkos::RangePolicy<Exec>(exec, 0, points),
                           AnchorPoints<Mem>{x0_, w, xrel_, xb_, ref_, anchor_, dmin_, t_, all, s_.bound_pins});
      if (all) {
        pd.hits = View<uint32_t*>();
        Kokkos::parallel_for("weft::bounds_pairs", Kokkos::RangePolicy<Exec>(exec, 0, n), pd);
        return round + 2;
      }
    }
  }

  // Points anchored to the common translation by reference rounds since the last call.
  long take_anchored() {
    const long a = stats_anchored_;
    stats_anchored_ = 0;
    return a;
  }

  void finish(const Exec& exec, const View<real*>& w) {
    Kokkos::parallel_for("weft::bounds_finish", Kokkos::RangePolicy<Exec>(exec, 0, bound_.extent(0)),
                         bounds_detail::FinishBounds<Mem>{w, dmin_, qmin_, bound_, want_, near_, x0_, xq_, tq_, s_.gamma,
                                                          s_.separation, s_.bound_pins, refresh_});
    // With references a point that followed its own stands near X0 + r, not X0, at the next refresh.
    if (sweep_)
      Kokkos::parallel_for("weft::bounds_reference_end", Kokkos::RangePolicy<Exec>(exec, 0, x0_.extent(0)),
                           bounds_detail::ReferenceEnd<Mem>{x0_, ref_, xq_});
    tq_ = tq_ + t_;
    tm_ = tm_ + t_;
  }

  // Cuts every point back to its bound around X0 + t, marking the points cut back.
  void truncate(const Exec& exec, const View<Vec3*>& x, const View<real*>& w) {
    Kokkos::parallel_for("weft::bounds_truncate", Kokkos::RangePolicy<Exec>(exec, 0, x.extent(0)), truncate_step(x, w));
  }
  // truncate() as a per-point step, for a kernel that moves each point first (the Jacobi contacts' apply).
  bounds_detail::Truncate<Mem> truncate_step(const View<Vec3*>& x, const View<real*>& w) const {
    return {x,    x0_,  w,    bound_, want_, deficit_, pending_, cut_, tally_, touch_, ref_, t_,
            false, false, s_.predicted_reference, View<int*>(), pin_share_, s_.early_excess};
  }

  // At a query: the prediction cut back (first query of a substep), or the deficit left by the last query
  // added and cut back again. The part cut off is kept for the next query: in XPBD, motion cut off and
  // not handed on would be lost, as damping.
  void truncate_prediction(const Exec& exec, const View<Vec3*>& x, const View<real*>& w) {
    run_truncate(exec, x, w, true, resume_);
  }

  // Points the last truncation cut back (an integer sum, read back). One counter bumped by every thread
  // instead cost 10 ms a truncation on the H100 where most points were cut back.
  long cut_count(const Exec& exec) const { return cut_counts(exec).all; }
  // Points cut back, summed over every truncation since the last call (one sum, read back), for the
  // frame's statistics: the checks for an early pass read counts only while one could run.
  long take_cut_tally(const Exec& exec) {
    const long n = sum_counts(exec, tally_);
    Kokkos::deep_copy(exec, tally_, 0L);
    return n;
  }
  // The same, and how many of them had a moving collider within their contact reach.
  struct CutCounts {
    long all, pushed;
  };
  CutCounts cut_counts(const Exec& exec) const {
    const long s = sum_counts(exec, cut_);
    return {s & (bounds_detail::kPushed - 1), s / bounds_detail::kPushed};
  }

 private:
  // R: the largest StillMoves since the last measured pass (an exact maximum, read back once).
  real still_moves(const Exec& exec, const View<Vec3*>& x, const View<real*>& w) {
    Kokkos::parallel_for("weft::bounds_still_moves", Kokkos::RangePolicy<Exec>(exec, 0, x.extent(0)),
                         bounds_detail::StillMoves<Mem>{x, x0_, xm_, deficit_, pending_, w, moved_, tm_, t_, resume_,
                                                        s_.bound_pins});
    moved_max_ = max_fixed(exec, moved_);
    return moved_max_;
  }

  // A query's truncation (carry) gives pin groups their shares first; the truncations after the sweeps
  // find every pin where the query left it.
  void run_truncate(const Exec& exec, const View<Vec3*>& x, const View<real*>& w, bool carry, bool resume) {
    using namespace bounds_detail;
    const bool groups = carry && pin_share_.extent(0) > 0;
    if (groups) {
      Kokkos::deep_copy(exec, pin_share_, kWhole);
      Kokkos::parallel_for("weft::bounds_pin_shares", Kokkos::RangePolicy<Exec>(exec, 0, x.extent(0)),
                           PinShares<Mem>{x, x0_, deficit_, ref_, pending_, pin_group_, w, bound_, pin_share_, t_, resume,
                                          s_.predicted_reference});
    }
    Kokkos::parallel_for("weft::bounds_truncate", Kokkos::RangePolicy<Exec>(exec, 0, x.extent(0)),
                         Truncate<Mem>{x, x0_, w, bound_, want_, deficit_, pending_, cut_, tally_, touch_, ref_, t_, carry, resume,
                                       s_.predicted_reference, groups ? pin_group_ : View<int*>(), pin_share_,
                                       s_.early_excess});
  }

  bounds_detail::PairDistances<Mem> distances(const SideMesh<Mem>& A, const SideMesh<Mem>& B,
                                              const View<IndexPair*>& pairs, const View<Vec3*>& xend,
                                              const View<real*>& w, const View<uint32_t*>& hits,
                                              const NarrowSettings& ns) const {
    bounds_detail::PairDistances<Mem> pd{A, B, pairs, xend, w, margin_, dmin_, s_.detect_scale, s_.bound_pins, hits, ns};
    pd.touch = touch_;
    skip_past_bounds(pd);
    return pd;
  }
  // Pairs past every bound are skipped (PairDistances::past_bounds) unless nearest margins read every
  // distance. At a still pass d - 4R stands for a nearest distance d, R at most the still distance
  // (StillDistances).
  template <bool Ref>
  void skip_past_bounds(bounds_detail::PairDistances<Mem, Ref>& pd) const {
    if (!s_.bound_pins || s_.nearest_margins) return;
    pd.qmin = qmin_;
    pd.past = s_.still_distance > 0 ? bounds_detail::to_fixed(4 * s_.still_distance) + 2 : 0;
  }

  BoundSettings s_;
  long movable_ = -1;
  View<real*> floor_, ceiling_;
  View<Vec3*> x0_, xrel_, xb_;
  View<real*> bound_, want_, margin_;
  View<Vec3*> scratch_;  // per point, its wanted move (summed for the translation)
  View<bounds_detail::Fixed*> dmin_, qmin_;
  View<Vec3*> deficit_;  // per point, the prediction's motion still to hand on (pinned: its target)
  View<int*> pending_;   // pinned points short of their target
  View<long*> cut_;        // per point, cut_mark() where the last truncation cut it back, else 0
  View<long*> tally_;      // per point, the truncations that cut it back since take_cut_tally()
  View<int*> flag_;        // per point, for counts
  View<int*> touch_;       // per point, 1 while a moving collider of this query is within its contact reach
  View<Vec3*> xq_;        // X0 of the last full query
  View<Vec3> sum_;        // the wanted moves' sum, for the common translation
  View<real*> near_;      // per point, its nearest feature at the last query (far before the first)
  View<int*> pin_group_;          // per point, its pin group (collision/pin_groups.hpp) or -1
  View<bounds_detail::Fixed*> pin_share_;  // per pin group, the share of their moves its pins take
  View<Vec3*> ref_;       // predicted_reference: per point, its reference move beside t (0 once anchored)
  View<int*> anchor_;     // predicted_reference: 0 on its reference, 2 anchored this round, 1 before
  long stats_anchored_ = 0;
  Vec3 t_{0, 0, 0}, tq_{0, 0, 0};  // this query's translation; the sum of those since the last full query
  bool resume_ = false, refresh_ = false, queried_ = false;
  bool active_ = true, sweep_ = false;  // references this frame; this query sweeps them
  // Still passes: the last measured pass's nearest self distances and positions (X0); the translations
  // since; this pass's R and whether it is still.
  View<bounds_detail::Fixed*> dself_;
  View<Vec3*> xm_;
  View<real*> moved_;
  Vec3 tm_{0, 0, 0};
  real moved_max_ = 0;
  bool measured_ = false, still_ = false;
};

}  // namespace weft
