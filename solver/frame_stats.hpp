// Per-frame figures a run reports (and tests assert on).
#pragma once
#include "core/real.hpp"

#include <cstdint>

namespace weft {

struct FrameStats {
  int frame = 0;
  real kinetic_energy = 0;  // J, over points that move
  real max_speed = 0;       // m/s
  real max_strain = 0;      // largest triangle strain (constraints/triangle_strain.hpp: principal stretches)
  real p99_strain = 0;      // its 99th percentile over the triangles
  real max_edge_strain = 0; // max |length / rest - 1| over distance constraints
  real rms_speed = 0;       // m/s, over points that move
  long non_finite = 0;      // points whose position is NaN or Inf
  long contacts = 0;            // contacts found by the last collision pass
  long impact_zone_points = 0;  // points smoothed at the end of the last substep
  long failsafe_points = 0;     // points the crossing fail-safe moved back, over the frame's substeps
  long failsafe_rounds = 0;     // its rounds (each a pass over the candidate pairs), over the frame's substeps
  long failsafe_pinned = 0;     // of failsafe_points, pinned points held back (they trail their animation)
  long collision_queries = 0;   // proximity contacts: passes that queried pairs afresh (the others kept the
                                // last query's self pairs: CollisionSettings::pair_refresh)
  long early_passes = 0;        // passes run early because many points were cut back to their bounds
  long points_cut_back = 0;     // points cut back to their displacement bounds, summed over the truncations
  real max_pin_lag = 0;         // m, largest distance of a pinned point from its animated target
  double seconds = 0;       // wall time of the frame
  // With SolverSettings::profile (a fence after each stage, so a little slower): wall time per stage.
  double seconds_constraints = 0, seconds_collision_passes = 0, seconds_contacts = 0, seconds_smoothing = 0,
         seconds_failsafe = 0;
  long collision_passes = 0;    // scheduled and early
  // Inside the collision stage (with profile): the trees' build at each substep's start, and the parts of
  // the collision passes (refit and queries, narrow phase with CCD, contact colouring).
  double seconds_lbvh_build = 0, seconds_broad_phase = 0, seconds_narrow_phase = 0, seconds_contact_colouring = 0;
};

}  // namespace weft
