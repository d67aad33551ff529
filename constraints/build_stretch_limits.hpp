// Long-range stretch limits of a scene (docs/solver.md, "Stretch limits"), built on the host once per scene.
#pragma once
#include "constraints/rows.hpp"
#include "scene/scene.hpp"

#include <vector>

namespace weft {

// Hops between the two points of a level-k limit (k = 1, 2, 3): 4, 16, 64.
constexpr int stretch_limit_hops(int level) { return level <= 0 ? 1 : 4 * stretch_limit_hops(level - 1); }
static_assert(stretch_limit_hops(1) == 4 && stretch_limit_hops(2) == 16 && stretch_limit_hops(3) == 64);

// Distance rows that only pull (compress compliance +inf, constraints/xpbd.hpp), for every level up to
// s.settings.stretch_limits: from each point to the points exactly stretch_limit_hops(k) triangle edges
// away that lie most nearly in a straight line from it (straight distance at least 0.9 of the path and 0.97
// of the straightest's; at most six, the straightest first, ties to the lower index), each pair once. A limit's length is its path along the edges at
// rest (through points each one hop nearer), so the rest shape and any bending of it satisfy every limit;
// its compliance is the path's hops times the softest stretch compliance of the distance rows at its two
// points (edges in series), and points with no distance row get none. Pairs of two points that do not move
// (w = 0) are left out. Ordered by (lower point, higher point). None when s.settings.stretch_limits is 0.
std::vector<Row> build_stretch_limits(const Scene& s, const std::vector<real>& w);

}  // namespace weft
