#include "collision/body_cleaning_input.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <map>

namespace weft {

bool is_closed_surface(const std::vector<std::array<int, 3>>& tris) {
  if (tris.empty()) return false;
  std::map<std::pair<int, int>, int> directed;  // each directed edge once, and its reverse once
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k)
      if (++directed[{t[k], t[(k + 1) % 3]}] > 1) return false;
  for (const auto& [e, n] : directed)
    if (!directed.count({e.second, e.first})) return false;
  return true;
}

real signed_volume6(const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris) {
  real v = 0;
  for (const auto& t : tris) v += dot(x[t[0]], cross(x[t[1]], x[t[2]]));
  return v;
}

void check_collider_orientation(const Scene& s) {
  for (const Collider& c : s.colliders)
    if (is_closed_surface(c.triangles) && signed_volume6(c.motion.frames[0], c.triangles) < 0)
      throw InputError(s.name + ": collider '" + c.name +
                       "' is a closed surface whose triangles face inward; reverse their winding");
}

BodyMesh make_body_mesh(const std::vector<Collider>& colliders) {
  BodyMesh b;
  static_cast<ColliderSet&>(b) = make_collider_set(colliders);
  std::vector<uint8_t> closed(colliders.size());
  for (size_t k = 0; k < colliders.size(); ++k) closed[k] = is_closed_surface(colliders[k].triangles) ? 1 : 0;
  for (int c : b.triangle_collider) {
    b.closed.push_back(closed[size_t(c)]);
    b.triangle_thickness.push_back(colliders[size_t(c)].thickness);
  }
  const int nv = b.vertices();
  b.vt_offsets.assign(size_t(nv) + 1, 0);
  for (const auto& t : b.triangles)
    for (int k = 0; k < 3; ++k) ++b.vt_offsets[t[k] + 1];
  for (int v = 0; v < nv; ++v) b.vt_offsets[v + 1] += b.vt_offsets[v];
  b.vt_tris.resize(b.vt_offsets[nv]);
  std::vector<int> fill(b.vt_offsets.begin(), b.vt_offsets.end() - 1);
  for (int t = 0; t < int(b.triangles.size()); ++t)  // ascending triangle order around every vertex
    for (int k = 0; k < 3; ++k) b.vt_tris[fill[b.triangles[t][k]]++] = t;
  return b;
}

ClothLayers make_cloth_layers(const Scene& s) {
  std::vector<int> layers(s.points.layer.begin(), s.points.layer.end());
  std::sort(layers.begin(), layers.end());
  layers.erase(std::unique(layers.begin(), layers.end()), layers.end());
  if (layers.size() > 64)
    throw InputError(s.name + ": the solvability check handles at most 64 cloth layers, the scene has " +
                     std::to_string(layers.size()));
  const auto bit = [&](int layer) { return int(std::lower_bound(layers.begin(), layers.end(), layer) - layers.begin()); };
  ClothLayers c;
  c.bit_thickness.assign(layers.size(), 0);
  for (size_t p = 0; p < s.points.size(); ++p) {
    real& th = c.bit_thickness[bit(s.points.layer[p])];
    th = std::max(th, s.points.thickness[p]);
  }
  for (const auto& t : s.triangles) c.triangle_bit.push_back(uint64_t(1) << bit(s.points.layer[t[0]]));
  return c;
}

}  // namespace weft
