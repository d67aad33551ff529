// Scenes generated in code: `weft run builtin:<name> [--res N]`.
#pragma once
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace weft::io {

struct BuiltinOptions {
  int res = 0;  // resolution (quads along a side); 0: the scene's default
};

std::vector<std::string> builtin_scene_names();
// Throws InputError for an unknown name, listing the known ones.
Scene make_builtin_scene(const std::string& name, const BuiltinOptions& opt = {});

}  // namespace weft::io
