// Every collider of a scene as one mesh over their vertices concatenated in the scene's collider order: the
// layout the solver's animation, the collision stage, attachments, the solvability check and the contact
// sheet share, built here once.
#pragma once
#include "scene/scene.hpp"

#include <array>
#include <vector>

namespace weft {

struct ColliderSet {
  std::vector<int> first_vertex{0};                // per collider, then the vertex count
  std::vector<std::array<int, 3>> triangles;       // every collider's triangles over the concatenated vertices
  std::vector<int> triangle_collider;              // per triangle, its collider
  std::vector<real> vertex_thickness, vertex_friction;  // per vertex, its collider's
  int frames = 0;  // the longest collider animation (shorter ones hold their last frame)
  int colliders() const { return int(first_vertex.size()) - 1; }
  int vertices() const { return first_vertex.back(); }
};

ColliderSet make_collider_set(const std::vector<Collider>& colliders);

// Every collider vertex at stored frame f (0-based; from 0 to set.frames - 1), each collider holding its last
// frame past its end.
std::vector<Vec3> collider_positions(const std::vector<Collider>& colliders, const ColliderSet& set, int f);

}  // namespace weft
