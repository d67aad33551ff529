#include "constraints/build_tethers.hpp"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace weft {

std::vector<Tether> build_tethers(const Scene& s, const std::vector<real>& w) {
  const real stretch = s.settings.tether_stretch;
  const size_t n = s.points.size();
  if (stretch <= 0 || n == 0) return {};
  // Undirected edges as adjacency lists (compressed rows), in input order: the search below depends only on
  // the scene.
  std::vector<std::pair<int, int>> edges;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) edges.push_back({t[k], t[(k + 1) % 3]});
  for (const DistanceConstraint& d : s.constraints.distance) edges.push_back({d.a, d.b});
  std::vector<size_t> off(n + 1, 0);
  for (const auto& [a, b] : edges) { ++off[a + 1]; ++off[b + 1]; }
  for (size_t i = 0; i < n; ++i) off[i + 1] += off[i];
  std::vector<int> nbr(off[n]);
  std::vector<size_t> fill(off.begin(), off.end() - 1);
  for (const auto& [a, b] : edges) { nbr[fill[a]++] = b; nbr[fill[b]++] = a; }

  // Dijkstra from every hard-pinned point at once; the queue orders by (distance, point), so ties resolve
  // the same way on every machine.
  const real inf = std::numeric_limits<real>::infinity();
  std::vector<real> dist(n, inf);
  std::vector<int> anchor(n, -1);
  using Item = std::pair<real, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (size_t i = 0; i < n; ++i)
    if (w[i] == 0) {
      dist[i] = 0;
      anchor[i] = int(i);
      queue.push({0, int(i)});
    }
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    for (size_t k = off[i]; k < off[i + 1]; ++k) {
      const int j = nbr[k];
      const real dj = d + norm(s.points.position[j] - s.points.position[i]);
      if (dj < dist[j] || (dj == dist[j] && anchor[i] < anchor[j])) {
        dist[j] = dj;
        anchor[j] = anchor[i];
        queue.push({dj, j});
      }
    }
  }
  std::vector<Tether> out;
  for (size_t i = 0; i < n; ++i)
    if (w[i] > 0 && anchor[i] >= 0) out.push_back({int(i), anchor[i], dist[i] * stretch});
  return out;
}

}  // namespace weft
