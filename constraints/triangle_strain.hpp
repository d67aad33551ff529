// Strain of a cloth triangle from its deformation gradient, for every material alike: edges, triangle
// stretch or FEM. F = [p1 - p0, p2 - p0] Dm^-1 (constraints/triarap.hpp); its singular values s1 >= s2 are
// the principal stretches, and the strain is s1 - 1 (0 when the triangle is stretched in no direction): how
// far it is stretched along its most stretched direction, whatever the material. Compression is left out,
// as cloth buckles rather than compresses. A stretched edge's length / rest - 1 is at most this.
#pragma once
#include "constraints/triarap.hpp"
#include "scene/scene.hpp"

#include <array>
#include <vector>

namespace weft {

// A cloth triangle with its rest shape (Dm^-1, row-major).
struct TriangleRest {
  int p[3];
  real dm_inv[4];
};

KOKKOS_INLINE_FUNCTION real triangle_strain(Vec3 p0, Vec3 p1, Vec3 p2, const real (&dm_inv)[4]) {
  Vec3 f0, f1;
  triangle_deformation(p0, p1, p2, dm_inv, f0, f1);
  // Eigenvalues of F^T F = [[a, b], [b, c]]: the squared principal stretches.
  const real a = dot(f0, f0), b = dot(f0, f1), c = dot(f1, f1);
  const real mean = (a + c) / 2, half = (a - c) / 2;
  const real radius = sqrt_(half * half + b * b);
  return max_(sqrt_(mean + radius) - 1, real(0));
}

// Each cloth triangle's rest shape, from its material: the inverse rest shape of a triangle-stretch or FEM
// constraint on it; else the rest lengths of distance constraints along its three edges; else its shape at
// the initial positions. Degenerate rest shapes are left out.
std::vector<TriangleRest> triangle_rest_shapes(const Scene& s);

}  // namespace weft
