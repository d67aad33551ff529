// `weft run <scene>`: simulate a frame range, print per-frame statistics, optionally a hash of every frame.
#include "apps/cli.hpp"
#include "backends/simulation.hpp"
#include "core/hash.hpp"
#include "io/scene_source.hpp"

#include <cstdio>
#include <iostream>

namespace weft::cli {
namespace {

struct RunOptions {
  std::string scene;
  int res = 0;
  std::string frames;
  std::string schedule;
  int substeps = -1, iterations = -1, collision_passes = -1, smoothing = -1;
  bool hash = false, quiet = false;
};

// The paper's three schedules: (iterations, collision passes, substeps).
void apply_schedule(const std::string& name, SolverSettings& st) {
  if (name.empty()) return;
  if (name == "paper-1") { st.iterations = 200; st.collision_passes = 20; st.substeps = 1; }
  else if (name == "paper-2") { st.iterations = 20; st.collision_passes = 2; st.substeps = 10; }
  else if (name == "paper-3") { st.iterations = 10; st.collision_passes = 1; st.substeps = 20; }
  else throw Error("unknown schedule '" + name + "' (paper-1, paper-2, paper-3)", 2);
}

void apply_frames(const std::string& range, SolverSettings& st) {
  if (range.empty()) return;
  int a = 0, b = 0;
  char extra = 0;
  if (std::sscanf(range.c_str(), "%d-%d%c", &a, &b, &extra) != 2 || b < a)
    throw Error("--frames wants A-B with A <= B, got '" + range + "'", 2);
  st.frame_start = a;  // the scene's initial state is frame A
  st.frame_end = b;
}

int run(const GlobalOptions& g, const RunOptions& o) {
  const Backend b = resolve_backend(g);
  Runtime rt(g.threads);
  Scene scene = io::load_scene(o.scene, io::BuiltinOptions{o.res});
  SolverSettings& st = scene.settings;
  apply_frames(o.frames, st);
  apply_schedule(o.schedule, st);
  if (o.substeps >= 0) st.substeps = o.substeps;
  if (o.iterations >= 0) st.iterations = o.iterations;
  if (o.collision_passes >= 0) st.collision_passes = o.collision_passes;
  if (o.smoothing >= 0) st.smoothing_iterations = o.smoothing;
  auto sim = make_simulation(b, scene);
  if (!o.quiet)
    std::printf("%s: %zu points, %zu triangles, %ld constraint rows in %d colours, backend %s\n", scene.name.c_str(),
                scene.points.size(), scene.triangles.size(), sim->row_count(), sim->colour_count(), backend_name(b));
  uint64_t h = hash_combine(0, sim->hash_positions());
  double total = 0;
  while (sim->frame() < st.frame_end) {
    const FrameStats fs = sim->step_frame();
    total += fs.seconds;
    if (o.hash) h = hash_combine(h, sim->hash_positions());
    if (!o.quiet)
      std::printf("frame %d  ke %.3e J  rms speed %.3e m/s  max strain %.3e  %.2f ms\n", fs.frame, fs.kinetic_energy,
                  fs.rms_speed, fs.max_strain, 1e3 * fs.seconds);
    if (fs.non_finite) throw Error(scene.name + ": " + std::to_string(fs.non_finite) + " points became non-finite at frame " +
                                   std::to_string(fs.frame), 3);
  }
  const int nframes = st.frame_end - st.frame_start;
  if (!o.quiet && nframes > 0) std::printf("%d frames, %.3f ms per frame\n", nframes, 1e3 * total / nframes);
  if (o.hash) std::printf("hash %s\n", hash_hex(h).c_str());
  return 0;
}

void add_run(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "simulate a scene");
  cmd->add_option("scene", o->scene, "builtin:NAME")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene (quads along a side)")->check(CLI::PositiveNumber);
  cmd->add_option("--frames", o->frames, "frame range A-B (A is the initial state)");
  cmd->add_option("--schedule", o->schedule, "paper-1 (200 it, 20 passes, 1 substep), paper-2 (20, 2, 10), paper-3 (10, 1, 20)");
  cmd->add_option("--substeps", o->substeps, "substeps per frame")->check(CLI::PositiveNumber);
  cmd->add_option("--iterations", o->iterations, "constraint iterations per substep")->check(CLI::NonNegativeNumber);
  cmd->add_option("--collision-passes", o->collision_passes, "collision passes per substep")->check(CLI::NonNegativeNumber);
  cmd->add_option("--smoothing", o->smoothing, "Jacobi smoothing iterations per substep")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--hash", o->hash, "print 'hash <16 hex digits>' of every frame's positions as the last line");
  cmd->add_flag("--quiet", o->quiet, "no per-frame lines");
  cmd->callback([&g, &action, o] { action = [&g, o] { return run(g, *o); }; });
}

const Register reg("run", add_run);

}  // namespace
}  // namespace weft::cli
