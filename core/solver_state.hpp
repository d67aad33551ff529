// The device-resident state of a running simulation, as seen by the solver's stages.
#pragma once
#include "core/vec.hpp"

#include <Kokkos_Core.hpp>

namespace weft {

template <class Exec>
struct SolverState {
  using Mem = typename Exec::memory_space;
  Exec exec;
  Kokkos::View<Vec3*, Mem> x;        // current (predicted, then corrected) positions
  Kokkos::View<Vec3*, Mem> x_start;  // positions at the start of the substep
  Kokkos::View<Vec3*, Mem> v;        // velocities
  Kokkos::View<real*, Mem> w;        // inverse masses (0: does not move)
  Kokkos::View<Vec3*, Mem> collider_x, collider_x_start;  // all collider vertices at substep end / start
};

}  // namespace weft
