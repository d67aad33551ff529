// A contact sheet: several frames of a simulation side by side in one PNG (Cairo), flat shaded, cloth
// coloured by layer and colliders in grey, each frame labelled. For looking at a run at a glance.
#pragma once
#include "core/scene.hpp"
#include "io/cache_file.hpp"

#include <array>
#include <string>
#include <vector>

namespace weft::io {

struct SheetFrame {
  int frame = 0;
  std::vector<Vec3> cloth;     // cloth point positions
  std::vector<Vec3> collider;  // collider vertex positions (all colliders, concatenated)
};

struct SheetContent {
  std::string title;
  std::vector<std::array<int, 3>> cloth_triangles, collider_triangles;
  std::vector<int> triangle_colour;  // per cloth triangle: a palette index (a layer or a piece)
  std::vector<SheetFrame> frames;
};

// Renders the frames in a grid of `columns` cells of cell_px x cell_px pixels and writes the PNG under a
// temporary name renamed into place. Every cell uses the same camera (front, a little from the side and
// above, orthographic), framed to hold all frames. Throws std::runtime_error naming the file on failure.
void write_contact_sheet(const std::string& path, const SheetContent& content, int columns = 4, int cell_px = 360);

// The sheet of `count` frames of a cache spread evenly over its stored frames first..last (inclusive; frame
// numbers). With the scene the cache was computed from, cloth is coloured by layer and colliders are drawn;
// without it (scene == nullptr) cloth is coloured by connected piece.
SheetContent cache_sheet(const CacheReader& cache, const Scene* scene, int first, int last, int count);

}  // namespace weft::io
