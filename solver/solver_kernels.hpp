// The solver's device kernels, as named functors (nvcc's host-device lambdas break when one template
// instance is compiled in several translation units; docs/solver.md, "Kernels are functors").
#pragma once
#include "constraints/rows.hpp"
#include "constraints/tether.hpp"
#include "constraints/triangle_strain.hpp"
#include "core/real.hpp"
#include "core/vec.hpp"

#include <Kokkos_Core.hpp>

namespace weft::kernels {

template <class Mem>
struct InterpolateFrames {
  Kokkos::View<const Vec3*, Kokkos::LayoutStride, Mem> x0, x1;  // rows of an animation, or streamed frames
  Kokkos::View<Vec3*, Mem> out;
  real a;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { out(i) = x0(i) + a * (x1(i) - x0(i)); }
};

// The stored frames f0, f1 around time t (in frames since the first stored one) of nf >= 1 frames, and the
// weight of f1; past the last frame, the last is held.
struct FramePair {
  long f0, f1;
  real a;
};
inline FramePair frame_pair(real t, long nf) {
  long f0 = long(t);
  real a = t - real(f0);
  if (f0 >= nf - 1) { f0 = nf - 1; a = 0; }
  return {f0, f0 + 1 < nf ? f0 + 1 : f0, a};
}

// out = x0 + a (x1 - x0).
template <class Exec>
void interpolate(const Exec& exec, const Kokkos::View<const Vec3*, Kokkos::LayoutStride, typename Exec::memory_space>& x0,
                 const Kokkos::View<const Vec3*, Kokkos::LayoutStride, typename Exec::memory_space>& x1, real a,
                 const Kokkos::View<Vec3*, typename Exec::memory_space>& out) {
  Kokkos::parallel_for("weft::interpolate_animation", Kokkos::RangePolicy<Exec>(exec, 0, out.extent(0)),
                       InterpolateFrames<typename Exec::memory_space>{x0, x1, out, a});
}

// Goals at time t (in frames since the first frame): linear between stored frames, last frame held.
template <class Exec>
void interpolate_animation(const Exec& exec, const Kokkos::View<Vec3**, typename Exec::memory_space>& frames,
                           const Kokkos::View<Vec3*, typename Exec::memory_space>& out, real t) {
  const long nf = long(frames.extent(0)), n = long(frames.extent(1));
  if (nf == 0 || n == 0) return;
  const FramePair p = frame_pair(t, nf);
  interpolate(exec, Kokkos::subview(frames, p.f0, Kokkos::ALL), Kokkos::subview(frames, p.f1, Kokkos::ALL), p.a, out);
}

template <class Mem>
struct Predict {
  Kokkos::View<Vec3*, Mem> x, xs, v;
  Kokkos::View<real*, Mem> w;
  Vec3 accel;
  real keep, h;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    xs(i) = x(i);
    if (w(i) > 0) {
      const Vec3 vi = keep * v(i) + h * accel;  // damping never weakens gravity at rest
      v(i) = vi;
      x(i) = x(i) + h * vi;
    }
  }
};

// Distance of each pinned point from where it belongs: an animated pin from its target (it trails where
// the bounds or the crossing fail-safe hold it back), then a still point from where it stands.
template <class Mem>
struct PinLag {
  Kokkos::View<int*, Mem> point, target;
  Kokkos::View<Vec3*, Mem> goals;
  Kokkos::View<int*, Mem> still;
  Kokkos::View<Vec3*, Mem> still_at, x;
  Kokkos::View<real*, Mem> lag;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    const long nk = long(point.extent(0));
    lag(k) = k < nk ? sqrt_(norm2(x(point(k)) - goals(target(k)))) : sqrt_(norm2(x(still(k - nk)) - still_at(k - nk)));
  }
};

// Pinned points go to their targets. One that the crossing fail-safe held back (it is not where its previous
// target was) moves with its animation and closes `catch_up` of its lag per substep instead of jumping, so
// that it does not replay at once the motion that was stopped; it snaps to its target once within 1 µm.
template <class Mem>
struct FollowTargets {
  Kokkos::View<int*, Mem> point, target;
  Kokkos::View<Vec3*, Mem> goals, previous, x;
  real catch_up;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    const int i = point(k), t = target(k);
    const Vec3 g = goals(t), p = previous(t), xi = x(i);
    if (xi.x == p.x && xi.y == p.y && xi.z == p.z) { x(i) = g; return; }
    const Vec3 lag = (1 - catch_up) * (p - xi);
    x(i) = norm2(lag) < real(1e-12) ? g : g - lag;
  }
};

