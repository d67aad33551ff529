// Narrow phase (collision/narrow_phase.hpp) over the candidate pairs of two moving cloth layers
// (cloth_layers.hpp), with the collision handler's own kernels (collision/narrow_pipeline.hpp): the cheap
// tests of every feature pair, the CCD of those they leave open, the contact fill.
#pragma once
#include "bench/micro/cloth_layers.hpp"

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Mem = Exec::memory_space;
using Layers = weft::bench::ClothLayers<Exec>;

// The whole narrow phase of the layers' candidate pairs: tests, compacted CCD, contact fill.
void narrow_phase(benchmark::State& state) {
  Layers& f = weft::bench::fixture<Layers>(state.range(0));
  weft::NarrowPipeline<Exec> narrow;
  Kokkos::View<weft::Contact*, Mem> contacts("bench::contacts", 0);
  long total = 0;
  for (auto _ : state) {
    total = narrow.run(f.exec, f.side(), f.side(), f.ns, f.pairs, f.npairs, contacts, 0);
    f.exec.fence();
  }
  weft::bench::items(state, f.npairs);
  state.counters["pairs"] = double(f.npairs);
  state.counters["contacts"] = double(total);
}
BENCHMARK(narrow_phase)->Apply(weft::bench::triangles);

}  // namespace
