// Narrow phase for one triangle pair: the feature pairs its representative features produce (paper sec. 3,
// "R-Triangle"), each tested by proximity at the current positions and by continuous collision detection
// over the substep. Bits of the result: 0-2 vertex of A vs face B, 3-5 vertex of B vs face A, 6-14 edge of A
// vs edge of B (6 + 3 ka + kb). Features sharing a point are never paired.
#pragma once
#include "collision/aabb.hpp"
#include "collision/ccd.hpp"
#include "collision/ccd_proximity.hpp"
#include "collision/contact.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

// One side of a pair: a cloth or collider mesh at the start (xs) and end (x) of the motion tested, and at
// the start of the substep (xo), which decides the side of a two-sided contact. xs is xo unless collision
// passes test only the motion since the previous pass (CollisionSettings::ccd_span).
template <class Mem>
struct SideMesh {
  Kokkos::View<const Vec3*, Mem> x, xs, xo;
  Kokkos::View<const int* [3], Mem> tris;
  Kokkos::View<const uint8_t*, Mem> rmask;       // representative features per triangle
  Kokkos::View<const real*, Mem> thickness;      // per point (cloth) or per vertex (collider: its collider's)
  Kokkos::View<const real*, Mem> friction, dfriction;  // a collider's friction scales both
  Kokkos::View<const int*, Mem> layer;
  Kokkos::View<const int* [3], Mem> neighbour;   // collider: triangle across each edge (-1 none)
  bool collider = false;

  KOKKOS_INLINE_FUNCTION real th(int v) const { return thickness(v); }
  KOKKOS_INLINE_FUNCTION real fr(int v) const { return friction(v); }
  KOKKOS_INLINE_FUNCTION real dfr(int v) const { return dfriction(v); }
  KOKKOS_INLINE_FUNCTION int ref(int v) const { return collider ? collider_ref(v) : v; }
  KOKKOS_INLINE_FUNCTION Vec3 face_normal(int t) const {
    const Vec3 a = x(tris(t, 0)), b = x(tris(t, 1)), c = x(tris(t, 2));
    return normalized(cross(b - a, c - a));
  }
};

struct NarrowSettings {
  real detect_scale = 1.25;           // vertex-face proximity contacts within this times the separation
  real ee_detect_scale = 1.0;         // edge-edge: only pairs already closer than the separation (or crossing,
                                      // by CCD); resting layers are held by vertex-face contacts
  real min_sin_angle = 0.17364817766693033;  // sin(10 deg): self edge-edge pairs closer to parallel are dropped
  real static_friction = 0.5, dynamic_friction = 0.5;
  real layer_shock = 4;
  bool self = true;                   // both sides cloth (start-side normals, parallel edge rule)
  // CCD: a box is reported once |F| varies by less than max(ccd.tolerance, ccd_tolerance_scale * r) over
  // it. A false positive only adds a contact that stays inactive while C >= 0, and a coarse tolerance keeps
  // near misses (cloth sliding past cloth just outside r) from exhausting the search.
  real ccd_tolerance_scale = 0.1;
  CcdSettings ccd{1e-6, 2000};
};