template <class Mem>
struct UpdateVelocity {
  Kokkos::View<Vec3*, Mem> x, xs, v;
  real h;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { v(i) = (x(i) - xs(i)) / h; }
};

// The rows of kind K of one colour of Gauss-Seidel: the rows of a colour share no point, so they run in
// parallel (and so do the kinds of a colour). r is the row's index among all rows (its lambda); rows holds
// the rows of kind K from index `base` on.
template <class Mem, int K>
struct ProjectRows {
  Kokkos::View<PackedRow<K>*, Mem> rows;
  long base;
  Kokkos::View<XpbdMaterial*, Mem> materials;
  Kokkos::View<Vec3*, Mem> x, xs;
  Kokkos::View<real*, Mem> w, lambda;
  RowContext<Mem> ctx;
  real h;
  KOKKOS_INLINE_FUNCTION void operator()(long r) const {
    const PackedRow<K>& row = rows(r - base);
    project_row_of<K>(row, materials(row.material), x, xs, w, lambda(r), ctx, h);
  }
};

// Chebyshev semi-iterative acceleration (Wang 2015) of a substep's iterations. Before a sweep: the iterate
// before the last moves to xkm1, the current one to xk. After it: each moving point goes to
// xkm1 + omega (x - xkm1), past the sweep's result along the last two iterations' direction.
template <class Mem, class T>
struct ChebyshevSave {
  Kokkos::View<T*, Mem> x, xk, xkm1;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    xkm1(i) = xk(i);
    xk(i) = x(i);
  }
};

// Points with w > 0 only (the others follow their animation). With a collision stage, a point its contacts
// or its bound moved after the last sweep (it starts this iteration elsewhere than that sweep left it, xc)
// keeps the sweep's result: extrapolating a contact's push would carry the point into what it touches.
// With `keep`, every point's result is also kept as the next iteration's xc (where no tether moves the
// points after the blend), which spares a copy.
template <class Mem>
struct ChebyshevBlend {
  Kokkos::View<Vec3*, Mem> x, xk, xkm1, xc;  // xc: empty without a collision stage
  Kokkos::View<real*, Mem> w;
  real omega;
  bool keep;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const bool blend = w(i) > 0 && !(xc.extent(0) > 0 && !(xk(i).x == xc(i).x && xk(i).y == xc(i).y && xk(i).z == xc(i).z));
    if (blend) x(i) = xkm1(i) + omega * (x(i) - xkm1(i));
    if (keep) xc(i) = x(i);
  }
};

// The rows' multipliers by the same weight as the points: XPBD keeps x - x_predicted = M^-1 grad C^T lambda
// over a substep's iterations, and a blend of the points alone would break it, so that compliant rows
// settle at the wrong stretch.
// The next iteration's save (ChebyshevSave) is done here too: nothing else changes the multipliers between
// a sweep's blend and the next sweep.
template <class Mem>
struct ChebyshevBlendLambda {
  Kokkos::View<real*, Mem> lambda, lk, lkm1;
  real omega;
  KOKKOS_INLINE_FUNCTION void operator()(long r) const {
    const real blended = lkm1(r) + omega * (lambda(r) - lkm1(r));
    lambda(r) = blended;
    lkm1(r) = lk(r);
    lk(r) = blended;
  }
};

// Two elementwise kernels in one launch, element i of each below its size: the points' and the
// multipliers' Chebyshev saves or blends (each element's arithmetic as in its own kernel).
template <class A, class B>
struct BothElementwise {
  A a;
  B b;
  long na, nb;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    if (i < na) a(i);
    if (i < nb) b(i);
  }
};

// Every tether at once: each moves only its own point, towards a point that does not move.
template <class Mem>
struct ProjectTethers {
  Kokkos::View<Tether*, Mem> tethers;
  Kokkos::View<Vec3*, Mem> x;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    const Tether t = tethers(k);
    x(t.point) = tether_project(x(t.point), x(t.anchor), t.length);
  }
};

