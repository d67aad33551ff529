#include "core/topology.hpp"

#include <algorithm>
#include <cstdint>

namespace weft {

real triangle_area(Vec3 a, Vec3 b, Vec3 c) { return 0.5 * norm(cross(b - a, c - a)); }

Topology build_topology(const std::vector<std::array<int, 3>>& tris) {
  // (edge key, triangle, corner opposite the edge), sorted by key then triangle: deterministic.
  struct Half { uint64_t key; int tri, a, b, opp; };
  std::vector<Half> h;
  h.reserve(tris.size() * 3);
  for (int t = 0; t < int(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3], o = tris[t][(k + 2) % 3];
      const uint64_t lo = uint64_t(std::min(a, b)), hi = uint64_t(std::max(a, b));
      h.push_back({lo << 32 | hi, t, a, b, o});
    }
  std::sort(h.begin(), h.end(), [](const Half& x, const Half& y) { return x.key != y.key ? x.key < y.key : x.tri < y.tri; });
  Topology topo;
  for (size_t i = 0; i < h.size();) {
    size_t j = i;
    while (j < h.size() && h[j].key == h[i].key) ++j;
    const int e = int(topo.edges.size());
    topo.edges.push_back({int(h[i].key >> 32), int(h[i].key & 0xffffffffu)});
    topo.edge_triangles.push_back({h[i].tri, j - i > 1 ? h[i + 1].tri : -1});
    if (j - i == 1) topo.boundary_edges.push_back(e);
    else if (j - i > 2) topo.nonmanifold_edges.push_back(e);
    else topo.bend_quads.push_back({h[i].opp, h[i + 1].opp, h[i].a, h[i].b});
    i = j;
  }
  return topo;
}

int Topology::edge_index(int a, int b) const {
  const std::array<int, 2> key{std::min(a, b), std::max(a, b)};
  const auto it = std::lower_bound(edges.begin(), edges.end(), key);
  return it != edges.end() && *it == key ? int(it - edges.begin()) : -1;
}

std::vector<std::array<int, 3>> triangle_neighbours(const std::vector<std::array<int, 3>>& tris) {
  const Topology topo = build_topology(tris);
  std::vector<std::array<int, 3>> nb(tris.size(), {-1, -1, -1});
  for (int t = 0; t < int(tris.size()); ++t)
    for (int k = 0; k < 3; ++k)
      for (int o : topo.edge_triangles[size_t(topo.edge_index(tris[t][k], tris[t][(k + 1) % 3]))])
        if (o >= 0 && o != t) {
          nb[t][k] = o;
          break;
        }
  return nb;
}

std::vector<real> lumped_masses(const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris,
                                real density) {
  std::vector<real> m(x.size(), 0.0);
  for (const auto& t : tris) {
    const real third = density * triangle_area(x[t[0]], x[t[1]], x[t[2]]) / 3;
    for (int k = 0; k < 3; ++k) m[t[k]] += third;
  }
  return m;
}

}  // namespace weft
