// The paper's three solver schedules by name: the one table that `weft run --schedule`, `weft bench
// --schedules paper` and `weft info` (which the report scripts read) take them from.
#pragma once
#include "scene/scene.hpp"

#include <string>

namespace weft {

struct Schedule {
  const char* name;
  int iterations;        // constraint iterations per substep
  int collision_passes;  // per substep
  int substeps;          // per frame
};

inline constexpr Schedule kSchedules[] = {
    {"paper-1", 200, 20, 1},
    {"paper-2", 20, 2, 10},
    {"paper-3", 10, 1, 20},
};

// Sets st's iterations, collision passes and substeps to the named schedule's; false, st unchanged, for a
// name the table lacks.
inline bool apply_schedule(const std::string& name, SolverSettings& st) {
  for (const Schedule& s : kSchedules)
    if (name == s.name) {
      st.iterations = s.iterations;
      st.collision_passes = s.collision_passes;
      st.substeps = s.substeps;
      return true;
    }
  return false;
}

// "paper-1, paper-2, paper-3": the table's names, for messages.
inline std::string schedule_names() {
  std::string names;
  for (const Schedule& s : kSchedules) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

}  // namespace weft
