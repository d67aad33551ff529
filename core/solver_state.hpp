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

// The collision stage plugs into the frame schedule through these calls (collision/ implements it).
template <class Exec>
class CollisionStage {
 public:
  virtual ~CollisionStage() = default;
  virtual void begin_substep(const SolverState<Exec>& s, real h, int substep) = 0;  // substep: of the frame, from 0
  virtual void pass(const SolverState<Exec>& s, real h) = 0;     // detect contacts (a collision pass)
  virtual void project(const SolverState<Exec>& s, real h) = 0;  // one Gauss-Seidel sweep over contacts
  virtual void finish_positions(const SolverState<Exec>& s, real h) = 0;  // after the last iteration
  virtual void end_substep(const SolverState<Exec>& s, real h) = 0;  // after v = (x - x_start) / h
  // After project(): whether a pass should run before the next sweep, beside the scheduled ones.
  virtual bool wants_pass(const SolverState<Exec>&) { return false; }
};

}  // namespace weft
