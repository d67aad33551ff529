// A contact sheet: several frames of a simulation side by side in one PNG, cloth coloured by layer and
// colliders in grey, each frame labelled. For looking at a run at a glance. Each cell is rasterized here into
// a supersampled colour + depth buffer (a z-buffer, flat shading, two-sided lighting); Cairo composes the
// cells, labels and the PNG.
#pragma once
#include "io/cache_file.hpp"
#include "scene/scene.hpp"

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

// Where the orthographic camera looks from: standard is in front (+z), a little from the side (+x) and above;
// front, side (from +x) and top (from +y, front at the bottom) are straight on; three_quarter is 45 degrees
// round and 25 degrees above.
enum class SheetAngle { standard, front, side, top, three_quarter };

struct SheetView {
  SheetAngle angle = SheetAngle::standard;
  bool frame_all = false;  // frame the colliders too (default: every frame's cloth only, with a margin)
  double zoom = 1;         // multiplies the framing's scale: 2 draws everything twice as large, cropped by the cell
};

// "standard", "front", "side", "top" or "three-quarter" into `angle`; false (angle untouched) for another name.
bool parse_sheet_angle(const std::string& name, SheetAngle& angle);

// Renders the frames in a grid of `columns` cells of cell_px x cell_px pixels and writes the PNG under a
// temporary name renamed into place. Every cell uses the same camera and framing (by default the cloth of all
// frames fills the cell; colliders beyond it are cut off by the cell). Triangles are depth tested per sample
// (2x2 supersampled) with a small bias so that cloth resting on a collider wins over it; a cloth triangle seen
// from its back is lit with its normal flipped and drawn a little darker. The same input gives the same PNG
// bytes. Throws std::runtime_error naming the file on failure.
void write_contact_sheet(const std::string& path, const SheetContent& content, int columns = 4, int cell_px = 360,
                         const SheetView& view = {});

// The sheet of `count` frames of a cache spread evenly over its stored frames first..last (inclusive; frame
// numbers). With the scene the cache was computed from, cloth is coloured by layer and colliders are drawn;
// without it (scene == nullptr) cloth is coloured by connected piece.
SheetContent cache_sheet(const CacheReader& cache, const Scene* scene, int first, int last, int count);

}  // namespace weft::io
