// `weft check-intersections <scene> [--frame F]`: discrete triangle-triangle intersections of the cloth,
// after simulating a scene up to frame F (default: its initial state). Given an OBJ mesh instead, counts the
// intersections of that static mesh (another simulator's output, say) the same way. Last line:
// `intersections <N>`.
#include "apps/cli.hpp"
#include "backends/simulation.hpp"
#include "constraints/vellum_cloth.hpp"
#include "io/obj.hpp"
#include "io/scene_source.hpp"

#include <cstdio>

namespace weft::cli {
namespace {

struct Options {
  std::string scene;
  int res = 0;
  int frame = -1;
};

bool is_obj(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".obj") == 0;
}

// The mesh as a one-piece cloth scene that is never stepped: only its triangles and positions matter.
Scene static_mesh_scene(const std::string& path) {
  const io::TriMesh m = io::read_obj(path);
  if (m.triangles.empty()) throw InputError(path + ": no triangles");
  Scene s;
  s.name = path;
  add_cloth_piece(s, m.positions, m.triangles, ClothMaterial{});
  s.settings.self_collision = false;
  return s;
}

int check(const GlobalOptions& g, const Options& o) {
  const Backend b = resolve_backend(g);
  Runtime rt(g.threads);
  if (is_obj(o.scene)) {
    if (o.frame >= 0 || o.res > 0) throw Error("--frame and --res apply to scenes, not to an OBJ mesh", 2);
    std::printf("intersections %ld\n", make_simulation(b, static_mesh_scene(o.scene))->intersections());
    return 0;
  }
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
  auto* cmd = app.add_subcommand("check-intersections", "count intersecting cloth triangle pairs at a frame, or of an OBJ mesh");
  cmd->add_option("scene", o->scene, "builtin:NAME, scene.json, scene.h5, or mesh.obj (a static mesh)")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene")->check(CLI::PositiveNumber);
  cmd->add_option("--frame", o->frame, "simulate up to this frame first (default: the initial state)");
  cmd->callback([&g, &action, o] { action = [&g, o] { return check(g, *o); }; });
}

const Register reg("check-intersections", add_check);

}  // namespace
}  // namespace weft::cli
