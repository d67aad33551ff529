// A contact is a one-sided constraint C = n . sum_i b_i x_i - r >= 0 over up to four points (paper 2.2):
// vertex-face b = (1, -u, -v, -w), edge-edge b = (1-s, s, -(1-t), -t), with n fixed while the contact lives
// and r the two sides' thickness. Points are cloth points (index >= 0) or collider vertices (-1 - index),
// which never move. Projection moves cloth points only, then applies static / dynamic friction.
#pragma once
#include "core/vec.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

enum ContactKind : int { kContactVF = 0, kContactEE = 1 };

struct Contact {
  int kind = kContactVF;
  int p[4] = {-1, -1, -1, -1};  // cloth point i >= 0, collider vertex -1 - k
  real b[4] = {0, 0, 0, 0};
  Vec3 n;
  real r = 0;             // separation to keep (sum of thicknesses)
  real mu_s = 0, mu_d = 0;  // static and dynamic friction of the pair
  real wscale[4] = {1, 1, 1, 1};  // layer shock: lower layers act heavier
};

KOKKOS_INLINE_FUNCTION int collider_ref(int k) { return -1 - k; }

template <class XView, class CView>
KOKKOS_INLINE_FUNCTION Vec3 contact_point_pos(int p, const XView& x, const CView& cx) {
  return p >= 0 ? x(p) : cx(-1 - p);
}

// C at the given positions.
template <class XView, class CView>
KOKKOS_INLINE_FUNCTION real contact_value(const Contact& c, const XView& x, const CView& cx) {
  Vec3 s{};
  for (int k = 0; k < 4; ++k)
    if (c.b[k] != 0) s += c.b[k] * contact_point_pos(c.p[k], x, cx);
  return dot(c.n, s) - c.r;
}

// The normal step of a contact with C < 0: each point's weight wk (inverse mass over its layer-shock
// scale, 0 for collider points) and the multiplier dl; false when no point can move.
// Layer shock stands in for shock propagation: a lower layer carries the layer above it, so in a contact its
// points act layer_shock times heavier than the heavier of themselves and the heaviest moving point they
// carry. Scaling a point's own mass alone, a light layer under one a thousand times heavier took nearly all
// of every correction, and the heavy layer pressed it into the sphere below and stretched it (the stability
// case mass-ratio-1000: max strain 0.63, 0.26 at rest, against 0.12 and 0.07; docs/collisions.md).
template <class WView>
KOKKOS_INLINE_FUNCTION bool contact_weights(const Contact& c, const WView& w, real (&wk)[4], real& denom) {
  real carried = 0;  // the smallest moving weight on the upper side
  for (int k = 0; k < 4; ++k) {
    wk[k] = c.p[k] >= 0 ? w(c.p[k]) : 0.0;
    if (!(c.wscale[k] > 1) && wk[k] > 0) carried = carried > 0 ? min_(carried, wk[k]) : wk[k];
  }
  denom = 0;
  for (int k = 0; k < 4; ++k) {
    if (c.wscale[k] > 1) wk[k] = (carried > 0 ? min_(wk[k], carried) : wk[k]) / c.wscale[k];
    denom += wk[k] * c.b[k] * c.b[k];
  }
  return denom > 0;
}

template <class WView>
KOKKOS_INLINE_FUNCTION bool contact_normal_step(const Contact& c, real C, const WView& w, real (&wk)[4], real& denom,
                                                real& dl) {
  if (!contact_weights(c, w, wk, denom)) return false;
  dl = -C / denom;
  return true;
}

// Position-based friction: the correction (to be weighted by wk b / denom per point) that removes the
// tangential part of the contact's relative displacement d over the substep while it is below mu_s times
// the normal correction dn, and reduces it by mu_d times dn otherwise; false when there is none.
KOKKOS_INLINE_FUNCTION bool friction_correction(Vec3 n, real mu_s, real mu_d, Vec3 d, real dn, Vec3& corr) {
  const Vec3 dt = d - dot(d, n) * n;
  const real len = norm(dt);
  if (!(len > 0)) return false;
  const real keep = len < mu_s * dn ? 0.0 : max_(real(0), 1 - mu_d * dn / len);
  corr = (keep - 1) * dt;  // removes (1 - keep) of the tangential motion
  return true;
}
KOKKOS_INLINE_FUNCTION bool friction_correction(const Contact& c, Vec3 d, real dn, Vec3& corr) {
  return friction_correction(c.n, c.mu_s, c.mu_d, d, dn, corr);
}

// Relative displacement of the contact's two sides since the start of the substep.
template <class XView, class CView>
KOKKOS_INLINE_FUNCTION Vec3 contact_displacement(const Contact& c, const XView& x, const XView& xs, const CView& cx,
                                                 const CView& cxs) {
  Vec3 d{};
  for (int k = 0; k < 4; ++k)
    if (c.b[k] != 0) d += c.b[k] * (contact_point_pos(c.p[k], x, cx) - contact_point_pos(c.p[k], xs, cxs));
  return d;
}

// Projects one contact (Gauss-Seidel, compliance 0), then applies friction from the corrected positions.
template <class XView, class WView, class CView>
KOKKOS_INLINE_FUNCTION void project_contact(const Contact& c, const XView& x, const XView& xs, const WView& w,
                                            const CView& cx, const CView& cxs) {
  const real C = contact_value(c, x, cx);
  if (!(C < 0)) return;
  real wk[4], denom, dl;
  if (!contact_normal_step(c, C, w, wk, denom, dl)) return;
  // Points with weight b = 0 (closest point on an edge or corner) are not this contact's: the colouring
  // let another contact of the colour own them, so they must not even be written.
  for (int k = 0; k < 4; ++k)
    if (wk[k] > 0 && c.b[k] != 0) x(c.p[k]) += (wk[k] * c.b[k] * dl) * c.n;
  if (!(c.mu_s > 0 || c.mu_d > 0)) return;
  Vec3 corr;
  if (!friction_correction(c, contact_displacement(c, x, xs, cx, cxs), -C, corr)) return;
  for (int k = 0; k < 4; ++k)
    if (wk[k] > 0 && c.b[k] != 0) x(c.p[k]) += (wk[k] * c.b[k] / denom) * corr;
}

}  // namespace weft
