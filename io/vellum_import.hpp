// Houdini Vellum cloth assets into a Scene: the simulation geometry and the constraint geometry that the
// Vellum Constraints node writes (semantics: docs/vellum.md), and the animated colliders they attach to,
// read from per-frame geometry files.
#pragma once
#include "scene/scene.hpp"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace weft::io {

// A collider from one mesh file (.geo, .bgeo or .obj; static) or a frame pattern ("body.$F4.geo") read over
// frames first..last. Every frame must have the first frame's triangles; a missing or malformed frame, a
// topology change or a non-finite position throws InputError naming the file (and so the frame) and element.
Collider read_collider(const std::string& name, const std::string& pattern, int first, int last);

// The collider name read_collider gets when none is given: the file name without folder, frame variable
// and extension ("anim/body.$F4.geo" -> "body").
std::string collider_name_from_pattern(const std::string& pattern);

struct VellumCollider {
  std::string name;     // empty: collider_name_from_pattern(pattern); attach constraints' target_path names it
  std::string pattern;  // file or frame pattern
  real thickness = Collider{}.thickness;
  real friction = Collider{}.friction;
};

struct VellumImportOptions {
  std::vector<VellumCollider> colliders;
  std::optional<std::array<int, 2>> frames;  // first, last; else the detail attributes', else the defaults
  bool skip_unsupported = false;             // import without what weft cannot simulate, instead of refusing
  // The cloth's animated target (a .geo/.bgeo/.obj, or a $F sequence over the frames) with the simulation
  // geometry's points: pintoanimation points follow it exactly, pin constraints are pulled to it. "": they
  // hold their imported positions.
  std::string pin_target;
};

// What an import did, for the user: counts per Vellum constraint type, and everything that was not imported
// as it stands in the files.
struct VellumImportReport {
  std::map<std::string, size_t> imported;     // per constraint type, as named in the file
  std::map<std::string, size_t> skipped;      // per constraint type: stiffness 0 (Vellum does not solve them)
  std::map<std::string, size_t> unsupported;  // per constraint type or feature that weft cannot simulate
  std::vector<std::string> notes;             // decisions the user should know about (fixed attach goals, ...)
};

// Reads the pair into a validated Scene named after the simulation geometry. Bad input throws InputError
// naming the file and the element; unsupported constraint types or features throw InputError listing each
// with its count unless opt.skip_unsupported, when they are left out and listed in the report.
Scene import_vellum(const std::string& sim_geo, const std::string& constraint_geo, const VellumImportOptions& opt,
                    VellumImportReport* report = nullptr);

}  // namespace weft::io
