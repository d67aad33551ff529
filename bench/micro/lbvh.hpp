// LBVH broad phase (collision/lbvh.hpp) over the swept triangle boxes of two cloth layers
// (cloth_layers.hpp): a new tree, as at the start of every substep; a refit, as at every collision pass;
// and the self query that lists the candidate triangle pairs (count, scan, fill).
#pragma once
#include "bench/micro/cloth_layers.hpp"

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Layers = weft::bench::ClothLayers<Exec>;

void lbvh_build(benchmark::State& state) {
  Layers& f = weft::bench::fixture<Layers>(state.range(0));
  for (auto _ : state) {
    f.bvh.build(f.boxes);
    f.exec.fence();
  }
  weft::bench::items(state, f.triangles);
}
BENCHMARK(lbvh_build)->Apply(weft::bench::triangles);

void lbvh_refit(benchmark::State& state) {
  Layers& f = weft::bench::fixture<Layers>(state.range(0));
  for (auto _ : state) {
    f.bvh.refit(f.boxes);
    f.exec.fence();
  }
  weft::bench::items(state, f.triangles);
}
BENCHMARK(lbvh_refit)->Apply(weft::bench::triangles);

void lbvh_query_self(benchmark::State& state) {
  Layers& f = weft::bench::fixture<Layers>(state.range(0));
  long pairs = 0;
  for (auto _ : state) {
    pairs = f.bvh.query_self(weft::KeepAllPairs{}, f.pairs);
    f.exec.fence();
  }
  weft::bench::items(state, f.triangles);
  state.counters["pairs"] = double(pairs);
}
BENCHMARK(lbvh_query_self)->Apply(weft::bench::triangles);

}  // namespace
