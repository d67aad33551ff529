// Tethers (long-range attachments, Kim, Chentanez and Müller 2012): a cloth point may be no farther from its
// nearest hard-pinned point than `length`, its shortest path to it along the cloth's edges at rest, times the
// scene's tether stretch. Gauss-Seidel moves a correction about one edge per iteration, so at one substep a
// frame a long hanging garment stretches under its own weight; a tether holds it in one step. Only the
// tethered point moves (its anchor has w = 0), so all tethers project side by side in one kernel.
#pragma once
#include "core/vec.hpp"

namespace weft {

struct Tether {
  int point, anchor;
  real length;  // allowed distance: path length at rest times the tether stretch
};

// p pulled straight back towards the anchor when farther than `length`; unchanged otherwise.
KOKKOS_INLINE_FUNCTION Vec3 tether_project(Vec3 p, Vec3 anchor, real length) {
  const Vec3 d = p - anchor;
  const real len2 = norm2(d);
  if (len2 <= length * length) return p;
  return anchor + (length / sqrt_(len2)) * d;
}

}  // namespace weft
