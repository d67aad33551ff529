// One stage of a frame, as a Kokkos Tools region (any Kokkos profiler shows the stages, e.g. nsys with the
// nvtx connector), and with SolverSettings::profile its fenced wall time: device work is asynchronous, so
// the stage is fenced before and after and its time lands where it ran. Without profiling the stage just
// runs.
#pragma once
#include <Kokkos_Core.hpp>

#include <chrono>

namespace weft {

template <class F>
void timed_stage(const char* region, bool profile, double& seconds, F&& stage) {
  Kokkos::Profiling::pushRegion(region);
  if (!profile) {
    stage();
    Kokkos::Profiling::popRegion();
    return;
  }
  Kokkos::fence();
  const auto t0 = std::chrono::steady_clock::now();
  stage();
  Kokkos::fence();
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Kokkos::Profiling::popRegion();
}

}  // namespace weft
