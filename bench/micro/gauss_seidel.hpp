// One constraint iteration of the XPBD solver: Solver::gauss_seidel_sweep (solver/solver.hpp), one kernel
// launch per colour and row kind over every distance and bend row, on the hanging sheet (cloth_grid.hpp) one substep
// after the start, so positions, lambdas and x_start are those of a running solve. Counter `bytes`: what a
// sweep must move at the least (every packed row and lambda once, every point's position, start position and
// inverse mass read and its position written once); `bytes_per_second` against the card's memory bandwidth
// is how far the sweep is from its floor.
#pragma once
#include "bench/micro/bench_common.hpp"
#include "bench/micro/cloth_grid.hpp"
#include "solver/solver.hpp"

namespace {

using Exec = WEFT_BENCH_EXECSPACE;

struct SweepFixture {
  std::unique_ptr<weft::Solver<Exec>> solver;
  weft::real h = 0;
  explicit SweepFixture(long triangles) {
    const weft::Scene scene = weft::bench::hanging_sheet(triangles);
    h = 1 / (scene.settings.fps * scene.settings.substeps);
    solver = std::make_unique<weft::Solver<Exec>>(scene);
    solver->substep(0);
    Exec().fence();
  }
};

void gauss_seidel_sweep(benchmark::State& state) {
  SweepFixture& f = weft::bench::fixture<SweepFixture>(state.range(0));
  const Exec exec;
  for (auto _ : state) {
    f.solver->gauss_seidel_sweep(f.h);
    exec.fence();
  }
  weft::bench::items(state, f.solver->row_count());
  const double points = double(f.solver->state().x.extent(0));
  const double bytes = double(f.solver->row_storage_bytes()) + 16.0 * double(f.solver->row_count()) +
                       points * (3 * sizeof(weft::Vec3) + sizeof(weft::real));
  state.counters["rows"] = double(f.solver->row_count());
  state.counters["colours"] = f.solver->colour_count();
  state.counters["bytes"] = bytes;
  state.counters["bytes_per_second"] = benchmark::Counter(bytes, benchmark::Counter::kIsIterationInvariantRate);
}
// The skirt's size (300K triangles) besides the usual three.
BENCHMARK(gauss_seidel_sweep)->Apply([](benchmark::internal::Benchmark* b) {
  weft::bench::sizes(b, "tris", {10000, 100000, 300000, 1000000});
  b->Unit(benchmark::kMicrosecond);
});

}  // namespace
