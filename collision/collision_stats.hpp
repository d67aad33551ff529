// What the collision stage reports for one frame (FrameStats::collision, the cache's stats table).
#pragma once

namespace weft {

struct CollisionStats {
  long contacts = 0;            // contacts found by the last collision pass
  long impact_zone_points = 0;  // points smoothed at the end of the last substep
  long failsafe_points = 0;     // ccd: points the crossing fail-safe moved back, over the frame's substeps
  long failsafe_rounds = 0;     // ccd: its rounds (each a pass over the candidate pairs)
  long failsafe_pinned = 0;     // ccd: of failsafe_points, pinned points held back (they trail their animation)
  long queries = 0;             // proximity: passes that queried pairs afresh (the others kept the last query's
                                // self pairs: CollisionSettings::pair_refresh)
  long early_passes = 0;        // proximity: passes run early because many points were cut back to their bounds
  long still_passes = 0;        // proximity: refreshes that found the cloth still and kept the last measured contacts
  long points_cut_back = 0;     // proximity: points cut back to their bounds, summed over the truncations
  // With SolverSettings::profile (fenced): the trees' build at each substep's start, and the parts of the
  // collision passes (refit and queries, narrow phase, contact colouring).
  double seconds_lbvh_build = 0, seconds_broad_phase = 0, seconds_narrow_phase = 0, seconds_contact_colouring = 0;
};

}  // namespace weft
