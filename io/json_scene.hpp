// Scenes authored by hand as JSON: solver settings, cloth pieces from OBJ files or generators with Vellum-style
// materials and pins, colliders from OBJ files, OBJ sequences or generators. Schema: docs/scene-json.md.
#pragma once
#include "scene/scene.hpp"

#include <string>

namespace weft::io {

// Reads and validates a JSON scene; file paths in it are relative to the JSON file's folder. Bad input throws
// InputError naming the file and the JSON path ("scene.json: cloth[1].material.density: expected a number").
Scene read_json_scene(const std::string& path);

}  // namespace weft::io
