// Helpers shared by the benchmark bodies: the kept fixture, the size arguments, uploads and test data.
#pragma once
#include "core/hash.hpp"
#include "core/real.hpp"

#include <Kokkos_Core.hpp>
#include <benchmark/benchmark.h>

#include <array>
#include <memory>
#include <string>
#include <typeindex>
#include <vector>

namespace weft::bench {

// Google Benchmark calls a benchmark function several times while it picks the iteration count, so a
// fixture is built once per (type, size) and kept. Only the latest one lives, so the large fixtures of
// different benchmarks never add up; main drops it before Kokkos::finalize, since it holds Views.
struct FixtureSlot {
  std::shared_ptr<void> fixture;
  std::type_index type = typeid(void);
  long size = -1;
};

inline FixtureSlot& fixture_slot() {
  static FixtureSlot slot;
  return slot;
}

template <class T>
T& fixture(long size) {
  FixtureSlot& s = fixture_slot();
  if (!s.fixture || s.type != std::type_index(typeid(T)) || s.size != size) {
    s = FixtureSlot{};  // free the old fixture before building the new one
    s.fixture = std::make_shared<T>(size);
    s.type = typeid(T);
    s.size = size;
  }
  return *static_cast<T*>(s.fixture.get());
}

inline void drop_fixture() { fixture_slot() = FixtureSlot{}; }

// Sizes (triangles, elements or queries): 10K, 100K, 1M. Wall-clock time, since OpenMP threads and the GPU
// work outside the calling thread's CPU time.
inline void sizes(benchmark::internal::Benchmark* b, const char* name, std::vector<long> n = {10000, 100000, 1000000}) {
  b->ArgName(name);
  for (long k : n) b->Arg(k);
  b->UseRealTime();
}
inline void triangles(benchmark::internal::Benchmark* b) { sizes(b, "tris"); b->Unit(benchmark::kMillisecond); }
inline void elements(benchmark::internal::Benchmark* b) { sizes(b, "n"); b->Unit(benchmark::kMicrosecond); }

// Items per second = items per iteration x iterations / time.
inline void items(benchmark::State& state, long per_iteration) {
  state.SetItemsProcessed(int64_t(state.iterations()) * per_iteration);
}

// Deterministic data without a library RNG: the k-th number of stream `seed`, uniform in [0, 1).
KOKKOS_INLINE_FUNCTION real unit_random(uint64_t seed, uint64_t k) {
  return real(splitmix64(splitmix64(seed) ^ k) >> 11) * 0x1.0p-53;
}

template <class Mem, class T>
Kokkos::View<T*, Mem> upload(const std::vector<T>& h, const char* label) {
  Kokkos::View<T*, Mem> d(std::string(label), h.size());
  auto m = Kokkos::create_mirror_view(d);
  for (size_t i = 0; i < h.size(); ++i) m(i) = h[i];
  Kokkos::deep_copy(d, m);
  return d;
}

template <class Mem>
Kokkos::View<int* [3], Mem> upload_triangles(const std::vector<std::array<int, 3>>& t) {
  Kokkos::View<int* [3], Mem> d("bench::tris", t.size());
  auto m = Kokkos::create_mirror_view(d);
  for (size_t i = 0; i < t.size(); ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = t[i][k];
  Kokkos::deep_copy(d, m);
  return d;
}

}  // namespace weft::bench
