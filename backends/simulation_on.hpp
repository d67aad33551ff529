// Simulation on one execution space; included only by backends/<backend>.cpp.
#pragma once
#include "backends/simulation.hpp"
#include "core/error.hpp"
#include "core/solver.hpp"

namespace weft {

template <class Exec>
class SimulationOn final : public Simulation {
 public:
  explicit SimulationOn(const Scene& scene) : solver_(checked(scene)) {}
  FrameStats step_frame() override { return solver_.step_frame(); }
  FrameStats measure() const override { return solver_.measure(); }
  int frame() const override { return solver_.frame(); }
  uint64_t hash_positions() const override { return solver_.hash_positions(); }
  std::vector<Vec3> positions() const override { return solver_.positions(); }
  std::vector<Vec3> velocities() const override { return solver_.velocities(); }
  int colour_count() const override { return solver_.colour_count(); }
  long row_count() const override { return solver_.row_count(); }

 private:
  static const Scene& checked(const Scene& s) {
    if (s.needs_collisions)
      throw InputError(s.name + ": this scene needs collision handling, which this build of weft does not have yet");
    return s;
  }
  Solver<Exec> solver_;
};

}  // namespace weft
