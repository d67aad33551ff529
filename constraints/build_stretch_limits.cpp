#include "constraints/build_stretch_limits.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace weft {

namespace {

// Breadth-first rings over the triangle edges from one point, out to a number of hops. A point's path is
// the shortest over its neighbours one ring nearer: at least the shortest path along the edges, so never
// shorter than the cloth between the two points.
class Rings {
 public:
  explicit Rings(const Scene& s) : x_(s.points.position), nbr_(s.points.size()), hop_(s.points.size(), -1),
                                   path_(s.points.size(), std::numeric_limits<real>::infinity()) {
    for (const auto& t : s.triangles)
      for (int k = 0; k < 3; ++k) {
        nbr_[t[k]].push_back(t[(k + 1) % 3]);
        nbr_[t[(k + 1) % 3]].push_back(t[k]);
      }
    for (auto& v : nbr_) {  // sorted and unique: the search depends only on the scene
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    }
  }

  // Rings 1..far from a; on_ring(h, points of ring h, ascending) after each ring's paths are known.
  template <class F>
  void search(int a, int far, F&& on_ring) {
    std::vector<int> ring(1, a), seen(1, a);
    hop_[a] = 0;
    path_[a] = 0;
    for (int h = 1; h <= far && !ring.empty(); ++h) {
      std::vector<int> next;
      for (int u : ring)
        for (int v : nbr_[u])
          if (hop_[v] < 0) {
            hop_[v] = h;
            next.push_back(v);
            seen.push_back(v);
          }
      std::sort(next.begin(), next.end());
      for (int v : next)
        for (int u : nbr_[v])
          if (hop_[u] == h - 1) path_[v] = std::min(path_[v], path_[u] + norm(x_[v] - x_[u]));
      on_ring(h, next);
      ring.swap(next);
    }
    for (int v : seen) {
      hop_[v] = -1;
      path_[v] = std::numeric_limits<real>::infinity();
    }
  }

  real path(int v) const { return path_[v]; }

 private:
  const std::vector<Vec3>& x_;
  std::vector<std::vector<int>> nbr_;
  std::vector<int> hop_;
  std::vector<real> path_;
};

}  // namespace

std::vector<Row> build_stretch_limits(const Scene& s, const std::vector<real>& w) {
  const int levels = s.settings.stretch_limits;
  const size_t n = s.points.size();
  if (levels <= 0 || n == 0) return {};
  // The softest stretch compliance of the distance rows at each point; -1 where there is none.
  std::vector<real> soft(n, -1);
  for (const DistanceConstraint& d : s.constraints.distance)
    for (int p : {d.a, d.b}) soft[p] = std::max(soft[p], d.m.compliance);
  const auto& x = s.points.position;
  const int far = stretch_limit_hops(levels);
  Rings rings(s);

  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < n; ++i) {
    if (soft[i] < 0) continue;
    rings.search(int(i), far, [&](int h, const std::vector<int>& ring) {
      bool level = false;
      for (int k = 1; k <= levels; ++k) level = level || h == stretch_limit_hops(k);
      if (!level) return;
      std::vector<std::pair<real, int>> straight;  // (-straightness, point): the straightest first
      for (int v : ring) {
        if (soft[v] < 0 || (w[i] == 0 && w[v] == 0) || !(rings.path(v) > 0)) continue;
        const real r = norm(x[v] - x[i]) / rings.path(v);
        if (r >= 0.9) straight.push_back({-r, v});
      }
      std::sort(straight.begin(), straight.end());
      for (size_t k = 0; k < straight.size() && k < 6 && -straight[k].first >= -0.97 * straight[0].first; ++k)
        pairs.push_back({std::min(int(i), straight[k].second), std::max(int(i), straight[k].second)});
    });
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

  // Each pair's rest path from its lower point (the same rings, searched again).
  std::vector<Row> rows;
  rows.reserve(pairs.size());
  for (size_t k = 0; k < pairs.size();) {
    const int a = pairs[k].first;
    size_t end = k;
    while (end < pairs.size() && pairs[end].first == a) ++end;
    rings.search(a, far, [&](int h, const std::vector<int>& ring) {
      for (size_t j = k; j < end; ++j) {
        const int b = pairs[j].second;
        if (!std::binary_search(ring.begin(), ring.end(), b)) continue;
        Row r;
        r.kind = kRowDistance;
        r.n = 2;
        r.idx[0] = a;
        r.idx[1] = b;
        r.rest = rings.path(b);
        r.m.compliance = real(h) * std::max(soft[a], soft[b]);  // h edges in series
        r.m.compress_compliance = std::numeric_limits<real>::infinity();  // pulls only
        r.m.damping_ratio = 0;
        rows.push_back(r);
      }
    });
    k = end;
  }
  return rows;
}

}  // namespace weft
