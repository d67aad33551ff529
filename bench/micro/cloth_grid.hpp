// Cloth sheets for the benchmarks. io/procedural.hpp's grid() lives in weft_io (HDF5, Cairo); the
// benchmarks link only weft_solver, so they make the same alternating-diagonal grid here.
#pragma once
#include "constraints/vellum_cloth.hpp"
#include "core/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace weft::bench {

struct Sheet {
  std::vector<Vec3> x;
  std::vector<std::array<int, 3>> tris;
};

// The side, in quads, of a square grid of about `triangles` triangles.
inline int grid_res(long triangles) { return std::max(1, int(std::lround(std::sqrt(double(triangles) / 2)))); }

// res x res quads with edges of `edge` metres in the plane y = height, from corner (x0, z0); two triangles
// a quad with alternating diagonals, as io::grid.
inline Sheet sheet(int res, real edge, real height, real x0, real z0) {
  Sheet s;
  for (int j = 0; j <= res; ++j)
    for (int i = 0; i <= res; ++i) s.x.push_back({x0 + i * edge, height, z0 + j * edge});
  auto id = [res](int i, int j) { return j * (res + 1) + i; };
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) { s.tris.push_back({a, b, c}); s.tris.push_back({a, c, d}); }
      else { s.tris.push_back({a, b, d}); s.tris.push_back({b, c, d}); }
    }
  return s;
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
  s.settings.self_collision = false;
  return s;
}

}  // namespace weft::bench
