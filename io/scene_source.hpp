// Where `weft run` and friends get a scene: builtin:NAME now; scene files are read here too.
#pragma once
#include "core/scene.hpp"
#include "io/builtin_scenes.hpp"

#include <string>

namespace weft::io {

Scene load_scene(const std::string& spec, const BuiltinOptions& opt);

}  // namespace weft::io
