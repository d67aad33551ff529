// Turns a scene's constraint tables into solver rows (host side, once per scene).
#pragma once
#include "constraints/rows.hpp"
#include "scene/scene.hpp"

#include <vector>

namespace weft {

// collider_offset[c] is the first vertex of collider c in the concatenated collider vertex array.
std::vector<Row> build_rows(const Scene& s, const std::vector<int>& collider_offset);

// The particles a row moves (for colouring).
int row_particles(const Row& r, int (&out)[8]);

}  // namespace weft
