// Turns a scene's constraint tables into solver rows (host side, once per scene).
#pragma once
#include "constraints/rows.hpp"
#include "scene/scene.hpp"

#include <vector>

namespace weft {

// collider_first_vertex: ColliderSet::first_vertex (scene/collider_set.hpp), where attachments find their
// collider triangle's vertices.
std::vector<Row> build_rows(const Scene& s, const std::vector<int>& collider_first_vertex);

// The particles a row moves (for colouring).
int row_particles(const Row& r, int (&out)[8]);

}  // namespace weft
