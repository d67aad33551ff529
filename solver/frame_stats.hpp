// Per-frame figures a run reports (and tests assert on): the state's measures, and what each stage reports
// for the frame through its own struct.
#pragma once
#include "collision/collision_stats.hpp"
#include "core/real.hpp"

namespace weft {

// The frame's schedule as the solver ran it.
struct ScheduleStats {
  long collision_passes = 0;  // scheduled and early
  // With SolverSettings::profile (a fence after each stage, so a little slower): wall time per stage.
  double seconds_constraints = 0, seconds_collision_passes = 0, seconds_contacts = 0, seconds_smoothing = 0,
         seconds_failsafe = 0;
};

struct FrameStats {
  int frame = 0;
  real kinetic_energy = 0;  // J, over points that move
  real max_speed = 0;       // m/s
  real max_strain = 0;      // largest triangle strain (constraints/triangle_strain.hpp: principal stretches)
  real p99_strain = 0;      // its 99th percentile over the triangles
  real max_edge_strain = 0; // max |length / rest - 1| over distance constraints
  real rms_speed = 0;       // m/s, over points that move
  long non_finite = 0;      // points whose position is NaN or Inf
  real max_pin_lag = 0;     // m, largest distance of a pinned point from its animated target (or a still
                            // one from where it stands)
  double seconds = 0;       // wall time of the frame
  ScheduleStats schedule;   // the solver's schedule
  CollisionStats collision; // the collision stage (zeros without one)
};

}  // namespace weft
