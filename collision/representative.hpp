// Representative triangles (Curtis, Tamstorf and Manocha 2008): every vertex and every edge of a mesh is
// owned by exactly one of its triangles (the lowest-numbered one), so a triangle pair produces each
// vertex-face and edge-edge feature pair once. Bits 0-2: the triangle owns its corner k; bits 3-5: it owns
// its edge (corner k, corner k+1).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace weft {

std::vector<uint8_t> representative_features(const std::vector<std::array<int, 3>>& triangles, int points);

}  // namespace weft
