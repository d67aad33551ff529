// Fenced wall time of one stage of a frame (SolverSettings::profile): device work is asynchronous, so the
// stage is fenced before and after and its time lands where it ran. Without profiling the stage just runs.
#pragma once
#include <Kokkos_Core.hpp>

#include <chrono>

namespace weft {

template <class F>
void timed_stage(bool profile, double& seconds, F&& stage) {
  if (!profile) {
    stage();
    return;
  }
  Kokkos::fence();
  const auto t0 = std::chrono::steady_clock::now();
  stage();
  Kokkos::fence();
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace weft
