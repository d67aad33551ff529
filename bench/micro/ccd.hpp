// The CCD alone (collision/ccd.hpp: ccd_vertex_face, ccd_edge_edge) through ccd_batch, one query a thread,
// with the narrow phase's settings. Queries are cloth-sized: 1 cm features that move up to a few mm, one
// side approaching the other by up to 2 cm, minimum separation 3.6 mm (two of cloth_layers.hpp's
// thicknesses); the counter `hits` says what share of them collide.
#pragma once
#include "bench/micro/bench_common.hpp"
#include "collision/ccd_batch.hpp"
#include "collision/narrow_phase.hpp"

namespace {

using Exec = WEFT_BENCH_EXECSPACE;
using Mem = Exec::memory_space;
using weft::real;
using weft::Vec3;

constexpr real kFeature = 0.01, kJitter = 0.002, kApproach = 0.02, kSeparation = 0.0036;

template <weft::CcdKind K>
struct CcdQueries {
  Kokkos::View<Vec3*, Mem> rows;  // 8 per query: four start positions, four end positions
  Kokkos::View<weft::CcdResult*, Mem> out;
  long n;

  explicit CcdQueries(long queries) : n(queries) {
    std::vector<Vec3> h(8 * n);
    for (long q = 0; q < n; ++q) {
      long k = 0;
      auto r = [&](real lo, real hi) { return lo + (hi - lo) * weft::bench::unit_random(uint64_t(K) + 2, 32 * q + k++); };
      auto jitter = [&] { return Vec3{r(-kJitter, kJitter), r(-kJitter, kJitter), r(-kJitter, kJitter)}; };
      // Moving side: a vertex (vertex-face) or an edge along x (edge-edge), above the static side.
      const Vec3 a{r(-0.25, 1.0) * kFeature, r(0.1, 2.0) * kFeature, r(-0.25, 1.0) * kFeature};
      const Vec3 drop{0, -r(0, kApproach), 0};
      // Static side, y = 0: the triangle (0, 0, 0), (1, 0, 0), (0, 0, 1) cm, or an edge along z.
      Vec3 start[4], end[4];
      if (K == weft::CcdKind::VertexFace) {
        start[0] = a;
        start[1] = Vec3{0, 0, 0} + jitter();
        start[2] = Vec3{kFeature, 0, 0} + jitter();
        start[3] = Vec3{0, 0, kFeature} + jitter();
      } else {
        start[0] = Vec3{a.x - kFeature / 2, a.y, a.z} + jitter();
        start[1] = Vec3{a.x + kFeature / 2, a.y, a.z} + jitter();
        start[2] = Vec3{a.x, 0, -kFeature / 2} + jitter();
        start[3] = Vec3{a.x, 0, kFeature / 2} + jitter();
      }
      const int moving = K == weft::CcdKind::VertexFace ? 1 : 2;  // the vertex, or the upper edge's two points
      for (int j = 0; j < 4; ++j) end[j] = start[j] + jitter() + (j < moving ? drop : Vec3{});
      for (int j = 0; j < 4; ++j) { h[8 * q + j] = start[j]; h[8 * q + 4 + j] = end[j]; }
    }
    rows = weft::bench::upload<Mem>(h, "bench::ccd_rows");
    out = Kokkos::View<weft::CcdResult*, Mem>("bench::ccd_out", n);
  }

  double hit_share() const {
    auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
    long hits = 0;
    for (long q = 0; q < n; ++q) hits += m(q).hit;
    return n ? double(hits) / double(n) : 0;
  }
};

template <weft::CcdKind K>
void run_ccd(benchmark::State& state) {
  auto& f = weft::bench::fixture<CcdQueries<K>>(state.range(0));
  const Exec exec;
  const weft::CcdSettings settings = weft::NarrowSettings{}.ccd;
  for (auto _ : state) {
    weft::ccd_batch(exec, K, Kokkos::View<const Vec3*, Mem>(f.rows), kSeparation, settings, f.out);
    exec.fence();
  }
  weft::bench::items(state, f.n);
  state.counters["hits"] = f.hit_share();
}

void ccd_vertex_face(benchmark::State& state) { run_ccd<weft::CcdKind::VertexFace>(state); }
void ccd_edge_edge(benchmark::State& state) { run_ccd<weft::CcdKind::EdgeEdge>(state); }

void queries(benchmark::internal::Benchmark* b) {
  weft::bench::sizes(b, "queries", {1000, 10000, 100000});
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK(ccd_vertex_face)->Apply(queries);
BENCHMARK(ccd_edge_edge)->Apply(queries);

}  // namespace
