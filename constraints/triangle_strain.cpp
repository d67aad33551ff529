#include "constraints/triangle_strain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace weft {

namespace {

std::array<int, 3> sorted3(int a, int b, int c) {
  std::array<int, 3> t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

std::pair<int, int> edge_key(int a, int b) { return a < b ? std::pair{a, b} : std::pair{b, a}; }

}  // namespace

std::vector<TriangleRest> triangle_rest_shapes(const Scene& s) {
  const Constraints& c = s.constraints;
  // Rest shapes the triangle constraints store, keyed by their corners (Dm^-1 belongs to their corner order).
  std::map<std::array<int, 3>, TriangleRest> stored;
  for (const TriarapConstraint& t : c.triarap)
    stored.try_emplace(sorted3(t.p0, t.p1, t.p2), TriangleRest{{t.p0, t.p1, t.p2}, {t.dm_inv[0], t.dm_inv[1], t.dm_inv[2], t.dm_inv[3]}});
  for (const FemConstraint& f : c.fem)
    stored.try_emplace(sorted3(f.p0, f.p1, f.p2), TriangleRest{{f.p0, f.p1, f.p2}, {f.dm_inv[0], f.dm_inv[1], f.dm_inv[2], f.dm_inv[3]}});
  std::map<std::pair<int, int>, real> rest_length;
  for (const DistanceConstraint& d : c.distance) rest_length.try_emplace(edge_key(d.a, d.b), d.rest);
  const auto length = [&](int a, int b) {
    const auto it = rest_length.find(edge_key(a, b));
    return it == rest_length.end() ? real(-1) : it->second;
  };
  std::vector<TriangleRest> out;
  out.reserve(s.triangles.size());
  for (const std::array<int, 3>& t : s.triangles) {
    const auto it = stored.find(sorted3(t[0], t[1], t[2]));
    if (it != stored.end()) {
      out.push_back(it->second);
      continue;
    }
    Vec3 p0 = s.points.position[t[0]], p1 = s.points.position[t[1]], p2 = s.points.position[t[2]];
    const real a = length(t[0], t[1]), b = length(t[0], t[2]), e = length(t[1], t[2]);
    if (a > 0 && b > 0 && e > 0) {  // the triangle with the edges' rest lengths, when one exists
      const real x = (a * a + b * b - e * e) / (2 * a), y2 = b * b - x * x;
      if (y2 > 0) {
        p0 = Vec3{0, 0, 0};
        p1 = Vec3{a, 0, 0};
        p2 = Vec3{x, std::sqrt(y2), 0};
      }
    }
    TriangleRest r{{t[0], t[1], t[2]}, {}};
    real area = 0;
    triarap_rest(p0, p1, p2, r.dm_inv, area);
    if (area > 0) out.push_back(r);
  }
  return out;
}

}  // namespace weft
