// The collision stage plugs into the solver's frame schedule through these calls; CollisionHandler
// implements them.
#pragma once
#include "collision/collision_stats.hpp"
#include "core/solver_state.hpp"

namespace weft {

template <class Exec>
class CollisionStage {
 public:
  virtual ~CollisionStage() = default;
  virtual void begin_frame() = 0;                                                    // frame_stats() starts anew
  virtual void begin_substep(const SolverState<Exec>& s, real h, int substep) = 0;  // substep: of the frame, from 0
  virtual void pass(const SolverState<Exec>& s, real h) = 0;     // detect contacts (a collision pass)
  virtual void project(const SolverState<Exec>& s, real h) = 0;  // one Gauss-Seidel sweep over contacts
  virtual void finish_positions(const SolverState<Exec>& s, real h) = 0;  // after the last iteration
  virtual void end_substep(const SolverState<Exec>& s, real h) = 0;  // after v = (x - x_start) / h
  // After project(): whether a pass should run before the next sweep, beside the scheduled ones.
  virtual bool wants_pass(const SolverState<Exec>&) { return false; }
  virtual void end_frame(const SolverState<Exec>&) {}  // after the frame's last substep
  virtual void colliders_streamed() {}  // the colliders follow streamed frames from now on: they may move
  // The frame so far: sums since begin_frame(), the last pass's and substep's counts.
  virtual CollisionStats frame_stats() const = 0;
};

}  // namespace weft
