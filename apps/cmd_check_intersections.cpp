// `weft check-intersections <scene> [--frame F]`: discrete triangle-triangle intersections of the cloth,
// after simulating a scene up to frame F (default: its initial state). Last line: `intersections <N>`.
#include "apps/cli.hpp"
#include "backends/simulation.hpp"
#include "io/scene_source.hpp"

#include <cstdio>

namespace weft::cli {
namespace {

struct Options {
  std::string scene;
  int res = 0;
  int frame = -1;
};

int check(const GlobalOptions& g, const Options& o) {
  const Backend b = resolve_backend(g);
  Runtime rt(g.threads);
  Scene scene = io::load_scene(o.scene, io::BuiltinOptions{o.res});
  if (o.frame >= 0) scene.settings.frame_end = std::max(scene.settings.frame_end, o.frame);
  auto sim = make_simulation(b, scene);
  const int target = o.frame >= 0 ? o.frame : sim->frame();
  if (target < sim->frame()) throw Error("--frame " + std::to_string(target) + " is before the scene's first frame " +
                                         std::to_string(sim->frame()), 2);
  while (sim->frame() < target) {
    const FrameStats fs = sim->step_frame();
    std::printf("frame %d  contacts %ld  intersections %ld\n", fs.frame, fs.contacts, sim->intersections());
  }
  std::printf("intersections %ld\n", sim->intersections());
  return 0;
}

void add_check(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("check-intersections", "count intersecting cloth triangle pairs at a frame");
  cmd->add_option("scene", o->scene, "builtin:NAME, scene.json or scene.h5")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene")->check(CLI::PositiveNumber);
  cmd->add_option("--frame", o->frame, "simulate up to this frame first (default: the initial state)");
  cmd->callback([&g, &action, o] { action = [&g, o] { return check(g, *o); }; });
}

const Register reg("check-intersections", add_check);

}  // namespace
}  // namespace weft::cli
