// The main of every weft_bench_<backend>, included by its generated main.cpp: Kokkos around Google Benchmark.
// Kokkos reads its own arguments first (--kokkos-threads=N and the rest) and takes them out of argv, then
// Google Benchmark reads the --benchmark_* ones.
#include "bench/micro/bench_common.hpp"
#include "core/kokkos_compat.hpp"

#include <cstring>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  // weft's own spelling, --threads=N, becomes --kokkos-threads=N: Kokkos 3.4 reads --threads but leaves it in
  // argv, where Google Benchmark would reject it, and Kokkos 4 no longer reads it.
  std::vector<std::string> translated;
  translated.reserve(argc);
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--threads=", 10) == 0) {
      translated.push_back("--kokkos-threads=" + std::string(argv[i] + 10));
      argv[i] = translated.back().data();
    }
  Kokkos::initialize(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    Kokkos::finalize();
    return 1;
  }
  benchmark::AddCustomContext("weft_backend", WEFT_BENCH_BACKEND_NAME);
  benchmark::AddCustomContext("kokkos_version", weft::compat::kokkos_version_string());
  benchmark::AddCustomContext("kokkos_concurrency",
                              std::to_string(weft::compat::concurrency<WEFT_BENCH_EXECSPACE>()));
  benchmark::RunSpecifiedBenchmarks();
  weft::bench::drop_fixture();  // it holds Views, which must go before Kokkos does
  benchmark::Shutdown();
  Kokkos::finalize();
  return 0;
}
