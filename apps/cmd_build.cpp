// `weft build scene.json -o scene.h5`: a JSON scene description into a scene file.
#include "apps/cli.hpp"
#include "io/json_scene.hpp"
#include "io/scene_file.hpp"

#include <cstdio>
#include <memory>

namespace weft::cli {
namespace {

struct BuildOptions {
  std::string input, output;
};

int build(const BuildOptions& o) {
  const Scene s = io::read_json_scene(o.input);
  io::write_scene(s, o.output);
  const Constraints& c = s.constraints;
  std::printf("%s: %zu points, %zu triangles, %zu colliders, frames %d-%d\n", o.output.c_str(), s.points.size(),
              s.triangles.size(), s.colliders.size(), s.settings.frame_start, s.settings.frame_end);
  std::printf("constraints: distance %zu, bend %zu, triarap %zu, fem %zu, pin %zu, attach %zu, ptprim %zu\n",
              c.distance.size(), c.bend.size(), c.triarap.size(), c.fem.size(), c.pin.size(), c.attach.size(),
              c.ptprim.size());
  return 0;
}

void add_build(CLI::App& app, const GlobalOptions&, Action& action) {
  auto o = std::make_shared<BuildOptions>();
  auto* cmd = app.add_subcommand("build", "write a scene file from a JSON scene description (docs/scene-json.md)");
  cmd->add_option("scene", o->input, "JSON scene")->required();
  cmd->add_option("-o,--output", o->output, "scene file to write (.h5)")->required();
  cmd->callback([&action, o] { action = [o] { return build(*o); }; });
}

const Register reg("build", add_build);

}  // namespace
}  // namespace weft::cli