namespace narrow_detail {

KOKKOS_INLINE_FUNCTION bool shares(int a, int b, int c, int d) { return a == c || a == d || b == c || b == d; }

// Whether a pair's CCD runs with separation 0. A pair that starts the substep farther apart than the
// proximity reach must not come within r (the two thicknesses). A pair already in contact at the start is
// held by its proximity contact, so its CCD only has to catch a crossing (separation 0): CCD with separation
// r on a pair that rests at distance r is degenerate (|F| ~ r over a whole region of the parameter box), and
// resting layers would exhaust the search on every pair.
KOKKOS_INLINE_FUNCTION bool touching(real d0, real r, const NarrowSettings& s) { return d0 < s.detect_scale * r; }

// A point whose closest point on face f lies on an edge or a corner of f has the same closest point on
// every face around that edge or corner: only the feature's representative triangle keeps the proximity
// contact, so a point resting over a vertex of the next layer makes one contact, not six.
template <class Mem>
KOKKOS_INLINE_FUNCTION bool owns_closest_feature(const SideMesh<Mem>& F, int f, real u, real v, real w) {
  const int zeros = (u == 0) + (v == 0) + (w == 0);
  const uint8_t m = F.rmask(f);
  if (zeros == 2) return (m >> (u != 0 ? 0 : v != 0 ? 1 : 2)) & 1;        // corner
  if (zeros == 1) return (m >> (3 + (w == 0 ? 0 : u == 0 ? 1 : 2))) & 1;  // edge (0: ab, 1: bc, 2: ca)
  return true;
}

KOKKOS_INLINE_FUNCTION CcdSettings ccd_settings(real r, const NarrowSettings& s) {
  return CcdSettings{max_(s.ccd.tolerance, s.ccd_tolerance_scale * r), s.ccd.max_iterations, /*first_hit*/ true};
}

// The outcomes of a feature pair's cheap tests: decided (no contact, contact), or left to the CCD with
// separation r (kCcd) or 0 (kCcdTouching, see touching()).
enum FeatureTest : int { kMiss = 0, kHit = 1, kCcd = 2, kCcdTouching = 3 };

template <class Mem>
KOKKOS_INLINE_FUNCTION int vf_test(const SideMesh<Mem>& P, int p, const SideMesh<Mem>& F, int f, real r,
                                   const NarrowSettings& s) {
  const int a = F.tris(f, 0), b = F.tris(f, 1), c = F.tris(f, 2);
  real u, v, w;
  const real d2 = point_triangle_distance2(P.x(p), F.x(a), F.x(b), F.x(c), u, v, w);
  const real lim = s.detect_scale * r;
  // A face that does not own the closest feature still needs a contact if the point crosses it (a fold
  // at that edge or corner): the CCD decides.
  if (d2 < lim * lim && owns_closest_feature(F, f, u, v, w)) return kHit;
  // Linear motion moves the point-triangle vector by at most the largest relative displacement of p
  // against a corner, so a pair that starts farther apart than that plus the CCD separation cannot touch.
  const Vec3 dp = P.x(p) - P.xs(p);
  const real D = sqrt_(max_(norm2(dp - (F.x(a) - F.xs(a))), max_(norm2(dp - (F.x(b) - F.xs(b))), norm2(dp - (F.x(c) - F.xs(c))))));
  const real d0 = sqrt_(point_triangle_distance2(P.xs(p), F.xs(a), F.xs(b), F.xs(c), u, v, w));
  const bool t = touching(d0, r, s);
  if (d0 - D > (t ? real(0) : r) + 1e-9 * (1 + d0)) return kMiss;
  return t ? kCcdTouching : kCcd;
}

template <class Mem>
KOKKOS_INLINE_FUNCTION bool vf_ccd(const SideMesh<Mem>& P, int p, const SideMesh<Mem>& F, int f, real r, bool t,
                                   const NarrowSettings& s) {
  const int a = F.tris(f, 0), b = F.tris(f, 1), c = F.tris(f, 2);
  return ccd_vertex_face(P.xs(p), F.xs(a), F.xs(b), F.xs(c), P.x(p), F.x(a), F.x(b), F.x(c), t ? real(0) : r,
                         ccd_settings(r, s)).hit;
}

KOKKOS_INLINE_FUNCTION bool not_parallel(Vec3 ea, Vec3 eb, real min_sin) {
  const real c = norm(cross(ea, eb));
  return c > min_sin * norm(ea) * norm(eb);
}

template <class Mem>
KOKKOS_INLINE_FUNCTION int ee_test(const SideMesh<Mem>& A, int a0, int a1, const SideMesh<Mem>& B, int b0, int b1,
                                   real r, const NarrowSettings& s) {
  if (s.self && !(not_parallel(A.x(a1) - A.x(a0), B.x(b1) - B.x(b0), s.min_sin_angle) &&
                  not_parallel(A.xs(a1) - A.xs(a0), B.xs(b1) - B.xs(b0), s.min_sin_angle)))
    return kMiss;
  real sa, tb;
  const real d2 = segment_segment_distance2(A.x(a0), A.x(a1), B.x(b0), B.x(b1), sa, tb);
  const real lim = s.ee_detect_scale * r;
  if (d2 < lim * lim) return kHit;
  // The same bound as vf_test: the closest-point vector moves by at most the largest relative displacement.
  const Vec3 da0 = A.x(a0) - A.xs(a0), da1 = A.x(a1) - A.xs(a1), db0 = B.x(b0) - B.xs(b0), db1 = B.x(b1) - B.xs(b1);
  const real D = sqrt_(max_(max_(norm2(da0 - db0), norm2(da0 - db1)), max_(norm2(da1 - db0), norm2(da1 - db1))));
  const real d0 = sqrt_(segment_segment_distance2(A.xs(a0), A.xs(a1), B.xs(b0), B.xs(b1), sa, tb));
  const bool t = touching(d0, r, s);
  if (d0 - D > (t ? real(0) : r) + 1e-9 * (1 + d0)) return kMiss;
  return t ? kCcdTouching : kCcd;
}

template <class Mem>
KOKKOS_INLINE_FUNCTION bool ee_ccd(const SideMesh<Mem>& A, int a0, int a1, const SideMesh<Mem>& B, int b0, int b1,
                                   real r, bool t, const NarrowSettings& s) {
  return ccd_edge_edge(A.xs(a0), A.xs(a1), B.xs(b0), B.xs(b1), A.x(a0), A.x(a1), B.x(b0), B.x(b1), t ? real(0) : r,
                       ccd_settings(r, s)).hit;
}

template <class Mem>
KOKKOS_INLINE_FUNCTION real face_th(const SideMesh<Mem>& F, int f) {
  return max_(F.th(F.tris(f, 0)), max_(F.th(F.tris(f, 1)), F.th(F.tris(f, 2))));
}

// The box a point sweeps over the substep.
template <class Mem>
KOKKOS_INLINE_FUNCTION Aabb swept_point_box(const SideMesh<Mem>& S, int v) {
  return {vmin(S.xs(v), S.x(v)), vmax(S.xs(v), S.x(v))};
}

// The farthest apart, on any one axis, that a feature pair of separation r can be and still make a contact:
// the proximity test reaches detect_scale r, the CCD r (a CCD box whose corners are farther apart on one
// axis than its separation plus their rounding is dropped at once). The relative and absolute pads cover
// the rounding of the box gaps and of the squared distances.
KOKKOS_INLINE_FUNCTION real feature_reach(real r, real detect_scale) {
  return max_(detect_scale, real(1)) * r * (1 + 1e-6) + 1e-9;
}

// Boxes farther apart than m on some axis. Gaps beyond 2^400 are left to the full test, which treats
// coordinates it cannot bound as a possible contact.
KOKKOS_INLINE_FUNCTION bool apart(const Aabb& a, const Aabb& b, real m) {
  constexpr real big = 0x1p400;
  bool out = false;
  for (int i = 0; i < 3; ++i) {
    const real g1 = a.lo[i] - b.hi[i], g2 = b.lo[i] - a.hi[i];
    out = out || (g1 > m && g1 < big) || (g2 > m && g2 < big);
  }
  return out;
}

}  // namespace narrow_detail

