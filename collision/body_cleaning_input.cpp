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
  int off = 0;
  for (const Collider& c : colliders) {
    const bool closed = is_closed_surface(c.triangles);
    b.first_vertex.push_back(off);
    for (const auto& t : c.triangles) {
      b.tris.push_back({t[0] + off, t[1] + off, t[2] + off});
      b.closed.push_back(closed ? 1 : 0);
      b.triangle_thickness.push_back(c.thickness);
    }
    const int nv = int(c.motion.frames[0].size());
    b.vertex_thickness.insert(b.vertex_thickness.end(), nv, c.thickness);
    off += nv;
    b.frames = std::max(b.frames, int(c.motion.frames.size()));
  }
  b.first_vertex.push_back(off);
  b.vt_offsets.assign(off + 1, 0);
  for (const auto& t : b.tris)
    for (int k = 0; k < 3; ++k) ++b.vt_offsets[t[k] + 1];
  for (int v = 0; v < off; ++v) b.vt_offsets[v + 1] += b.vt_offsets[v];
  b.vt_tris.resize(b.vt_offsets[off]);
  std::vector<int> fill(b.vt_offsets.begin(), b.vt_offsets.end() - 1);
  for (int t = 0; t < int(b.tris.size()); ++t)  // ascending triangle order around every vertex
    for (int k = 0; k < 3; ++k) b.vt_tris[fill[b.tris[t][k]]++] = t;
  return b;
}

std::vector<Vec3> body_positions(const std::vector<Collider>& colliders, const BodyMesh& body, int f) {
  std::vector<Vec3> x;
  x.reserve(body.vertices());
  for (const Collider& c : colliders) {
    const auto& frame = c.motion.frames[std::min<size_t>(f, c.motion.frames.size() - 1)];
    x.insert(x.end(), frame.begin(), frame.end());
  }
  return x;
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
