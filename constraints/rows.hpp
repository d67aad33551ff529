// Every constraint kind as one row type, so that all kinds of one colour are projected in one kernel
// launch (launches dominate at production iteration counts). Rows are sorted by colour, then kind.
#pragma once
#include "constraints/bend.hpp"
#include "constraints/distance.hpp"
#include "constraints/fem_membrane.hpp"
#include "constraints/pin.hpp"
#include "constraints/stitch.hpp"
#include "constraints/triarap.hpp"
#include "constraints/xpbd.hpp"

namespace weft {

enum RowKind : int {
  kRowDistance = 0,  // idx a, b; rest = length
  kRowBend,          // idx o0, o1, e0, e1; rest = angle (rad)
  kRowTriarap,       // idx p0, p1, p2; data = inverse rest shape
  kRowPin,           // idx p; target >= 0: goal = targets(target), else data[0..2]; rest = distance
  kRowAttach,        // idx p; cidx = collider vertices; data[0..1] = (u, v); rest = distance
  kRowPtPrim,        // idx p, t0..t(n-2); data = weights; rest = distance
  kRowFemDeviatoric, // idx p0, p1, p2; data = inverse rest shape
  kRowFemHydrostatic,// idx p0, p1, p2; data = inverse rest shape; rest = gamma
  kRowKinds
};

struct Row {
  int kind = kRowDistance;
  int n = 0;                    // cloth particles in idx
  int idx[5] = {-1, -1, -1, -1, -1};
  int cidx[3] = {-1, -1, -1};   // collider vertices (attach)
  int target = -1;              // animated pin target
  real rest = 0;
  real data[4] = {0, 0, 0, 0};
  XpbdMaterial m;
};

// The positions a row reads besides the cloth: animated pin goals and collider vertices at the current time.
template <class Mem>
struct RowContext {
  Kokkos::View<Vec3*, Mem> targets;
  Kokkos::View<Vec3*, Mem> collider_x;
};

// The positions of a row's particles, p[k] = x(r.idx[k]) for k < r.n, loaded before any arithmetic so that
// a thread waits for memory once (the colour kernels are bound by load latency: ~50K rows fill a fifth of
// the GPU).
template <class XView>
KOKKOS_INLINE_FUNCTION void row_points(const Row& r, const XView& x, Vec3 (&p)[5]) {
  for (int k = 0; k < 5; ++k)
    if (k < r.n) p[k] = x(r.idx[k]);
}

// C and gradients of one row from its particles' positions p (row_points); returns the number of particles
// (0: nothing to do).
template <class Mem>
KOKKOS_INLINE_FUNCTION int row_eval(const Row& r, const Vec3 (&p)[5], const RowContext<Mem>& ctx, real& C, Vec3 (&g)[5]) {
  switch (r.kind) {
    case kRowDistance: {
      Vec3 gg[2];
      C = distance_eval(p[0], p[1], r.rest, gg);
      g[0] = gg[0]; g[1] = gg[1];
      return 2;
    }
    case kRowBend: {
      Vec3 gg[4];
      C = bend_eval(p[0], p[1], p[2], p[3], r.rest, gg);
      for (int k = 0; k < 4; ++k) g[k] = gg[k];
      return 4;
    }
    case kRowTriarap: {
      Vec3 gg[3];
      const real dm[4] = {r.data[0], r.data[1], r.data[2], r.data[3]};
      C = triarap_eval(p[0], p[1], p[2], dm, gg);
      for (int k = 0; k < 3; ++k) g[k] = gg[k];
      return 3;
    }
    case kRowPin: {
      Vec3 gg[1];
      const Vec3 goal = r.target >= 0 ? ctx.targets(r.target) : Vec3{r.data[0], r.data[1], r.data[2]};
      C = pin_eval(p[0], goal, r.rest, gg);
      g[0] = gg[0];
      return 1;
    }
    case kRowAttach: {
      Vec3 gg[1];
      const Vec3 goal = attach_goal(ctx.collider_x(r.cidx[0]), ctx.collider_x(r.cidx[1]), ctx.collider_x(r.cidx[2]),
                                    r.data[0], r.data[1]);
      C = pin_eval(p[0], goal, r.rest, gg);
      g[0] = gg[0];
      return 1;
    }
    case kRowPtPrim: {
      Vec3 t[4];
      const real w[4] = {r.data[0], r.data[1], r.data[2], r.data[3]};
      const int nt = r.n - 1;
      for (int k = 0; k < nt; ++k) t[k] = p[k + 1];
      C = ptprim_eval(p[0], t, w, nt, r.rest, g);
      return r.n;
    }
    case kRowFemDeviatoric:
    case kRowFemHydrostatic: {
      Vec3 gg[3];
      const real dm[4] = {r.data[0], r.data[1], r.data[2], r.data[3]};
      C = r.kind == kRowFemDeviatoric ? fem_deviatoric_eval(p[0], p[1], p[2], dm, gg)
                                      : fem_hydrostatic_eval(p[0], p[1], p[2], dm, r.rest, gg);
      for (int k = 0; k < 3; ++k) g[k] = gg[k];
      return 3;
    }
  }
  return 0;
}

// Solve one row in place (Gauss-Seidel): lambda accumulates; particles move by w g dlambda. The row and
// everything it reads are loaded first; no other row of its colour moves its particles.
template <class XView, class WView, class Mem>
KOKKOS_INLINE_FUNCTION void project_row(const Row& row, const XView& x, const XView& x_start, const WView& w,
                                        real& lambda, const RowContext<Mem>& ctx, real h) {
  const Row r = row;
  Vec3 p[5], dx[5];
  real wi[5] = {0, 0, 0, 0, 0};
  row_points(r, x, p);
  for (int k = 0; k < 5; ++k)
    if (k < r.n) {
      wi[k] = w(r.idx[k]);
      dx[k] = p[k] - x_start(r.idx[k]);
    }
  const real lambda0 = lambda;
  real C = 0;
  Vec3 g[5];
  const int n = row_eval(r, p, ctx, C, g);
  const real dl = xpbd_delta_lambda<5>(C, g, wi, dx, lambda0, r.m, h);
  lambda = lambda0 + dl;
  for (int k = 0; k < n; ++k) x(r.idx[k]) = p[k] + (wi[k] * dl) * g[k];
}

}  // namespace weft