// The cheap tests of the feature pairs of triangles A (side SA) and B (side SB), as bit masks (bits as at
// the top of this file): contacts decided already, and pairs only the CCD can decide (feature_ccd), with
// `touching` set for those whose CCD runs with separation 0. The CCD is left out so that it runs on a
// compacted list (collision/narrow_pipeline.hpp): inlined here, its registers and its long, uneven
// searches held every pair's thread back on the GPU.
struct FeatureTests {
  uint32_t hit = 0, ccd = 0, touching = 0;
};

template <class Mem>
KOKKOS_INLINE_FUNCTION FeatureTests feature_tests(const SideMesh<Mem>& SA, int A, const SideMesh<Mem>& SB, int B,
                                                  const NarrowSettings& s) {
  using namespace narrow_detail;
  const bool same = !SA.collider && !SB.collider;  // both cloth: shared points possible
  FeatureTests m;
  const auto record = [&m](int bit, int outcome) {
    if (outcome == kHit) m.hit |= 1u << bit;
    if (outcome >= kCcd) m.ccd |= 1u << bit;
    if (outcome == kCcdTouching) m.touching |= 1u << bit;
  };
  const int ta[3] = {SA.tris(A, 0), SA.tris(A, 1), SA.tris(A, 2)};
  const int tb[3] = {SB.tris(B, 0), SB.tris(B, 1), SB.tris(B, 2)};
  const uint8_t ra = SA.rmask(A), rb = SB.rmask(B);
  // Swept boxes of the corners: most feature pairs of a candidate triangle pair are too far apart on some
  // axis to touch, and skipping them spares their distance computations (the result is the same). On the
  // host this makes the narrow phase a third faster; on the GPU the extra registers made it 10-17% slower
  // (H200, skirt at 300K triangles), so there every feature pair takes the full test.
  constexpr bool boxes = Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
  const Aabb va[3] = {swept_point_box(SA, ta[0]), swept_point_box(SA, ta[1]), swept_point_box(SA, ta[2])};
  const Aabb vb[3] = {swept_point_box(SB, tb[0]), swept_point_box(SB, tb[1]), swept_point_box(SB, tb[2])};
  const Aabb boxA = merge(merge(va[0], va[1]), va[2]), boxB = merge(merge(vb[0], vb[1]), vb[2]);
  const real thA = face_th(SA, A), thB = face_th(SB, B);
  for (int k = 0; k < 3; ++k) {
    if ((ra >> k) & 1) {
      const int p = ta[k];
      const real r = SA.th(p) + thB;
      if (!(same && (p == tb[0] || p == tb[1] || p == tb[2])) && !(boxes && apart(va[k], boxB, feature_reach(r, s.detect_scale))))
        record(k, vf_test(SA, p, SB, B, r, s));
    }
    if ((rb >> k) & 1) {
      const int p = tb[k];
      const real r = SB.th(p) + thA;
      if (!(same && (p == ta[0] || p == ta[1] || p == ta[2])) && !(boxes && apart(vb[k], boxA, feature_reach(r, s.detect_scale))))
        record(3 + k, vf_test(SB, p, SA, A, r, s));
    }
  }
  for (int ka = 0; ka < 3; ++ka) {
    if (!((ra >> (3 + ka)) & 1)) continue;
    const int a0 = ta[ka], a1 = ta[(ka + 1) % 3];
    const Aabb ea = merge(va[ka], va[(ka + 1) % 3]);
    for (int kb = 0; kb < 3; ++kb) {
      if (!((rb >> (3 + kb)) & 1)) continue;
      const int b0 = tb[kb], b1 = tb[(kb + 1) % 3];
      if (same && shares(a0, a1, b0, b1)) continue;
      const real r = max_(SA.th(a0), SA.th(a1)) + max_(SB.th(b0), SB.th(b1));
      if (boxes && apart(ea, merge(vb[kb], vb[(kb + 1) % 3]), feature_reach(r, s.ee_detect_scale))) continue;
      record(6 + 3 * ka + kb, ee_test(SA, a0, a1, SB, b0, b1, r, s));
    }
  }
  return m;
}

