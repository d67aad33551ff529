// `weft bench <scene>`: time per frame and per stage, for the current schedule or the paper's three
// (docs/performance.md). Reports numbers; asserts nothing.
#include "apps/cli.hpp"
#include "backends/simulation.hpp"
#include "io/scene_overrides.hpp"
#include "io/scene_source.hpp"
#include "io/trimesh.hpp"
#include "scene/schedules.hpp"

#include <algorithm>
#include <cstdio>

namespace weft::cli {
namespace {

struct Options {
  std::string scene, schedules = "current", json, self_collision, contact_model, pair_refresh, contact_solver, ccd_span,
      tethers;
  std::vector<std::string> set;  // settings by name (weft run --set)
  int res = 0, frames = 10, warmup = -1;  // -1: 16 with --schedules paper (the skirt is in contact by then), else 2
};

struct Result {
  std::string schedule;
  int iterations, passes, substeps;
  double ms_frame = 0;         // unfenced: what a run takes
  double ms_frame_fenced = 0;  // the same frames with every stage fenced, for the stage times below
  double ms_constraints = 0, ms_pass = 0, ms_contacts = 0, ms_smoothing = 0, ms_failsafe = 0;
  // The collision stage's parts: tree builds per frame; broad phase, narrow phase, colouring per pass.
  double ms_build = 0, ms_broad = 0, ms_narrow = 0, ms_colouring = 0;
  double contacts = 0, failsafe_rounds = 0;  // means per frame
  double passes_per_frame = 0;                          // collision passes, scheduled and early
  double queries = 0, early_passes = 0, still_passes = 0, cut_back = 0;  // proximity contacts: means per frame
  long intersections = 0;                    // the largest of the timed frames' (cloth triangle pairs)
  double pin_lag = 0;                        // m, the largest of the timed frames'
  double max_strain = 0, p99_strain = 0;     // the largest of the timed frames' (accuracy, not speed)
  long memory = -1;
  bool collision_stage = false;  // the scene has one (colliders or self collision)
};

// Each schedule runs twice over the same frames (the bits do not depend on profiling): once as a user's run
// does, for the time per frame and the memory, and once with every stage fenced, for the stage times. A
// fence after each stage keeps the host from queueing the next launches while the device works, so the
// fenced frame is slower than the real one. `schedule` names a row of scene/schedules.hpp, or is "scene": the
// scene's own settings.
Result bench_one(Backend b, Scene scene, const Options& o, const std::string& schedule) {
  SolverSettings& st = scene.settings;
  if (schedule != "scene") apply_schedule(schedule, st);
  st.frame_end = st.frame_start + o.warmup + o.frames;
  Result r{schedule, st.iterations, st.collision_passes, st.substeps};
  // A simulation of the scene past its warm-up frames, profiled or not.
  auto warmed_up = [&](bool profile) {
    st.profile = profile;
    auto sim = make_simulation(b, scene);
    for (int f = 0; f < o.warmup; ++f) sim->step_frame();
    return sim;
  };
  {
    const long mem0 = device_memory_used_bytes();
    auto sim = warmed_up(false);
    for (int f = 0; f < o.frames; ++f) r.ms_frame += 1e3 * sim->step_frame().seconds / o.frames;
    const long mem1 = device_memory_used_bytes();
    r.memory = mem0 >= 0 && mem1 >= 0 ? mem1 - mem0 : -1;
  }
  auto sim = warmed_up(true);
  long passes = 0;
  for (int f = 0; f < o.frames; ++f) {
    const FrameStats fs = sim->step_frame();
    r.ms_frame_fenced += 1e3 * fs.seconds / o.frames;
    r.ms_constraints += 1e3 * fs.schedule.seconds_constraints / o.frames;
    r.ms_contacts += 1e3 * fs.schedule.seconds_contacts / o.frames;
    r.ms_smoothing += 1e3 * fs.schedule.seconds_smoothing / o.frames;
    r.ms_failsafe += 1e3 * fs.schedule.seconds_failsafe / o.frames;
    r.ms_pass += 1e3 * fs.schedule.seconds_collision_passes;
    r.ms_build += 1e3 * fs.collision.seconds_lbvh_build / o.frames;
    r.ms_broad += 1e3 * fs.collision.seconds_broad_phase;
    r.ms_narrow += 1e3 * fs.collision.seconds_narrow_phase;
    r.ms_colouring += 1e3 * fs.collision.seconds_contact_colouring;
    passes += fs.schedule.collision_passes;
    r.contacts += double(fs.collision.contacts) / o.frames;
    r.failsafe_rounds += double(fs.collision.failsafe_rounds) / o.frames;
    r.queries += double(fs.collision.queries) / o.frames;
    r.early_passes += double(fs.collision.early_passes) / o.frames;
    r.still_passes += double(fs.collision.still_passes) / o.frames;
    r.cut_back += double(fs.collision.points_cut_back) / o.frames;
    r.max_strain = fs.max_strain > r.max_strain ? fs.max_strain : r.max_strain;
    r.p99_strain = std::max(r.p99_strain, double(fs.p99_strain));
    r.intersections = std::max(r.intersections, sim->intersections());
    r.pin_lag = std::max(r.pin_lag, double(fs.max_pin_lag));
  }
  r.collision_stage = passes > 0;
  r.passes_per_frame = double(passes) / o.frames;
  for (double* per_pass : {&r.ms_pass, &r.ms_broad, &r.ms_narrow, &r.ms_colouring})
    *per_pass = passes > 0 ? *per_pass / passes : 0;
  return r;
}

int bench(const GlobalOptions& g, const Options& o) {
  const Backend b = resolve_backend(g);
  Runtime rt(g.threads);
  Scene scene = io::load_scene(o.scene, io::BuiltinOptions{o.res});
  std::vector<io::SceneOverride> overrides;
  for (const std::string& kv : o.set) overrides.push_back(io::parse_override(kv));
  io::apply_overrides(scene, overrides);
  apply_self_collision(o.self_collision, scene.settings.collision.self_collision);
  apply_contact_model(o.contact_model, scene.settings.collision.contact_model);
  apply_pair_refresh(o.pair_refresh, scene.settings.collision.pair_refresh);
  apply_contact_solver(o.contact_solver, scene.settings.collision.contact_solver);
  apply_ccd_span(o.ccd_span, scene.settings.collision.ccd_span);
  apply_tethers(o.tethers, scene.settings.tether_stretch);
  warn_about_thickness(scene);
  warn_about_starting_state(b, scene);
  Options opt = o;
  if (opt.warmup < 0) opt.warmup = o.schedules == "paper" ? 16 : 2;
  std::vector<std::string> schedules;
  if (o.schedules == "paper") {
    for (const Schedule& s : kSchedules) schedules.push_back(s.name);
  } else if (o.schedules == "current") {
    schedules = {"scene"};
  } else {
    throw Error("--schedules is 'paper' or 'current'", 2);
  }
  const bool proximity = scene.settings.collision.contact_model == ContactModel::Proximity;
  const char* model = contact_model_name(scene.settings.collision.contact_model);
  const char* contacts =
      contact_solver_name(proximity ? ContactSolver::Jacobi : scene.settings.collision.contact_solver);
  const char* span = ccd_span_name(scene.settings.collision.ccd_span);
  const real tethers = scene.settings.tether_stretch;
  std::printf("%s: %zu points, %zu triangles, backend %s, contact model %s, %s contacts%s%s, tethers %g, stretch limits %d, coarse levels %d, %d frames "
              "after %d warm-up (ms/frame unfenced; the stages from a second, fenced run)\n",
              scene.name.c_str(), scene.points.size(), scene.triangles.size(), backend_name(b), model, contacts,
              proximity ? "" : ", CCD span ", proximity ? "" : span, tethers, scene.settings.stretch_limits, scene.settings.coarse_levels, opt.frames, opt.warmup);
  std::printf("%-9s %5s %5s %5s %10s %8s %12s %13s %10s %10s %10s %8s %10s %9s %10s %10s %6s %9s\n", "schedule", "iter",
              "pass", "sub", "ms/frame", "fenced", "constraints", "ms/col.pass", "contacts", "smoothing", "fail-safe",
              proximity ? "queries" : "rounds", "#contacts", "mem MiB", "max strain", "p99 strain", "isect", "pin lag m");
  std::vector<Result> results;
  for (const std::string& sc : schedules) {
    const Result r = bench_one(b, scene, opt, sc);
    std::printf("%-9s %5d %5d %5d %10.2f %8.2f %12.2f %13.3f %10.2f %10.2f %10.2f %8.1f %10.0f %9.1f %10.3f %10.4f %6ld %9.2e\n",
                r.schedule.c_str(), r.iterations, r.passes, r.substeps, r.ms_frame, r.ms_frame_fenced, r.ms_constraints,
                r.ms_pass, r.ms_contacts, r.ms_smoothing, r.ms_failsafe, proximity ? r.queries : r.failsafe_rounds,
                r.contacts, r.memory >= 0 ? r.memory / 1048576.0 : -1.0, r.max_strain, r.p99_strain, r.intersections, r.pin_lag);
    if (r.collision_stage) {
      std::printf("%-9s collision stage: tree builds %.2f ms/frame; per pass: broad phase %.3f ms, narrow phase %.3f ms, "
                  "contact colouring %.3f ms\n", "", r.ms_build, r.ms_broad, r.ms_narrow, r.ms_colouring);
      if (proximity)
        std::printf("%-9s proximity: %.1f passes per frame (%.1f early), %.1f of them full queries (the others kept "
                    "their pairs), %.1f still, %.0f points cut back per frame\n", "", r.passes_per_frame, r.early_passes,
                    r.queries, r.still_passes, r.cut_back);
    }
    results.push_back(r);
  }
  if (!o.json.empty()) io::write_file_atomically(o.json, [&](std::ostream& out) {
    out << "{\"scene\": \"" << scene.name << "\", \"triangles\": " << scene.triangles.size() << ", \"backend\": \""
        << backend_name(b) << "\", \"contact_model\": \"" << model << "\", \"contact_solver\": \"" << contacts << "\", \"ccd_span\": \"" << span
        << "\", \"tether_stretch\": " << tethers << ", \"stretch_limits\": " << scene.settings.stretch_limits
        << ", \"coarse_levels\": " << scene.settings.coarse_levels
        << ", \"results\": [";
    for (size_t i = 0; i < results.size(); ++i) {
      const Result& r = results[i];
      out << (i ? ", " : "") << "{\"schedule\": \"" << r.schedule << "\", \"iterations\": " << r.iterations
          << ", \"collision_passes\": " << r.passes << ", \"substeps\": " << r.substeps << ", \"ms_per_frame\": " << r.ms_frame
          << ", \"ms_per_frame_fenced\": " << r.ms_frame_fenced
          << ", \"ms_constraints\": " << r.ms_constraints << ", \"ms_per_collision_pass\": " << r.ms_pass
          << ", \"ms_contacts\": " << r.ms_contacts << ", \"ms_smoothing\": " << r.ms_smoothing
          << ", \"ms_failsafe\": " << r.ms_failsafe << ", \"failsafe_rounds\": " << r.failsafe_rounds
          << ", \"ms_lbvh_build\": " << r.ms_build << ", \"ms_broad_phase_per_pass\": " << r.ms_broad
          << ", \"ms_narrow_phase_per_pass\": " << r.ms_narrow << ", \"ms_colouring_per_pass\": " << r.ms_colouring
          << ", \"contacts\": " << r.contacts << ", \"max_strain\": " << r.max_strain
          << ", \"p99_strain\": " << r.p99_strain << ", \"intersections\": " << r.intersections
          << ", \"max_pin_lag\": " << r.pin_lag
          << ", \"passes_per_frame\": " << r.passes_per_frame
          << ", \"queries\": " << r.queries << ", \"early_passes\": " << r.early_passes
          << ", \"still_passes\": " << r.still_passes
          << ", \"points_cut_back\": " << r.cut_back
          << ", \"memory_bytes\": " << r.memory << "}";
    }
    out << "]}\n";
  });
  return 0;
}

void add_bench(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("bench", "time a scene per frame and per stage");
  cmd->add_option("scene", o->scene, "builtin:NAME, scene.json or scene.h5")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene")->check(CLI::PositiveNumber);
  cmd->add_option("--frames", o->frames, "frames timed (default 10)")->check(CLI::PositiveNumber);
  cmd->add_option("--warmup", o->warmup, "frames run before timing (default 16 with --schedules paper, else 2)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--schedules", o->schedules, "current (the scene's) or paper (the paper's three)");
  cmd->add_option("--json", o->json, "also write the results as JSON");
  add_self_collision_option(cmd, o->self_collision);
  add_contact_model_option(cmd, o->contact_model);
  add_pair_refresh_option(cmd, o->pair_refresh);
  add_contact_solver_option(cmd, o->contact_solver);
  add_ccd_span_option(cmd, o->ccd_span);
  add_tethers_option(cmd, o->tethers);
  cmd->add_option("--set", o->set,
                  "NAME=VALUE: a setting by name as weft run takes it, before the options above; --schedules paper "
                  "then sets iterations, passes and substeps (repeatable; 'weft run --set help' lists them)")
      ->allow_extra_args(false);
  cmd->callback([&g, &action, o] { action = [&g, o] { return bench(g, *o); }; });
}

const Register reg("bench", add_bench);

}  // namespace
}  // namespace weft::cli
