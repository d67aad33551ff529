// Cloth sheets for the benchmarks, from io::grid (io/procedural.cpp, which the benchmarks compile in: the
// rest of weft_io would bring HDF5 and Cairo).
#pragma once
#include "constraints/vellum_cloth.hpp"
#include "io/procedural.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>

namespace weft::bench {

using Sheet = io::Mesh;

// The side, in quads, of a square grid of about `triangles` triangles.
inline int grid_res(long triangles) { return std::max(1, int(std::lround(std::sqrt(double(triangles) / 2)))); }

// res x res quads with edges of `edge` metres in the plane y = height, from corner (x0, z0).
inline Sheet sheet(int res, real edge, real height, real x0, real z0) {
  return io::grid(res, res, {x0, height, z0}, {res * edge, 0, 0}, {0, 0, res * edge});
}

// io/builtin_scenes.cpp's hanging sheet with about `triangles` triangles: a 1 m square of default Vellum
// cloth (distance and bend rows), pinned at two corners, no collisions.
inline Scene hanging_sheet(long triangles) {
  const int res = grid_res(triangles);
  Scene s;
  s.name = "bench:hanging-sheet";
  const Sheet g = sheet(res, 1.0 / res, 1.0, -0.5, -0.5);
  add_cloth_piece(s, g.x, g.tris, ClothMaterial{});
  s.points.stopped[0] = 1;
  s.points.stopped[res] = 1;
  s.settings.collision.self_collision = false;
  return s;
}

}  // namespace weft::bench
