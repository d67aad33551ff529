// Edges, edge-adjacent triangle pairs (for bending) and boundaries of a welded triangle mesh.
#pragma once
#include "core/vec.hpp"

#include <array>
#include <vector>

namespace weft {

struct Topology {
  std::vector<std::array<int, 2>> edges;           // unique undirected edges (lo, hi), sorted
  std::vector<std::array<int, 2>> edge_triangles;  // the one or two triangles of each edge; -1 when absent
  // Per interior edge: o0, o1, e0, e1 with (o0, e0, e1) the first triangle's winding and o1 opposite.
  std::vector<std::array<int, 4>> bend_quads;
  std::vector<int> boundary_edges;                 // edges with one triangle
  std::vector<int> nonmanifold_edges;              // edges with more than two triangles
  int edge_index(int a, int b) const;              // the edge between points a and b (either order), or -1
};

// Per triangle and corner k, the triangle across its edge (corner k, corner k + 1): the lowest-numbered other
// triangle on that edge, or -1 on a boundary.
std::vector<std::array<int, 3>> triangle_neighbours(const std::vector<std::array<int, 3>>& triangles);

Topology build_topology(const std::vector<std::array<int, 3>>& triangles);

real triangle_area(Vec3 a, Vec3 b, Vec3 c);

// Point masses from an area density (kg/m^2): each triangle gives a third of its mass to each corner.
std::vector<real> lumped_masses(const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& triangles,
                                real density);

}  // namespace weft
