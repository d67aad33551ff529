// Every constraint kind as one row type (Row), so that all kinds are coloured together on the host. On the
// device each kind is stored packed (PackedRow<K>: only the fields that kind reads, the material an index
// into a table), sorted by kind, then colour; the solver projects each colour's rows of one kind by a kernel
// compiled for that kind.
#pragma once
#include "constraints/bend.hpp"
#include "constraints/distance.hpp"
#include "constraints/fem_membrane.hpp"
#include "constraints/pin.hpp"
#include "constraints/stitch.hpp"
#include "constraints/triarap.hpp"
#include "constraints/xpbd.hpp"

#include <stdexcept>
#include <string>
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

// f(std::integral_constant<int, K>{}) for K = kind, a row kind: reaches code compiled for one kind from a
// kind known at run time (host code; throws for a kind outside the enum).
template <class F>
inline decltype(auto) with_row_kind(int kind, const F& f) {
  switch (kind) {
    case kRowDistance: return f(std::integral_constant<int, kRowDistance>{});
    case kRowBend: return f(std::integral_constant<int, kRowBend>{});
    case kRowTriarap: return f(std::integral_constant<int, kRowTriarap>{});
    case kRowPin: return f(std::integral_constant<int, kRowPin>{});
    case kRowAttach: return f(std::integral_constant<int, kRowAttach>{});
    case kRowPtPrim: return f(std::integral_constant<int, kRowPtPrim>{});
    case kRowFemDeviatoric: return f(std::integral_constant<int, kRowFemDeviatoric>{});
    case kRowFemHydrostatic: return f(std::integral_constant<int, kRowFemHydrostatic>{});
    default: throw std::logic_error("row kind " + std::to_string(kind));
  }
}

// A row of kind K as the device stores it: only the fields K reads, and its material as an index into the
// solver's material table. A sweep streams every row once; a distance row is 24 bytes here and 112 as a Row.
template <int K>
struct PackedRow {  // triarap and FEM rows: data = inverse rest shape; rest = gamma (hydrostatic)
  int idx[3];
  int material;
  real rest;
  real data[4];
};
template <>
struct PackedRow<kRowDistance> {
  int idx[2];
  int material;
  real rest;
};
template <>
struct PackedRow<kRowBend> {
  int idx[4];
  int material;
  real rest;
};
template <>
struct PackedRow<kRowPin> {
  int idx[1];
  int material;
  int target;
  real rest;
  real data[3];
};
template <>
struct PackedRow<kRowAttach> {
  int idx[1];
  int material;
  int cidx[3];
  real rest;
  real data[2];
};
template <>
struct PackedRow<kRowPtPrim> {
  int idx[5];
  int n;
  int material;
  real rest;
  real data[4];
};

// Row r of kind K, packed, with its material at `material` in the table.
template <int K>
PackedRow<K> pack_row(const Row& r, int material) {
  PackedRow<K> p{};
  p.material = material;
  constexpr int N = K == kRowPtPrim ? 5 : row_kind_points(K);
  for (int k = 0; k < N; ++k) p.idx[k] = r.idx[k];
  if constexpr (K == kRowPtPrim) p.n = r.n;
  if constexpr (K == kRowPin) p.target = r.target;
  if constexpr (K == kRowAttach)
    for (int k = 0; k < 3; ++k) p.cidx[k] = r.cidx[k];
  if constexpr (K != kRowDistance && K != kRowBend) {
    constexpr int D = K == kRowPin ? 3 : K == kRowAttach ? 2 : 4;
    for (int k = 0; k < D; ++k) p.data[k] = r.data[k];
  }
  p.rest = r.rest;
  return p;
}

// C and gradients of a row of fixed kind K (not kRowPtPrim or kRowKinds) from its particles' positions p;
// R is Row or PackedRow<K>.
template <int K, class R, class Mem>
KOKKOS_INLINE_FUNCTION real row_eval_of(const R& r, const Vec3 (&p)[row_kind_points(K)], const RowContext<Mem>& ctx,
                                        Vec3 (&g)[row_kind_points(K)]) {
  static_assert(K != kRowPtPrim && K != kRowKinds, "point-primitive rows have a variable point count");
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

// A packed row of kind K evaluated at the current positions: C, and per point its index, position, gradient,
// inverse mass and motion since the substep's start. A point-primitive row has 2 to 5 points (count); its
// unused slots keep zero gradient, weight and motion, so they add exact zeros to every sum.
template <int K>
struct RowState {
  static constexpr int N = K == kRowPtPrim ? 5 : row_kind_points(K);
  int count = N;
  int idx[N];
  Vec3 p[N], g[N], dx[N];
  real w[N];
  real C = 0;
};

template <int K, class XView, class WView, class Mem>
KOKKOS_INLINE_FUNCTION void evaluate_row(const PackedRow<K>& row, const XView& x, const XView& x_start, const WView& w,
                                         const RowContext<Mem>& ctx, RowState<K>& s) {
  constexpr int N = RowState<K>::N;
  if constexpr (K == kRowPtPrim) {
    s.count = row.n;
    for (int k = 0; k < N; ++k) {
      s.idx[k] = row.idx[k];
      s.w[k] = 0;
      if (k < s.count) {
        s.p[k] = x(s.idx[k]);
        s.w[k] = w(s.idx[k]);
        s.dx[k] = s.p[k] - x_start(s.idx[k]);
      }
    }
    Vec3 t[4];
    const int nt = s.count - 1;
    for (int k = 0; k < nt; ++k) t[k] = s.p[k + 1];
    const real wt[4] = {row.data[0], row.data[1], row.data[2], row.data[3]};
    s.C = ptprim_eval(s.p[0], t, wt, nt, row.rest, s.g);
  } else {
    for (int k = 0; k < N; ++k) s.idx[k] = row.idx[k];
    for (int k = 0; k < N; ++k) {
      s.p[k] = x(s.idx[k]);
      s.w[k] = w(s.idx[k]);
      s.dx[k] = s.p[k] - x_start(s.idx[k]);
    }
    s.C = row_eval_of<K>(row, s.p, ctx, s.g);
  }
}

// Solve one packed row of kind K in place (Gauss-Seidel): lambda accumulates; particles move by w g dlambda.
// No other row of its colour moves its particles. Fixed-size arrays in registers, so a kernel over one kind
// needs few registers and fits many threads on the GPU.
template <int K, class XView, class WView, class Mem>
KOKKOS_INLINE_FUNCTION void project_row_of(const PackedRow<K>& row, const XpbdMaterial& m, const XView& x,
                                           const XView& x_start, const WView& w, real& lambda,
                                           const RowContext<Mem>& ctx, real h) {
  RowState<K> s;
  evaluate_row(row, x, x_start, w, ctx, s);
  const real lambda0 = lambda;
  const real dl = xpbd_delta_lambda<RowState<K>::N>(s.C, s.g, s.w, s.dx, lambda0, m, h);
  lambda = lambda0 + dl;
  for (int k = 0; k < s.count; ++k) x(s.idx[k]) = s.p[k] + (s.w[k] * dl) * s.g[k];
}

}  // namespace weft
