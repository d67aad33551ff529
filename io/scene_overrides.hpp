// Settings given by name on the command line (`weft run --set substeps=20`) and in batch wedges: the solver
// settings of a JSON scene's "settings", and cloth-wide values (thickness, stiffness scales). The list, with
// units and ranges, is in docs/farm.md and `weft run --set help`.
#pragma once
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace weft::io {

struct SceneOverride {
  std::string name, value;
};

// "name=value" -> {name, value}; throws InputError when there is no '=' or either side is empty.
SceneOverride parse_override(const std::string& text);

// Throws InputError("<name>: ...") when the name is unknown (listing the known ones) or the value is not of
// the setting's kind or range. Needs no scene: a batch checks its wedges before anything runs.
void check_override(const SceneOverride& o);

// Applies the overrides in order, then validates the scene. Throws InputError as check_override does.
void apply_overrides(Scene& s, const std::vector<SceneOverride>& overrides);

// "name=value;name=value" in the given order: what a cache records, so that --resume refuses other values.
std::string overrides_text(const std::vector<SceneOverride>& overrides);

// One line per known setting: "name  kind: what it sets".
std::vector<std::string> override_help();

}  // namespace weft::io
