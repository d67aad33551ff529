// Reductions of doubles whose rounding does not depend on the backend or thread count: the data is cut
// into blocks of kReduceBlock elements, each block is folded left to right, and the block results are
// reduced the same way until one value is left. The shape depends only on n.
#pragma once
#include "core/real.hpp"

#include <Kokkos_Core.hpp>
#include <type_traits>
#include <vector>

namespace weft {

inline constexpr int kReduceBlock = 256;

// Sums of reals, or of vectors component by component (each component then rounds as its own sum would).
struct SumOp {
  KOKKOS_INLINE_FUNCTION static real identity() { return 0; }
  template <class T>
  KOKKOS_INLINE_FUNCTION T operator()(const T& a, const T& b) const { return a + b; }
};
struct MinOp {
  KOKKOS_INLINE_FUNCTION static real identity() { return __builtin_huge_val(); }
  KOKKOS_INLINE_FUNCTION real operator()(real a, real b) const { return min_(a, b); }
};
struct MaxOp {
  KOKKOS_INLINE_FUNCTION static real identity() { return -__builtin_huge_val(); }
  KOKKOS_INLINE_FUNCTION real operator()(real a, real b) const { return max_(a, b); }
};

// Kernels are named functors, not lambdas: nvcc's host-device lambdas break when one template instance
// is compiled in several translation units (docs/solver.md, "Kernels are functors").
template <class Out, class Op>
struct ReduceIdentity {
  Out out;
  KOKKOS_INLINE_FUNCTION void operator()(int) const {
    using T = typename Out::non_const_value_type;
    if constexpr (std::is_same_v<T, real>) out() = Op::identity();
    else out() = T{};  // a vector sum
  }
};

template <class In, class Partial, class Op>
struct ReduceBlocks {
  In in;
  Partial partial;
  long len;
  Op op;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kReduceBlock, hi = lo + kReduceBlock < len ? lo + kReduceBlock : len;
    typename Partial::non_const_value_type acc = in(lo);
    for (long i = lo + 1; i < hi; ++i) acc = op(acc, in(i));
    partial(b) = acc;
  }
};

template <class Out, class Partial>
struct ReduceStore {
  Out out;
  Partial partial;
  KOKKOS_INLINE_FUNCTION void operator()(int) const { out() = partial(0); }
};

namespace reduce_detail {

// Working memory of the reductions below, kept between calls and grown as needed: a View allocated per
// call cost a device allocation and a free that synchronizes the device (cudaFree), several per pass and
// per iteration. Released when Kokkos finalizes. One per value type and memory space; calls on one
// execution space instance reuse it in stream order.
template <class T, class Mem>
Kokkos::View<T*, Mem> workspace(long n) {
  static Kokkos::View<T*, Mem>* ws = nullptr;
  if (!ws) {
    ws = new Kokkos::View<T*, Mem>();
    Kokkos::push_finalize_hook([] {
      delete ws;
      ws = nullptr;
    });
  }
  if (long(ws->extent(0)) < n)
    *ws = Kokkos::View<T*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::reduce_workspace"), n + n / 2 + 64);
  return *ws;
}

// Elements of the partial results of every level of a reduction of n values, and one spare after them
// (reduce_fixed's result).
inline long levels_size(long n) {
  long total = 0;
  do {
    n = (n + kReduceBlock - 1) / kReduceBlock;
    total += n;
  } while (n > 1);
  return total + 1;
}

// reduce_fixed_into with the partial results in ws.
template <class Exec, class Op, class XView, class OutView, class Partial>
void reduce_levels(const Exec& exec, const XView& x, const OutView& out, Op op, const Partial& ws) {
  using In = Kokkos::View<const typename Partial::non_const_value_type*, typename Exec::memory_space>;
  const long n = static_cast<long>(x.extent(0));
  if (n == 0) {
    Kokkos::parallel_for("weft::reduce_empty", Kokkos::RangePolicy<Exec>(exec, 0, 1), ReduceIdentity<OutView, Op>{out});
    return;
  }
  In in = x;
  long at = 0;
  while (true) {
    const long len = static_cast<long>(in.extent(0));
    const long nb = (len + kReduceBlock - 1) / kReduceBlock;
    const Partial partial = Kokkos::subview(ws, std::make_pair(at, at + nb));
    at += nb;
    Kokkos::parallel_for("weft::reduce_blocks", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                         ReduceBlocks<In, Partial, Op>{in, partial, len, op});
    if (nb == 1) {
      Kokkos::parallel_for("weft::reduce_out", Kokkos::RangePolicy<Exec>(exec, 0, 1),
                           ReduceStore<OutView, Partial>{out, partial});
      return;
    }
    in = partial;
  }
}

}  // namespace reduce_detail

