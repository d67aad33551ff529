// Tethers of a scene (constraints/tether.hpp), built on the host once per scene.
#pragma once
#include "constraints/tether.hpp"
#include "scene/scene.hpp"

#include <vector>

namespace weft {

// One tether per movable point (w[i] > 0) that the cloth's edges (triangle edges and distance rows, such as
// stitches, at the initial positions) connect to a hard-pinned point (w = 0): to the nearest by path length,
// ties going to the lower index, with length = path length x s.settings.tether_stretch. Ordered by point.
// None when the tether stretch is 0.
std::vector<Tether> build_tethers(const Scene& s, const std::vector<real>& w);

}  // namespace weft
