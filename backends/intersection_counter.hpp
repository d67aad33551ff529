// A triangle mesh's intersecting pairs (collision/mesh_intersections.hpp) on the backend chosen at run time:
// made once for the mesh's triangles, then counted at any number of positions (the frames of a cache, say).
#pragma once
#include "backends/backend.hpp"
#include "core/vec.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace weft {

class IntersectionCounter {
 public:
  virtual ~IntersectionCounter() = default;
  // Pairs of triangles that intersect at positions x (adjacent pairs excluded). Throws InputError naming the
  // mesh when x fails the checks a scene's cloth passes (validate_mesh, scene/mesh_checks.hpp).
  virtual long count(const std::vector<Vec3>& x) = 0;
  // The intersecting pairs (i < j) themselves, sorted; checked as count() checks x.
  virtual std::vector<std::array<int, 2>> pairs(const std::vector<Vec3>& x) = 0;
};

// `name` is the mesh's, for messages. Throws std::runtime_error when `b` is not compiled in.
std::unique_ptr<IntersectionCounter> make_intersection_counter(Backend b, const std::string& name,
                                                               const std::vector<std::array<int, 3>>& tris);

}  // namespace weft