// Reduce x[0..n) into out() on the device; no host copy. The values are reals, or vectors with SumOp.
template <class Exec, class Op, class XView, class OutView>
void reduce_fixed_into(const Exec& exec, const XView& x, const OutView& out, Op op = Op{}) {
  using T = typename XView::non_const_value_type;
  const long size = reduce_detail::levels_size(static_cast<long>(x.extent(0)));
  reduce_detail::reduce_levels(exec, x, out, op, reduce_detail::workspace<T, typename Exec::memory_space>(size));
}

// Reduce to a host value (one small copy).
template <class Exec, class Op, class XView>
real reduce_fixed(const Exec& exec, const XView& x, Op op = Op{}) {
  const long size = reduce_detail::levels_size(static_cast<long>(x.extent(0)));
  const auto ws = reduce_detail::workspace<real, typename Exec::memory_space>(size);
  const auto out = Kokkos::subview(ws, size - 1);  // the spare after the partials
  reduce_detail::reduce_levels(exec, x, out, op, ws);
  real h = 0;
  Kokkos::deep_copy(exec, h, out);
  exec.fence();
  return h;
}

template <class Exec, class XView> real sum_fixed(const Exec& e, const XView& x) { return reduce_fixed(e, x, SumOp{}); }
template <class Exec, class XView> real min_fixed(const Exec& e, const XView& x) { return reduce_fixed(e, x, MinOp{}); }
template <class Exec, class XView> real max_fixed(const Exec& e, const XView& x) { return reduce_fixed(e, x, MaxOp{}); }

// Integer counts by the same tree (exact in any order): kept off Kokkos' reductions, whose shared-memory
// warp code compute-sanitizer's racecheck reports as hazards on the H100.
template <class In, class Partial>
struct SumCountBlocks {
  In in;
  Partial partial;
  long len;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kReduceBlock, hi = lo + kReduceBlock < len ? lo + kReduceBlock : len;
    long acc = 0;
    for (long i = lo; i < hi; ++i) acc += long(in(i));
    partial(b) = acc;
  }
};

// The sum of the integers x[0..n) on the host (one small copy).
template <class Exec, class XView>
long sum_counts(const Exec& exec, const XView& x) {
  using Mem = typename Exec::memory_space;
  using Partial = Kokkos::View<long*, Mem>;
  long len = static_cast<long>(x.extent(0));
  if (len == 0) return 0;
  const Partial ws = reduce_detail::workspace<long, Mem>(reduce_detail::levels_size(len));
  long nb = (len + kReduceBlock - 1) / kReduceBlock, at = nb;
  Partial partial = Kokkos::subview(ws, std::make_pair(0L, nb));
  Kokkos::parallel_for("weft::count_blocks", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                       SumCountBlocks<XView, Partial>{x, partial, len});
  while (nb > 1) {
    len = nb;
    nb = (len + kReduceBlock - 1) / kReduceBlock;
    const Partial next = Kokkos::subview(ws, std::make_pair(at, at + nb));
    at += nb;
    Kokkos::parallel_for("weft::count_blocks", Kokkos::RangePolicy<Exec>(exec, 0, nb),
                         SumCountBlocks<Partial, Partial>{partial, next, len});
    partial = next;
  }
  long h = 0;
  Kokkos::deep_copy(exec, h, Kokkos::subview(partial, 0));
  exec.fence();
  return h;
}

// The same tree on the host, for tests and host-side statistics.
template <class Op>
real reduce_fixed_host(std::vector<real> v, Op op = Op{}) {
  if (v.empty()) return Op::identity();
  while (v.size() > 1) {
    std::vector<real> next((v.size() + kReduceBlock - 1) / kReduceBlock);
    for (size_t b = 0; b < next.size(); ++b) {
      const size_t lo = b * kReduceBlock, hi = lo + kReduceBlock < v.size() ? lo + kReduceBlock : v.size();
      real acc = v[lo];
      for (size_t i = lo + 1; i < hi; ++i) acc = op(acc, v[i]);
      next[b] = acc;
    }
    v.swap(next);
  }
  return v[0];
}

}  // namespace weft