// The CCD of one feature pair (its bit) that feature_tests left open: whether it is a contact.
template <class Mem>
KOKKOS_INLINE_FUNCTION bool feature_ccd(const SideMesh<Mem>& SA, int A, const SideMesh<Mem>& SB, int B, int bit,
                                        bool touching, const NarrowSettings& s) {
  using namespace narrow_detail;
  if (bit < 3) {
    const int p = SA.tris(A, bit);
    return vf_ccd(SA, p, SB, B, SA.th(p) + face_th(SB, B), touching, s);
  }
  if (bit < 6) {
    const int p = SB.tris(B, bit - 3);
    return vf_ccd(SB, p, SA, A, SB.th(p) + face_th(SA, A), touching, s);
  }
  const int ka = (bit - 6) / 3, kb = (bit - 6) % 3;
  const int a0 = SA.tris(A, ka), a1 = SA.tris(A, (ka + 1) % 3), b0 = SB.tris(B, kb), b1 = SB.tris(B, (kb + 1) % 3);
  const real r = max_(SA.th(a0), SA.th(a1)) + max_(SB.th(b0), SB.th(b1));
  return ee_ccd(SA, a0, a1, SB, b0, b1, r, touching, s);
}

namespace narrow_detail {

// Friction and layer shock of a contact between point sets of the two sides.
template <class Mem>
KOKKOS_INLINE_FUNCTION void finish_contact(Contact& c, const SideMesh<Mem>& S0, int v0, const SideMesh<Mem>& S1, int v1,
                                           bool first_is_s0, const NarrowSettings& s) {
  c.mu_s = s.static_friction * S0.fr(v0) * S1.fr(v1);
  c.mu_d = s.dynamic_friction * S0.dfr(v0) * S1.dfr(v1);
  if (!S0.collider && !S1.collider && s.layer_shock > 1) {
    const int l0 = S0.layer(v0), l1 = S1.layer(v1);
    // Slots of side 0 are those with b > 0 when first_is_s0 (the "a" side), else b < 0.
    for (int k = 0; k < 4; ++k) {
      const bool side0 = first_is_s0 ? c.b[k] > 0 : c.b[k] < 0;
      if ((side0 && l0 < l1) || (!side0 && l1 < l0)) c.wscale[k] = s.layer_shock;
    }
  }
}

// Vertex p of side P against the face (a, b, c3) of side F, its corners in the face's order.
template <class Mem>
KOKKOS_INLINE_FUNCTION Contact make_vf_at(const SideMesh<Mem>& P, int p, const SideMesh<Mem>& F, int a, int b, int c3,
                                          const NarrowSettings& s) {
  real u, v, w;
  point_triangle_distance2(P.x(p), F.x(a), F.x(b), F.x(c3), u, v, w);
  Contact c;
  c.kind = kContactVF;
  c.p[0] = P.ref(p); c.p[1] = F.ref(a); c.p[2] = F.ref(b); c.p[3] = F.ref(c3);
  c.b[0] = 1; c.b[1] = -u; c.b[2] = -v; c.b[3] = -w;
  c.r = P.th(p) + max_(F.th(a), max_(F.th(b), F.th(c3)));  // face_th
  Vec3 n = normalized(cross(F.x(b) - F.x(a), F.x(c3) - F.x(a)));  // face_normal
  if (!F.collider) {  // cloth faces are two-sided: keep the side the point started on
    const Vec3 d0 = P.xo(p) - (u * F.xo(a) + v * F.xo(b) + w * F.xo(c3));
    if (dot(n, d0) < 0) n = -n;
  }
  c.n = n;
  finish_contact(c, P, p, F, a, true, s);
  return c;
}

// Vertex p of side P against face f of side F.
template <class Mem>
KOKKOS_INLINE_FUNCTION Contact make_vf(const SideMesh<Mem>& P, int p, const SideMesh<Mem>& F, int f, const NarrowSettings& s) {
  return make_vf_at(P, p, F, F.tris(f, 0), F.tris(f, 1), F.tris(f, 2), s);
}

// The collider edge (e0, e1) of triangle f, edge k: its dihedral normal (mean of the two face normals).
template <class Mem>
KOKKOS_INLINE_FUNCTION Vec3 dihedral_normal(const SideMesh<Mem>& C, int f, int k) {
  const Vec3 n0 = C.face_normal(f);
  const int nb = C.neighbour(f, k);
  if (nb < 0) return n0;
  const Vec3 m = n0 + C.face_normal(nb);
  const real l = norm(m);
  return l > 0 ? m / l : n0;
}

// Edge (a0, a1) of side SA against edge (b0, b1) of side SB; `collider_n` the normal where a side is a
// collider (its edge's dihedral normal, pointing out of it), else the cloth edges' cross product is.
template <class Mem>
KOKKOS_INLINE_FUNCTION Contact make_ee_at(const SideMesh<Mem>& SA, int a0, int a1, const SideMesh<Mem>& SB, int b0, int b1,
                                          const NarrowSettings& s, Vec3 collider_n = Vec3{0, 0, 0}) {
  real sa, tb;
  segment_segment_distance2(SA.x(a0), SA.x(a1), SB.x(b0), SB.x(b1), sa, tb);
  Contact c;
  c.kind = kContactEE;
  c.p[0] = SA.ref(a0); c.p[1] = SA.ref(a1); c.p[2] = SB.ref(b0); c.p[3] = SB.ref(b1);
  c.b[0] = 1 - sa; c.b[1] = sa; c.b[2] = -(1 - tb); c.b[3] = -tb;
  c.r = max_(SA.th(a0), SA.th(a1)) + max_(SB.th(b0), SB.th(b1));
  Vec3 n = collider_n;
  if (!SA.collider && !SB.collider) {
    n = normalized(cross(SA.x(a1) - SA.x(a0), SB.x(b1) - SB.x(b0)));
    const Vec3 d0 = ((1 - sa) * SA.xo(a0) + sa * SA.xo(a1)) - ((1 - tb) * SB.xo(b0) + tb * SB.xo(b1));
    if (dot(n, d0) < 0) n = -n;  // sign from the start of the substep
  }
  c.n = n;
  finish_contact(c, SA, a0, SB, b0, true, s);
  return c;
}

// Edge (a0, a1) of side SA, triangle A, edge ka, against edge (b0, b1) of side SB, triangle B, edge kb.
template <class Mem>
KOKKOS_INLINE_FUNCTION Contact make_ee(const SideMesh<Mem>& SA, int A, int ka, const SideMesh<Mem>& SB, int B, int kb,
                                       const NarrowSettings& s) {
  // paper 2.2: against a collider edge, its dihedral normal, pointing out of it
  const Vec3 n = SB.collider ? dihedral_normal(SB, B, kb) : SA.collider ? -dihedral_normal(SA, A, ka) : Vec3{0, 0, 0};
  return make_ee_at(SA, SA.tris(A, ka), SA.tris(A, (ka + 1) % 3), SB, SB.tris(B, kb), SB.tris(B, (kb + 1) % 3), s, n);
}

}  // namespace narrow_detail

