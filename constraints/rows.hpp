// Every constraint kind as one row type, so that all kinds are coloured together. Rows are sorted by colour,
// then kind; the solver projects each colour's rows of one kind by a kernel compiled for that kind.
#pragma once
#include "constraints/bend.hpp"
#include "constraints/distance.hpp"
#include "constraints/fem_membrane.hpp"
#include "constraints/pin.hpp"
#include "constraints/stitch.hpp"
#include "constraints/triarap.hpp"
#include "constraints/xpbd.hpp"

#include <type_traits>

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

// The cloth points of a row of kind K; a point-primitive row (stitch) has 2 to 5, read from the row.
KOKKOS_INLINE_FUNCTION constexpr int row_kind_points(int kind) {
  return kind == kRowDistance ? 2
         : kind == kRowBend   ? 4
         : (kind == kRowPin || kind == kRowAttach) ? 1
         : kind == kRowPtPrim ? 5
                              : 3;  // triarap, FEM
}

// f(std::integral_constant<int, K>{}) for K = kind (kRowKinds for a kind outside the enum): reaches code
// compiled for one kind from a kind known at run time.
template <class F>
KOKKOS_INLINE_FUNCTION decltype(auto) with_row_kind(int kind, const F& f) {
  switch (kind) {
    case kRowDistance: return f(std::integral_constant<int, kRowDistance>{});
    case kRowBend: return f(std::integral_constant<int, kRowBend>{});
    case kRowTriarap: return f(std::integral_constant<int, kRowTriarap>{});
    case kRowPin: return f(std::integral_constant<int, kRowPin>{});
    case kRowAttach: return f(std::integral_constant<int, kRowAttach>{});
    case kRowPtPrim: return f(std::integral_constant<int, kRowPtPrim>{});
    case kRowFemDeviatoric: return f(std::integral_constant<int, kRowFemDeviatoric>{});
    case kRowFemHydrostatic: return f(std::integral_constant<int, kRowFemHydrostatic>{});
    default: return f(std::integral_constant<int, kRowKinds>{});
  }
}

// C and gradients of a row of fixed kind K (not kRowPtPrim or kRowKinds) from its particles' positions p.
template <int K, class Mem>
KOKKOS_INLINE_FUNCTION real row_eval_of(const Row& r, const Vec3 (&p)[row_kind_points(K)], const RowContext<Mem>& ctx,
                                        Vec3 (&g)[row_kind_points(K)]) {
  static_assert(K != kRowPtPrim && K != kRowKinds, "point-primitive rows have a variable point count: row_eval");
  if constexpr (K == kRowDistance) {
    return distance_eval(p[0], p[1], r.rest, g);
  } else if constexpr (K == kRowBend) {
    return bend_eval(p[0], p[1], p[2], p[3], r.rest, g);
  } else if constexpr (K == kRowTriarap) {
    const real dm[4] = {r.data[0], r.data[1], r.data[2], r.data[3]};
    return triarap_eval(p[0], p[1], p[2], dm, g);
  } else if constexpr (K == kRowPin) {
    const Vec3 goal = r.target >= 0 ? ctx.targets(r.target) : Vec3{r.data[0], r.data[1], r.data[2]};
    return pin_eval(p[0], goal, r.rest, g);
  } else if constexpr (K == kRowAttach) {
    const Vec3 goal = attach_goal(ctx.collider_x(r.cidx[0]), ctx.collider_x(r.cidx[1]), ctx.collider_x(r.cidx[2]),
                                  r.data[0], r.data[1]);
    return pin_eval(p[0], goal, r.rest, g);
  } else {
    const real dm[4] = {r.data[0], r.data[1], r.data[2], r.data[3]};
    return K == kRowFemDeviatoric ? fem_deviatoric_eval(p[0], p[1], p[2], dm, g)
                                  : fem_hydrostatic_eval(p[0], p[1], p[2], dm, r.rest, g);
  }
}

// C and gradients of one row of any kind from its particles' positions p[k] = x(r.idx[k]), k < r.n;
// returns the number of particles (0: nothing to do).
template <class Mem>
KOKKOS_INLINE_FUNCTION int row_eval(const Row& r, const Vec3 (&p)[5], const RowContext<Mem>& ctx, real& C, Vec3 (&g)[5]) {
  return with_row_kind(r.kind, [&](auto kind) -> int {
    constexpr int K = decltype(kind)::value;
    if constexpr (K == kRowKinds) {
      return 0;
    } else if constexpr (K == kRowPtPrim) {
      Vec3 t[4];
      const real w[4] = {r.data[0], r.data[1], r.data[2], r.data[3]};
      const int nt = r.n - 1;
      for (int k = 0; k < nt; ++k) t[k] = p[k + 1];
      C = ptprim_eval(p[0], t, w, nt, r.rest, g);
      return r.n;
    } else {
      constexpr int N = row_kind_points(K);
      Vec3 pk[N], gk[N];
      for (int k = 0; k < N; ++k) pk[k] = p[k];
      C = row_eval_of<K>(r, pk, ctx, gk);
      for (int k = 0; k < N; ++k) g[k] = gk[k];
      return N;
    }
  });
}

// Solve one row in place (Gauss-Seidel): lambda accumulates; particles move by w g dlambda. No other row of its
// colour moves its particles. Any kind; for point-primitive rows (their point count is in the row).
template <class XView, class WView, class Mem>
KOKKOS_INLINE_FUNCTION void project_row(const Row& row, const XView& x, const XView& x_start, const WView& w,
                                        real& lambda, const RowContext<Mem>& ctx, real h) {
  const Row r = row;
  Vec3 p[5], dx[5];
  real wi[5] = {0, 0, 0, 0, 0};
  for (int k = 0; k < 5; ++k)
    if (k < r.n) {
      p[k] = x(r.idx[k]);
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

// project_row for a row known to be of kind K: fixed-size arrays in registers and only the fields K reads,
// so a kernel over one kind needs a fraction of the registers of the generic one (164 and 528 bytes of
// stack on sm_90) and fits several times more threads on the GPU. The same arithmetic in the same order:
// the generic version's extra terms are zeros, so the bits are the same.
template <int K, class XView, class WView, class Mem>
KOKKOS_INLINE_FUNCTION void project_row_of(const Row& row, const XView& x, const XView& x_start, const WView& w,
                                           real& lambda, const RowContext<Mem>& ctx, real h) {
  if constexpr (K == kRowPtPrim) {
    project_row(row, x, x_start, w, lambda, ctx, h);
  } else {
    constexpr int N = row_kind_points(K);
    int idx[N];
    Vec3 p[N], dx[N], g[N];
    real wi[N];
    for (int k = 0; k < N; ++k) idx[k] = row.idx[k];
    for (int k = 0; k < N; ++k) {
      p[k] = x(idx[k]);
      wi[k] = w(idx[k]);
      dx[k] = p[k] - x_start(idx[k]);
    }
    const real lambda0 = lambda;
    const real C = row_eval_of<K>(row, p, ctx, g);
    const real dl = xpbd_delta_lambda<N>(C, g, wi, dx, lambda0, row.m, h);
    lambda = lambda0 + dl;
    for (int k = 0; k < N; ++k) x(idx[k]) = p[k] + (wi[k] * dl) * g[k];
  }
}

}  // namespace weft
