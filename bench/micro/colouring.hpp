// Colouring. Constraint rows: the solver's greedy colouring (core/colouring.hpp, host, once per scene) of
// the hanging sheet's rows, the same on every backend. Contacts: Jones-Plassmann on the device
// (collision/contact_colouring.hpp, every collision pass) of the contacts of two cloth layers
// (cloth_layers.hpp).
#pragma once
#include "bench/micro/cloth_layers.hpp"
#include "constraints/build_rows.hpp"
#include "core/colouring.hpp"

#include <chrono>

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Mem = Exec::memory_space;

struct RowsFixture {
  std::vector<weft::Row> rows;
  std::vector<char> movable;
  explicit RowsFixture(long triangles) {
    const weft::Scene scene = weft::bench::hanging_sheet(triangles);
    rows = weft::build_rows(scene, {});
    for (size_t i = 0; i < scene.points.size(); ++i)
      movable.push_back(scene.points.mass[i] > 0 && !(scene.points.stopped[i] & 1));
  }
};

void colour_rows_host(benchmark::State& state) {
  RowsFixture& f = weft::bench::fixture<RowsFixture>(state.range(0));
  int colours = 0;
  for (auto _ : state) {
    const weft::Colouring c = weft::colour_greedy(long(f.rows.size()), long(f.movable.size()), f.movable,
                                                  [&](long r, int(&out)[8]) { return weft::row_particles(f.rows[r], out); });
    colours = c.count;
  }
  weft::bench::items(state, long(f.rows.size()));
  state.counters["rows"] = double(f.rows.size());
  state.counters["colours"] = colours;
}
BENCHMARK(colour_rows_host)->Apply(weft::bench::triangles);

// The narrow phase's contacts of the layers, written once.
struct ContactsFixture {
  weft::bench::ClothLayers<Exec> layers;
  Kokkos::View<weft::Contact*, Mem> contacts{"bench::contacts", 0};
  long n = 0;
  explicit ContactsFixture(long triangles) : layers(triangles) {
    weft::NarrowPipeline<Exec> narrow;
    n = narrow.run(layers.exec, layers.side(), layers.side(), layers.ns, layers.pairs, layers.npairs, contacts, 0);
    layers.exec.fence();
  }
};

// Times the colouring alone: every iteration first restores the contacts' narrow-phase order (colour()
// sorts them by colour, and a sorted list would colour differently), outside the timed part.
void colour_contacts(benchmark::State& state) {
  ContactsFixture& f = weft::bench::fixture<ContactsFixture>(state.range(0));
  const Exec exec = f.layers.exec;
  weft::ContactColouring<Exec> colouring;
  Kokkos::View<weft::Contact*, Mem> work("bench::contacts_work", f.n);
  size_t colours = 0;
  for (auto _ : state) {
    Kokkos::deep_copy(exec, Kokkos::subview(work, std::make_pair(0L, f.n)), f.contacts);
    exec.fence();
    const auto t0 = std::chrono::steady_clock::now();
    colours = colouring.colour(exec, work, f.n, f.layers.w).size() - 1;
    exec.fence();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  weft::bench::items(state, f.n);
  state.counters["contacts"] = double(f.n);
  state.counters["colours"] = double(colours);
}
BENCHMARK(colour_contacts)->Apply([](benchmark::internal::Benchmark* b) {
  b->ArgName("tris");
  for (long n : {10000L, 100000L, 1000000L}) b->Arg(n);
  b->UseManualTime()->Unit(benchmark::kMillisecond);
});

}  // namespace
