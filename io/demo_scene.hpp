// The demo scene (`weft demo`, `weft run builtin:demo`): a figure built from capsules that twists at the
// waist and swings its legs and arms, wearing a dress of four nested layers hung from the chest.
#pragma once
#include "core/scene.hpp"

namespace weft::io {

inline constexpr int kDemoLayers = 4;

// res sets the cloth resolution: 4 res segments around each layer, quads a little taller than wide.
Scene demo_scene(int res);
long demo_cloth_triangles(int res);
// The res whose cloth triangle count is nearest to `triangles` (`weft demo --size N`).
int demo_res_for_triangles(long triangles);

}  // namespace weft::io
