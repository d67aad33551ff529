// Procedural meshes for built-in scenes and the demo.
#pragma once
#include "core/vec.hpp"

#include <array>
#include <vector>

namespace weft::io {

struct Mesh {
  std::vector<Vec3> x;
  std::vector<std::array<int, 3>> tris;
};

// A rectangle of nu x nv quads (two triangles each, alternating diagonals), origin + s*du + t*dv, s,t in [0,1].
Mesh grid(int nu, int nv, Vec3 origin, Vec3 du, Vec3 dv);
Mesh uv_sphere(Vec3 centre, real radius, int rings, int segments);
Mesh box(Vec3 lo, Vec3 hi);  // 12 outward-facing triangles
// An open tube around the y axis: rings x segments quads, radius r(t) for t = 0 (bottom) .. 1 (top).
Mesh tube(real y0, real y1, int rings, int segments, real r0, real r1);
// A closed capsule between a and b (hemispherical caps), outward facing.
Mesh capsule(Vec3 a, Vec3 b, real radius, int rings, int segments);

void append(Mesh& to, const Mesh& m);

}  // namespace weft::io
