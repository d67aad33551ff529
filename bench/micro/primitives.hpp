// The deterministic building blocks: fixed-tree reductions of doubles (core/reduce.hpp, to a host value as
// the solver's statistics do), the integer exclusive scan (core/scan.hpp), the stable radix sort of
// (uint64 key, uint32 value) pairs (core/sort.hpp) and the View hash (core/hash.hpp).
#pragma once
#include "bench/micro/bench_common.hpp"
#include "core/reduce.hpp"
#include "core/scan.hpp"
#include "core/sort.hpp"

#include <chrono>

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Mem = Exec::memory_space;
using weft::real;

// Data-filling kernels: named functors (docs/solver.md, "Kernels are functors").
struct FillReals {
  Kokkos::View<real*, Mem> v;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { v(i) = weft::bench::unit_random(7, uint64_t(i)); }
};
struct FillCounts {
  Kokkos::View<long*, Mem> c;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { c(i) = long(weft::splitmix64(uint64_t(i)) & 7u); }
};
struct FillKeys {
  Kokkos::View<uint64_t*, Mem> k;
  Kokkos::View<uint32_t*, Mem> v;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    k(i) = weft::splitmix64(uint64_t(i));
    v(i) = uint32_t(i);
  }
};

struct Data {
  Exec exec;
  long n;
  Kokkos::View<real*, Mem> reals;
  Kokkos::View<long*, Mem> counts, offsets;
  Kokkos::View<uint64_t*, Mem> keys0, keys;  // keys0: the unsorted input
  Kokkos::View<uint32_t*, Mem> vals0, vals;
  explicit Data(long size)
      : n(size), reals("bench::reals", n), counts("bench::counts", n), offsets("bench::offsets", n),
        keys0("bench::keys0", n), keys("bench::keys", n), vals0("bench::vals0", n), vals("bench::vals", n) {
    Kokkos::parallel_for("bench::fill_reals", Kokkos::RangePolicy<Exec>(exec, 0, n), FillReals{reals});
    Kokkos::parallel_for("bench::fill_counts", Kokkos::RangePolicy<Exec>(exec, 0, n), FillCounts{counts});
    Kokkos::parallel_for("bench::fill_keys", Kokkos::RangePolicy<Exec>(exec, 0, n), FillKeys{keys0, vals0});
    exec.fence();
  }
};

template <class Op>
void reduce(benchmark::State& state) {
  Data& d = weft::bench::fixture<Data>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(weft::reduce_fixed(d.exec, d.reals, Op{}));
    d.exec.fence();
  }
  weft::bench::items(state, d.n);
  state.SetBytesProcessed(int64_t(state.iterations()) * d.n * int64_t(sizeof(real)));
}
void reduce_sum(benchmark::State& state) { reduce<weft::SumOp>(state); }
void reduce_max(benchmark::State& state) { reduce<weft::MaxOp>(state); }
BENCHMARK(reduce_sum)->Apply(weft::bench::elements);
BENCHMARK(reduce_max)->Apply(weft::bench::elements);

void exclusive_scan(benchmark::State& state) {
  Data& d = weft::bench::fixture<Data>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(weft::exclusive_scan(d.exec, d.counts, d.offsets));
    d.exec.fence();
  }
  weft::bench::items(state, d.n);
  state.SetBytesProcessed(int64_t(state.iterations()) * d.n * int64_t(2 * sizeof(long)));
}
BENCHMARK(exclusive_scan)->Apply(weft::bench::elements);

// Times the sort alone: every iteration first restores the unsorted input, outside the timed part.
void radix_sort_pairs(benchmark::State& state) {
  Data& d = weft::bench::fixture<Data>(state.range(0));
  const int bits = int(state.range(1));
  for (auto _ : state) {
    Kokkos::deep_copy(d.exec, d.keys, d.keys0);
    Kokkos::deep_copy(d.exec, d.vals, d.vals0);
    d.exec.fence();
    const auto t0 = std::chrono::steady_clock::now();
    weft::radix_sort_pairs(d.exec, d.keys, d.vals, bits);
    d.exec.fence();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  weft::bench::items(state, d.n);
}
BENCHMARK(radix_sort_pairs)->Apply([](benchmark::internal::Benchmark* b) {
  b->ArgNames({"n", "bits"});
  for (long n : {10000L, 100000L, 1000000L})
    for (long bits : {32L, 64L}) b->Args({n, bits});  // 32: the LBVH's Morton codes
  b->UseManualTime()->Unit(benchmark::kMicrosecond);
});

void hash_view(benchmark::State& state) {
  Data& d = weft::bench::fixture<Data>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(weft::hash_view(d.exec, d.reals));
    d.exec.fence();
  }
  weft::bench::items(state, d.n);
  state.SetBytesProcessed(int64_t(state.iterations()) * d.n * int64_t(sizeof(real)));
}
BENCHMARK(hash_view)->Apply(weft::bench::elements);

}  // namespace
