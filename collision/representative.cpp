#include "collision/representative.hpp"

#include <algorithm>
#include <map>

namespace weft {

std::vector<uint8_t> representative_features(const std::vector<std::array<int, 3>>& tris, int points) {
  std::vector<uint8_t> mask(tris.size(), 0);
  std::vector<int> vertex_owner(points, -1);
  std::map<std::pair<int, int>, int> edge_owner;
  for (int t = 0; t < int(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3];
      if (vertex_owner[a] < 0) { vertex_owner[a] = t; mask[t] |= uint8_t(1u << k); }
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (edge_owner.emplace(key, t).second) mask[t] |= uint8_t(1u << (3 + k));
    }
  return mask;
}

}  // namespace weft