// Jacobi smoothing, first half: every row's correction from the same positions, rows of kind K only (as
// ProjectRows). Row r's correction of its particle k goes to slot k * total + r (total: rows of every kind),
// so that a warp's rows write side by side.
template <class Mem, int K>
struct JacobiRows {
  Kokkos::View<PackedRow<K>*, Mem> rows;
  long base, total;
  Kokkos::View<XpbdMaterial*, Mem> materials;
  Kokkos::View<Vec3*, Mem> x, xs, delta;
  Kokkos::View<real*, Mem> w, lambda;
  RowContext<Mem> ctx;
  real h;
  KOKKOS_INLINE_FUNCTION void operator()(long r) const {
    const PackedRow<K>& row = rows(r - base);
    RowState<K> s;
    evaluate_row(row, x, xs, w, ctx, s);
    const real dl = xpbd_delta_lambda<RowState<K>::N>(s.C, s.g, s.w, s.dx, lambda(r), materials(row.material), h);
    lambda(r) += dl;
    for (int k = 0; k < s.count; ++k) delta(k * total + r) = (s.w[k] * dl) * s.g[k];
  }
};

// Second half: each point moves by the average of its corrections, gathered in row order.
template <class Mem>
struct JacobiPoints {
  Kokkos::View<long*, Mem> off, slot;
  Kokkos::View<Vec3*, Mem> delta, x;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const long lo = off(i), hi = off(i + 1);
    if (hi == lo) return;
    Vec3 sum{};
    for (long k = lo; k < hi; ++k) sum += delta(slot(k));
    x(i) += sum / real(hi - lo);
  }
};

// Coarse levels: each follower of a level (a point of the level below not on it) moves by the weighted
// mean of its parents' moves since the cycle began (xs), gathered in a fixed order.
template <class Mem>
struct FollowParents {
  Kokkos::View<const int*, Mem> follower, parent;
  Kokkos::View<const long*, Mem> offset;
  Kokkos::View<const real*, Mem> weight, w;
  Kokkos::View<const Vec3*, Mem> xs;
  Kokkos::View<Vec3*, Mem> x;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    const int f = follower(k);
    if (!(w(f) > 0)) return;
    Vec3 d{};
    for (long j = offset(k); j < offset(k + 1); ++j) d += weight(j) * (x(parent(j)) - xs(parent(j)));
    x(f) += d;
  }
};

// Per-point and per-row quantities for the frame statistics.
template <class Mem>
struct KineticEnergy {
  Kokkos::View<Vec3*, Mem> v;
  Kokkos::View<real*, Mem> w, mass, out;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { out(i) = w(i) > 0 ? 0.5 * mass(i) * dot(v(i), v(i)) : 0.0; }
};

template <class Mem>
struct SpeedSquared {
  Kokkos::View<Vec3*, Mem> v;
  Kokkos::View<real*, Mem> w, out;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { out(i) = w(i) > 0 ? dot(v(i), v(i)) : 0.0; }
};

// |length / rest - 1| of every distance row (-1 for a row of rest length 0 and for a stretch limit, a row
// that only pulls: constraints/xpbd.hpp).
template <class Mem>
struct EdgeStrain {
  Kokkos::View<PackedRow<kRowDistance>*, Mem> rows;
  Kokkos::View<XpbdMaterial*, Mem> materials;
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<real*, Mem> out;
  KOKKOS_INLINE_FUNCTION void operator()(long r) const {
    const PackedRow<kRowDistance>& row = rows(r);
    const bool edge = row.rest > 0 && !pulls_only(materials(row.material));
    out(r) = edge ? abs_(norm(x(row.idx[1]) - x(row.idx[0])) / row.rest - 1) : -1.0;
  }
};

template <class Mem>
struct TriangleStrain {
  Kokkos::View<TriangleRest*, Mem> tris;
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<real*, Mem> out;
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const TriangleRest& r = tris(t);
    const real dm[4] = {r.dm_inv[0], r.dm_inv[1], r.dm_inv[2], r.dm_inv[3]};
    out(t) = triangle_strain(x(r.p[0]), x(r.p[1]), x(r.p[2]), dm);
  }
};

template <class Mem>
struct CountNonFinite {
  Kokkos::View<Vec3*, Mem> x;
  KOKKOS_INLINE_FUNCTION void operator()(long i, long& acc) const { acc += isfinite_(x(i)) ? 0 : 1; }
};

}  // namespace weft::kernels
