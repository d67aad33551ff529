// The demo scene (`weft demo`, `weft run builtin:demo`): a figure built from capsules that turns at the
// waist and swings its legs and arms, wearing a flared skirt of three layers, each sewn from six gores
// (separate panels joined by stitches along their side seams) and pinned at the waist to the figure.
#pragma once
#include "scene/scene.hpp"

namespace weft::io {

inline constexpr int kDemoLayers = 3;
inline constexpr int kDemoGores = 6;  // panels per layer

// res sets the cloth resolution: each gore is res quads wide and about 1.5 res quads tall.
Scene demo_scene(int res);
long demo_cloth_triangles(int res);
// The res whose cloth triangle count is nearest to `triangles` (`weft demo --size N`).
int demo_res_for_triangles(long triangles);

}  // namespace weft::io
