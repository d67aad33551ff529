// The host-side inputs of the solvability check (collision/body_cleaning.hpp): the body as one mesh over
// all colliders, with the triangles around each vertex and which triangles bound a closed collider, and
// the cloth triangles' layers as bits with each layer's thickness.
#pragma once
#include "scene/collider_set.hpp"
#include "scene/scene.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace weft {

// The collider set with what the check needs beside it.
struct BodyMesh : ColliderSet {
  std::vector<int> vt_offsets, vt_tris;  // triangles around vertex v: vt_tris[vt_offsets[v] .. vt_offsets[v+1])
  std::vector<uint8_t> closed;           // per triangle: its collider is a closed surface (parity applies)
  std::vector<real> triangle_thickness;  // per triangle, its collider's thickness
};

BodyMesh make_body_mesh(const std::vector<Collider>& colliders);

// Six times the volume a closed surface encloses: negative when its triangles face inward.
real signed_volume6(const std::vector<Vec3>& x, const std::vector<std::array<int, 3>>& tris);

// Throws InputError naming the scene and the collider when a closed collider faces inward on its first
// frame (its inside would be taken for outside, and the solver's contacts push cloth into it).
void check_collider_orientation(const Scene& s);

// Every edge is shared by exactly two triangles that run it in opposite directions.
bool is_closed_surface(const std::vector<std::array<int, 3>>& tris);

// Cloth triangles by layer: bit k stands for the k-th smallest layer number (at most 64 layers).
struct ClothLayers {
  std::vector<uint64_t> triangle_bit;  // per cloth triangle, the layer of its first corner
  std::vector<real> bit_thickness;     // per bit: the largest point thickness of that layer
};

// Throws InputError naming the scene when the cloth has more than 64 layers.
ClothLayers make_cloth_layers(const Scene& s);

}  // namespace weft
