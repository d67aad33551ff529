// Narrow phase (collision/narrow_phase.hpp) over the candidate pairs of two moving cloth layers
// (cloth_layers.hpp), with the collision handler's own kernels: the mask (feature_mask: proximity, then the
// CCD where proximity cannot decide) and the contact fill (scan of the counts, fill_contacts).
#pragma once
#include "bench/micro/cloth_layers.hpp"

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Mem = Exec::memory_space;
using Layers = weft::bench::ClothLayers<Exec>;

void narrow_mask(benchmark::State& state) {
  Layers& f = weft::bench::fixture<Layers>(state.range(0));
  Kokkos::View<uint32_t*, Mem> masks("bench::masks", f.npairs);
  Kokkos::View<long*, Mem> counts("bench::counts", f.npairs);
  const weft::NarrowMask<Mem> kernel{f.side(), f.side(), f.pairs, masks, counts, f.ns};
  for (auto _ : state) {
    Kokkos::parallel_for("bench::narrow_mask", Kokkos::RangePolicy<Exec>(f.exec, 0, f.npairs), kernel);
    f.exec.fence();
  }
  weft::bench::items(state, f.npairs);
  state.counters["pairs"] = double(f.npairs);
  state.counters["contacts"] = double(weft::exclusive_scan(f.exec, counts, counts));
}
BENCHMARK(narrow_mask)->Apply(weft::bench::triangles);

void narrow_fill(benchmark::State& state) {
  Layers& f = weft::bench::fixture<Layers>(state.range(0));
  Kokkos::View<uint32_t*, Mem> masks("bench::masks", f.npairs);
  Kokkos::View<long*, Mem> sizes("bench::sizes", f.npairs), counts("bench::counts", f.npairs);
  Kokkos::parallel_for("bench::narrow_mask", Kokkos::RangePolicy<Exec>(f.exec, 0, f.npairs),
                       weft::NarrowMask<Mem>{f.side(), f.side(), f.pairs, masks, sizes, f.ns});
  Kokkos::View<weft::Contact*, Mem> contacts("bench::contacts", 0);
  long total = 0;
  for (auto _ : state) {
    Kokkos::deep_copy(f.exec, counts, sizes);  // the scan overwrites the counts, as in the handler
    total = long(weft::exclusive_scan(f.exec, counts, counts));
    if (long(contacts.extent(0)) < total) contacts = Kokkos::View<weft::Contact*, Mem>("bench::contacts", total);
    Kokkos::parallel_for("bench::narrow_fill", Kokkos::RangePolicy<Exec>(f.exec, 0, f.npairs),
                         weft::NarrowFill<Mem>{f.side(), f.side(), f.pairs, masks, counts, f.ns, contacts, 0});
    f.exec.fence();
  }
  weft::bench::items(state, total);
  state.counters["contacts"] = double(total);
}
BENCHMARK(narrow_fill)->Apply(weft::bench::triangles);

}  // namespace
