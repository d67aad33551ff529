#include "scene/collider_set.hpp"

#include <algorithm>

namespace weft {

ColliderSet make_collider_set(const std::vector<Collider>& colliders) {
  ColliderSet s;
  s.first_vertex.clear();
  int off = 0;
  for (size_t k = 0; k < colliders.size(); ++k) {
    const Collider& c = colliders[k];
    s.first_vertex.push_back(off);
    for (const auto& t : c.triangles) {
      s.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
      s.triangle_collider.push_back(int(k));
    }
    const int nv = c.motion.frames.empty() ? 0 : int(c.motion.frames[0].size());
    s.vertex_thickness.insert(s.vertex_thickness.end(), size_t(nv), c.thickness);
    s.vertex_friction.insert(s.vertex_friction.end(), size_t(nv), c.friction);
    off += nv;
    s.frames = std::max(s.frames, int(c.motion.frames.size()));
  }
  s.first_vertex.push_back(off);
  return s;
}

std::vector<Vec3> collider_positions(const std::vector<Collider>& colliders, const ColliderSet& set, int f) {
  std::vector<Vec3> x;
  x.reserve(size_t(set.vertices()));
  for (const Collider& c : colliders) {
    if (c.motion.frames.empty()) continue;
    const auto& src = c.motion.frames[size_t(std::min(f, int(c.motion.frames.size()) - 1))];
    x.insert(x.end(), src.begin(), src.end());
  }
  return x;
}

}  // namespace weft