// A self contact made again where the cloth stands (cloth.x, and cloth.xo for the side its normal keeps)
// from its own points: its closest points, normal and layer shock as the narrow phase would give them there.
template <class Mem>
struct RemeasureSelfContacts {
  Kokkos::View<Contact*, Mem> c;
  SideMesh<Mem> cloth;
  NarrowSettings ns;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const Contact k = c(i);
    c(i) = k.kind == kContactVF ? narrow_detail::make_vf_at(cloth, k.p[0], cloth, k.p[1], k.p[2], k.p[3], ns)
                                : narrow_detail::make_ee_at(cloth, k.p[0], k.p[1], cloth, k.p[2], k.p[3], ns);
  }
};

// Writes the contacts of a pair's mask, in bit order, starting at out(first).
template <class Mem, class OutView>
KOKKOS_INLINE_FUNCTION void fill_contacts(const SideMesh<Mem>& SA, int A, const SideMesh<Mem>& SB, int B, uint32_t m,
                                          const NarrowSettings& s, const OutView& out, long first) {
  using namespace narrow_detail;
  long o = first;
  for (int bit = 0; bit < 15; ++bit) {
    if (!((m >> bit) & 1u)) continue;
    if (bit < 3) out(o++) = make_vf(SA, SA.tris(A, bit), SB, B, s);
    else if (bit < 6) {
      Contact c = make_vf(SB, SB.tris(B, bit - 3), SA, A, s);
      out(o++) = c;
    } else {
      const int e = bit - 6;
      out(o++) = make_ee(SA, A, e / 3, SB, B, e % 3, s);
    }
  }
}

}  // namespace weft
