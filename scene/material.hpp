// The material every constraint table of the scene stores (scene/scene.hpp), in the form the XPBD update
// (constraints/xpbd.hpp) reads it.
#pragma once
#include "core/real.hpp"

namespace weft {

// Per-constraint material, as stored: compliances (1/stiffness; 0 = rigid) and Vellum's damping ratio.
struct XpbdMaterial {
  real compliance = 0;           // used while C >= 0
  real compress_compliance = 0;  // used while C < 0 (Vellum's compressstiffness)
  real damping_ratio = 0;
};

// A row of this material only pulls: its compress compliance is +inf (DBL_MAX is the largest finite).
KOKKOS_INLINE_FUNCTION bool pulls_only(const XpbdMaterial& m) { return m.compress_compliance > 1.7976931348623157e308; }

// Vellum stiffness -> compliance; compressstiffness -1 means "same as stiffness", 0 no resistance while
// compressed (compress compliance +inf: the row only pulls, constraints/xpbd.hpp). k = 0 is never stored
// (those constraints are skipped when built).
inline XpbdMaterial xpbd_material(real stiffness, real compress_stiffness, real damping_ratio) {
  XpbdMaterial m;
  m.compliance = 1 / stiffness;
  m.compress_compliance = compress_stiffness < 0 ? m.compliance : 1 / compress_stiffness;
  m.damping_ratio = damping_ratio;
  return m;
}

}  // namespace weft
