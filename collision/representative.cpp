#include "collision/representative.hpp"

#include "core/topology.hpp"

namespace weft {

std::vector<uint8_t> representative_features(const std::vector<std::array<int, 3>>& tris, int points) {
  std::vector<uint8_t> mask(tris.size(), 0);
  std::vector<int> vertex_owner(points, -1);
  const Topology topo = build_topology(tris);
  std::vector<uint8_t> edge_owned(topo.edges.size(), 0);
  for (int t = 0; t < int(tris.size()); ++t)  // ascending: each feature goes to the first triangle that has it
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3];
      if (vertex_owner[a] < 0) { vertex_owner[a] = t; mask[t] |= uint8_t(1u << k); }
      uint8_t& owned = edge_owned[size_t(topo.edge_index(a, b))];
      if (!owned) { owned = 1; mask[t] |= uint8_t(1u << (3 + k)); }
    }
  return mask;
}

}  // namespace weft
