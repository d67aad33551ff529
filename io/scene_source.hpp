// Where `weft run` and friends get a scene: builtin:NAME now; scene files are read here too.
#pragma once
#include "io/builtin_scenes.hpp"
#include "scene/scene.hpp"

#include <string>

namespace weft::io {

Scene load_scene(const std::string& spec, const BuiltinOptions& opt);

// "A-B" with A <= B (a frame range as every command takes it); false when `text` is not one.
bool parse_frame_range(const std::string& text, int& first, int& last);

}  // namespace weft::io
