// The checks validate_scene (scene/scene.hpp) makes of the cloth's positions and triangles, for a mesh that is
// not a scene: the frames of a cache or an OBJ file whose intersections are counted, say.
#pragma once
#include "core/vec.hpp"

#include <array>
#include <string>
#include <vector>

namespace weft {

// Throws InputError("name: ...") naming the element, with validate_scene's messages: a non-finite position,
// a triangle index out of range, a zero-area triangle.
void validate_mesh(const std::string& name, const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris);

}  // namespace weft
