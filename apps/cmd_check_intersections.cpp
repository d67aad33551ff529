// `weft check-intersections <scene> [--frame F]`: discrete triangle-triangle intersections of the cloth,
// after simulating a scene up to frame F (default: its initial state). Given a cache, counts them at a stored
// frame (default: the last; --all-frames: every one) without simulating; given an OBJ mesh (another
// simulator's output, say), in that static mesh. Last line: `intersections <N>`.
#include "apps/cli.hpp"
#include "backends/intersection_counter.hpp"
#include "backends/simulation.hpp"
#include "io/cache_file.hpp"
#include "io/hdf5_util.hpp"
#include "io/obj.hpp"
#include "io/scene_source.hpp"

#include <algorithm>
#include <cstdio>

namespace weft::cli {
namespace {

struct Options {
  std::string scene;
  int res = 0;
  int frame = -1;
  bool all_frames = false;
};

bool is_obj(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".obj") == 0;
}

bool is_cache(const std::string& path) {
  if (path.size() <= 3 || path.compare(path.size() - 3, 3, ".h5") != 0) return false;
  return io::h5::format_of(io::h5::File::open(path)) == io::kCacheFormat;
}

// The counter for a mesh's triangles, made once and used for each of its frames.
std::unique_ptr<IntersectionCounter> counter(Backend b, const std::string& name,
                                             const std::vector<std::array<int, 3>>& tris) {
  if (tris.empty()) throw InputError(name + ": no triangles");
  return make_intersection_counter(b, name, tris);
}

// Frames of a cache: the one asked for (default: the last), or all of them with a line each and, last, the
// largest count.
int check_cache(Backend b, const Options& o) {
  const io::CacheReader c(o.scene);
  if (o.res > 0) throw Error("--res applies to built-in scenes, not to a cache", 2);
  if (c.frame_count() == 0) throw InputError(o.scene + ": the cache holds no frames");
  const std::vector<int>& frames = c.frames();
  if (o.all_frames) {
    if (o.frame >= 0) throw Error("--frame and --all-frames exclude each other", 2);
    const auto count = counter(b, o.scene, c.header().triangles);
    long worst = 0;
    for (int k = 0; k < c.frame_count(); ++k) {
      const long n = count->count(c.positions(k));
      std::printf("frame %d  intersections %ld\n", frames[k], n);
      worst = std::max(worst, n);
    }
    std::printf("intersections %ld\n", worst);
    return 0;
  }
  int k = c.frame_count() - 1;
  if (o.frame >= 0) {
    k = int(std::find(frames.begin(), frames.end(), o.frame) - frames.begin());
    if (k == c.frame_count())
      throw Error(o.scene + ": frame " + std::to_string(o.frame) + " is not in the cache (frames " +
                      std::to_string(frames.front()) + "-" + std::to_string(frames.back()) + ")", 2);
  }
  std::printf("frame %d\nintersections %ld\n", frames[k], counter(b, o.scene, c.header().triangles)->count(c.positions(k)));
  return 0;
}

int check(const GlobalOptions& g, const Options& o) {
  const Backend b = resolve_backend(g);
  Runtime rt(g.threads);
  if (is_obj(o.scene)) {
    if (o.frame >= 0 || o.res > 0 || o.all_frames) throw Error("--frame, --all-frames and --res apply to scenes, not to an OBJ mesh", 2);
    const io::TriMesh m = io::read_obj(o.scene);
    std::printf("intersections %ld\n", counter(b, o.scene, m.triangles)->count(m.positions));
    return 0;
  }
  if (is_cache(o.scene)) return check_cache(b, o);
  if (o.all_frames) throw Error("--all-frames applies to a cache", 2);
  Scene scene = io::load_scene(o.scene, io::BuiltinOptions{o.res});
  if (o.frame >= 0) scene.settings.frame_end = std::max(scene.settings.frame_end, o.frame);
  auto sim = make_simulation(b, scene);
  const int target = o.frame >= 0 ? o.frame : sim->frame();
  if (target < sim->frame()) throw Error("--frame " + std::to_string(target) + " is before the scene's first frame " +
                                         std::to_string(sim->frame()), 2);
  while (sim->frame() < target) {
    const FrameStats fs = sim->step_frame();
    std::printf("frame %d  contacts %ld  intersections %ld\n", fs.frame, fs.collision.contacts, sim->intersections());
  }
  std::printf("intersections %ld\n", sim->intersections());
  return 0;
}

void add_check(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("check-intersections",
                                 "count intersecting cloth triangle pairs at a frame of a scene or a cache, or of an OBJ mesh");
  cmd->add_option("scene", o->scene, "builtin:NAME, scene.json, scene.h5, cache.h5 (weft run -o), or mesh.obj")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene")->check(CLI::PositiveNumber);
  cmd->add_option("--frame", o->frame,
                  "a scene: simulate up to this frame first (default: the initial state); a cache: this stored frame "
                  "(default: the last)");
  cmd->add_flag("--all-frames", o->all_frames, "a cache: every stored frame, one line each; the last line is the largest count");
  cmd->callback([&g, &action, o] { action = [&g, o] { return check(g, *o); }; });
}

const Register reg("check-intersections", add_check);

}  // namespace
}  // namespace weft::cli
