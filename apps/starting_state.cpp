// The cloth as a scene starts it: its triangle pairs that already intersect. The proximity contact model
// keeps a crossed pair crossed (docs/collisions.md), so `weft run` and `weft bench` warn and `weft check`
// lists them.
#include "apps/cli.hpp"
#include "backends/intersection_counter.hpp"

#include <cstdio>

namespace weft::cli {

std::vector<std::array<int, 2>> starting_intersections(Backend b, const Scene& s) {
  if (s.triangles.empty()) return {};
  return make_intersection_counter(b, s.name, s.triangles)->pairs(s.points.position);
}

std::string describe_triangle_pair(const Scene& s, const std::array<int, 2>& p) {
  const auto& a = s.triangles[size_t(p[0])];
  const auto& c = s.triangles[size_t(p[1])];
  char buf[160];
  std::snprintf(buf, sizeof buf, "triangles %d (points %d %d %d) and %d (points %d %d %d)", p[0], a[0], a[1], a[2],
                p[1], c[0], c[1], c[2]);
  return buf;
}

void warn_about_starting_state(Backend b, const Scene& s) {
  if (!s.settings.collision.self_collision) return;  // cloth that may pass through itself may start so
  const std::vector<std::array<int, 2>> pairs = starting_intersections(b, s);
  if (pairs.empty()) return;
  std::fprintf(stderr,
               "weft: warning: %s: the cloth starts with %zu intersecting triangle pairs, first %s; self "
               "contacts keep a crossed pair crossed: untangle the cloth first (weft check lists the pairs)\n",
               s.name.c_str(), pairs.size(), describe_triangle_pair(s, pairs.front()).c_str());
}

}  // namespace weft::cli
