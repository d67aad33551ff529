// `weft import-vellum cloth.geo constraints.geo -o scene.h5`: a Houdini Vellum cloth asset into a scene file.
#include "apps/cli.hpp"
#include "io/scene_file.hpp"
#include "io/vellum_import.hpp"
#include "io/scene_source.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace weft::cli {
namespace {

struct ImportOptions {
  std::string sim, constraints, output, frames, pin_target;
  std::vector<std::string> colliders, collider_thickness, collider_friction;
  bool skip_unsupported = false;
  real fps = 0;
  int substeps = -1, iterations = -1, collision_passes = -1, smoothing = -1;
};

// --collider [NAME=]PATTERN
io::VellumCollider parse_collider(const std::string& arg) {
  io::VellumCollider c;
  const size_t eq = arg.find('=');
  if (eq != std::string::npos && arg.find('/') > eq) {
    c.name = arg.substr(0, eq);
    c.pattern = arg.substr(eq + 1);
  } else {
    c.pattern = arg;
  }
  if (c.pattern.empty()) throw Error("--collider wants [NAME=]FILE or a frame pattern such as 'body.$F4.geo'", 2);
  return c;
}

// --collider-thickness / --collider-friction [NAME=]VALUE: for the collider NAME, or (no NAME) for every one.
void apply_collider_values(const std::vector<std::string>& args, const char* option,
                           std::vector<io::VellumCollider>& colliders, real io::VellumCollider::*field) {
  for (int named = 0; named < 2; ++named)  // the values for all first, so a named one wins
    for (const std::string& arg : args) {
      const size_t eq = arg.find('=');
      if ((eq != std::string::npos) != bool(named)) continue;
      const std::string name = named ? arg.substr(0, eq) : "", text = named ? arg.substr(eq + 1) : arg;
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != 0 || !(v >= 0) || !std::isfinite(v))
        throw Error(std::string(option) + " wants [NAME=]VALUE with a number >= 0, got '" + arg + "'", 2);
      bool found = false;
      for (io::VellumCollider& c : colliders) {
        const std::string cname = c.name.empty() ? io::collider_name_from_pattern(c.pattern) : c.name;
        if (!named || cname == name) {
          c.*field = v;
          found = true;
        }
      }
      if (!found)
        throw Error(std::string(option) + " " + arg + ": " +
                        (named ? "no --collider is named '" + name + "'" : std::string("there is no --collider")), 2);
    }
}

std::array<int, 2> parse_frames(const std::string& range) {
  int a = 0, b = 0;
  if (!io::parse_frame_range(range, a, b))
    throw Error("--frames wants A-B with A <= B, got '" + range + "'", 2);
  return {a, b};
}

void print_counts(const char* title, const std::map<std::string, size_t>& counts) {
  if (counts.empty()) return;
  std::string line;
  for (const auto& [type, n] : counts) line += (line.empty() ? "" : ", ") + type + " " + std::to_string(n);
  std::printf("%s: %s\n", title, line.c_str());
}

int import(const ImportOptions& o) {
  io::VellumImportOptions opt;
  for (const std::string& c : o.colliders) opt.colliders.push_back(parse_collider(c));
  apply_collider_values(o.collider_thickness, "--collider-thickness", opt.colliders, &io::VellumCollider::thickness);
  apply_collider_values(o.collider_friction, "--collider-friction", opt.colliders, &io::VellumCollider::friction);
  if (!o.frames.empty()) opt.frames = parse_frames(o.frames);
  opt.skip_unsupported = o.skip_unsupported;
  opt.pin_target = o.pin_target;
  io::VellumImportReport report;
  Scene scene = io::import_vellum(o.sim, o.constraints, opt, &report);
  SolverSettings& st = scene.settings;
  if (o.fps > 0) st.fps = o.fps;
  if (o.substeps >= 0) st.substeps = o.substeps;
  if (o.iterations >= 0) st.iterations = o.iterations;
  if (o.collision_passes >= 0) st.collision_passes = o.collision_passes;
  if (o.smoothing >= 0) st.smoothing_iterations = o.smoothing;
  io::write_scene(scene, o.output);

  for (const std::string& note : report.notes) std::fprintf(stderr, "weft: note: %s\n", note.c_str());
  for (const auto& [what, n] : report.unsupported)
    std::fprintf(stderr, "weft: warning: left out, weft cannot simulate: %s (%zu)\n", what.c_str(), n);
  std::printf("%s: %zu points, %zu triangles, %zu colliders, frames %d-%d\n", o.output.c_str(), scene.points.size(),
              scene.triangles.size(), scene.colliders.size(), st.frame_start, st.frame_end);
  print_counts("constraints", report.imported);
  print_counts("skipped (stiffness 0)", report.skipped);
  print_counts("unsupported, left out", report.unsupported);
  return 0;
}

void add_import_vellum(CLI::App& app, const GlobalOptions&, Action& action) {
  auto o = std::make_shared<ImportOptions>();
  auto* cmd =
      app.add_subcommand("import-vellum", "convert a Houdini Vellum cloth asset (.geo/.bgeo) into a scene file");
  cmd->add_option("sim", o->sim, "simulation geometry (.geo or .bgeo)")->required();
  cmd->add_option("constraints", o->constraints, "constraint geometry (.geo or .bgeo)")->required();
  cmd->add_option("-o,--output", o->output, "scene file to write (.h5)")->required();
  cmd->add_option("--collider", o->colliders,
                  "[NAME=]FILE or frame pattern ('body.$F4.geo', .geo/.bgeo/.obj); repeatable. Attach constraints "
                  "find theirs by target_path")
      ->allow_extra_args(false);  // one value per --collider, so it never takes the positionals
  cmd->add_option("--collider-thickness", o->collider_thickness,
                  "[NAME=]METRES: contact thickness of the collider NAME, or of every collider (default 0); repeatable")
      ->allow_extra_args(false);
  cmd->add_option("--collider-friction", o->collider_friction,
                  "[NAME=]SCALE: friction of the collider NAME, or of every collider (default 0.5); repeatable")
      ->allow_extra_args(false);
  cmd->add_option("--pin-target", o->pin_target,
                  "FILE or frame pattern ('cloth_anim.$F4.bgeo'): the cloth animated, point for point; pintoanimation "
                  "points follow it exactly and pin constraints are pulled to it");
  cmd->add_option("--frames", o->frames, "frame range A-B (A is the initial state; collider frames are read over it)");
  cmd->add_flag("--skip-unsupported", o->skip_unsupported,
                "leave out (and list) constraint types weft cannot simulate");
  cmd->add_option("--fps", o->fps, "frames per second")->check(CLI::PositiveNumber);
  cmd->add_option("--substeps", o->substeps, "substeps per frame")->check(CLI::PositiveNumber);
  cmd->add_option("--iterations", o->iterations, "constraint iterations per substep")->check(CLI::NonNegativeNumber);
  cmd->add_option("--collision-passes", o->collision_passes, "collision passes per substep")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--smoothing", o->smoothing, "Jacobi smoothing iterations per substep")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([&action, o] { action = [o] { return import(*o); }; });
}

const Register reg("import-vellum", add_import_vellum);

}  // namespace
}  // namespace weft::cli
