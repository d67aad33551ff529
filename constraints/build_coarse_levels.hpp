// Coarse levels of a scene's stretch rows (docs/solver.md, "Coarse levels"; hierarchical position-based
// dynamics, Müller 2008), built on the host once per scene.
#pragma once
#include "constraints/rows.hpp"
#include "scene/scene.hpp"

#include <vector>

namespace weft {

// One level: rows among its points, and how the points of the level below that are not on it follow it.
struct CoarseLevel {
  std::vector<Row> rows;      // distance rows that only pull, between the level's points
  std::vector<int> follower;  // points of the level below not on this one, ascending
  std::vector<long> offset;   // follower k follows parent[offset[k] .. offset[k + 1])
  std::vector<int> parent;
  std::vector<real> weight;   // per parent, summing to 1 per follower
};

// Level 0 is the graph of the scene's distance rows (the points with one). Level k + 1 takes a maximal set
// of level k's points no two of which are neighbours (the points that do not move first, then by index, so
// it depends only on the scene); every other point of level k follows its neighbours on level k + 1,
// weighted by the inverse of their rest distance. Level k + 1's rows join its points that are linked on level
// k through at most two followers (paths of two or three rows); a row's length is the shortest such path at
// rest (so the rest shape and any bending of it satisfy it), its compliance the sum along that path (rows
// in series), and it only pulls (compress compliance +inf). Rows of two points that do not move are left
// out. Returns s.settings.coarse_levels levels, the coarsest last, or fewer where the next level would have
// no rows (a single point left); none when coarse_levels is 0.
std::vector<CoarseLevel> build_coarse_levels(const Scene& s, const std::vector<real>& w);

}  // namespace weft
