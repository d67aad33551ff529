// `weft run <scene>`: simulate a frame range, print per-frame statistics (or a progress bar on a terminal),
// optionally a hash of every frame; write the frames to an HDF5 cache and/or a Houdini .geo sequence as they
// are computed, and continue an interrupted cache with --resume.
#include "apps/run_scene.hpp"
#include "backends/body_cleaning.hpp"
#include "backends/simulation.hpp"
#include "core/hash.hpp"
#include "io/cache_file.hpp"
#include "io/geo_writeback.hpp"
#include "io/scene_file.hpp"
#include "io/scene_overrides.hpp"
#include "io/scene_source.hpp"
#include "scene/schedules.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace weft::cli {
namespace {

// "paper-1 (200 it, 20 passes, 1 substep), paper-2 (20, 2, 10), ...": the units on the first only.
std::string schedule_help() {
  std::string h;
  for (const Schedule& s : kSchedules) {
    const bool first = h.empty();
    h += (first ? "" : ", ") + std::string(s.name) + " (" + std::to_string(s.iterations) + (first ? " it, " : ", ") +
         std::to_string(s.collision_passes) + (first ? " passes, " : ", ") + std::to_string(s.substeps) +
         (first ? " substep)" : ")");
  }
  return h;
}

void apply_frames(const std::string& range, SolverSettings& st) {
  if (range.empty()) return;
  int a = 0, b = 0;
  if (!io::parse_frame_range(range, a, b))
    throw Error("--frames wants A-B with A <= B, got '" + range + "'", 2);
  st.frame_start = a;  // the scene's initial state is frame A
  st.frame_end = b;
}

// The command that continues this run from its cache.
std::string resume_command(const RunOptions& o) {
  std::string c = "weft run " + o.scene;
  const auto opt = [&](const char* name, const std::string& value) {
    if (!value.empty()) c += std::string(" ") + name + " " + value;
  };
  const auto num = [&](const char* name, int value, int unset) { if (value != unset) opt(name, std::to_string(value)); };
  num("--res", o.res, 0);
  opt("--frames", o.frames);
  opt("--schedule", o.schedule);
  num("--substeps", o.substeps, -1);
  num("--iterations", o.iterations, -1);
  num("--collision-passes", o.collision_passes, -1);
  num("--smoothing", o.smoothing, -1);
  opt("--geo-sequence", o.geo_dir);
  opt("--like", o.like);
  opt("--geo-format", o.geo_format);
  if (o.hash) c += " --hash";
  if (o.clean) c += " --clean";
  if (o.no_impact_zones) c += " --no-impact-zones";
  if (o.no_failsafe) c += " --no-failsafe";
  opt("--self-collision", o.self_collision);
  opt("--contact-model", o.contact_model);
  opt("--pair-refresh", o.pair_refresh);
  opt("--contact-solver", o.contact_solver);
  opt("--ccd-span", o.ccd_span);
  opt("--tethers", o.tethers);
  for (const std::string& kv : o.set) opt("--set", kv);
  return c + " -o " + o.output + " --resume";
}

// SIGINT / SIGTERM during the frame loop ask the run to stop once the frame in progress is written; a
// second signal acts as usual.
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void request_stop(int sig) { stop_signal = sig; }

class StopOnSignal {
 public:
  StopOnSignal() {
    struct sigaction sa {};
    sa.sa_handler = request_stop;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  int signal() const { return stop_signal; }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// A progress bar with the time left on a terminal; one line per frame otherwise (logs, pipes).
class Progress {
 public:
  Progress(bool quiet, int first, int last)
      : quiet_(quiet), tty_(::isatty(STDOUT_FILENO)), first_(first), last_(last), start_(Clock::now()) {}

  void frame(const FrameStats& fs) {
    ++done_;
    if (quiet_) return;
    if (!tty_) {
      std::printf("frame %d  ke %.3e J  rms speed %.3e m/s  max strain %.3e  contacts %ld  ", fs.frame,
                  fs.kinetic_energy, fs.rms_speed, fs.max_strain, fs.collision.contacts);
      if (fs.collision.queries > 0)  // proximity contacts
        std::printf("passes %ld (%ld early, %ld full queries, %ld still)  cut back %ld", fs.schedule.collision_passes,
                    fs.collision.early_passes, fs.collision.queries, fs.collision.still_passes, fs.collision.points_cut_back);
      else
        std::printf("moved back %ld (%ld pinned, %ld fail-safe rounds)", fs.collision.failsafe_points, fs.collision.failsafe_pinned,
                    fs.collision.failsafe_rounds);
      std::printf("  pin lag %.2e m  %.2f ms\n", fs.max_pin_lag, 1e3 * fs.seconds);
      std::fflush(stdout);  // a log being followed shows each frame as it is done
      return;
    }
    const int total = last_ - first_, width = 30;
    const double per_frame = std::chrono::duration<double>(Clock::now() - start_).count() / done_;
    const long eta = long(per_frame * (last_ - fs.frame) + 0.5);
    const int filled = total > 0 ? int(double(width) * (fs.frame - first_) / total) : width;
    std::printf("\r[%s%s] frame %d/%d  %.2f s/frame  ETA %ld:%02ld ", std::string(filled, '#').c_str(),
                std::string(width - filled, '.').c_str(), fs.frame, last_, per_frame, eta / 60, eta % 60);
    std::fflush(stdout);
  }
  void finish() const {
    if (!quiet_ && tty_ && done_ > 0) std::printf("\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool quiet_, tty_;
  int first_, last_, done_ = 0;
  Clock::time_point start_;
};

}  // namespace

int run_scene(const GlobalOptions& g, const RunOptions& o) {
  if (std::find(o.set.begin(), o.set.end(), "help") != o.set.end()) {
    std::printf("settings for --set NAME=VALUE (and batch wedges, docs/farm.md):\n");
    for (const std::string& line : io::override_help()) std::printf("  %s\n", line.c_str());
    return 0;
  }
  const Backend b = resolve_backend(g);
  if (o.resume && o.output.empty()) throw Error("--resume continues a cache: give it with -o CACHE.h5", 2);
  Runtime rt(g.threads);
  Scene scene = io::load_scene(o.scene, io::BuiltinOptions{o.res});
  SolverSettings& st = scene.settings;
  apply_frames(o.frames, st);
  if (!o.schedule.empty() && !apply_schedule(o.schedule, st))
    throw Error("unknown schedule '" + o.schedule + "' (" + schedule_names() + ")", 2);
  std::vector<io::SceneOverride> overrides;
  for (const std::string& kv : o.set) overrides.push_back(io::parse_override(kv));
  io::apply_overrides(scene, overrides);
  if (o.substeps >= 0) st.substeps = o.substeps;
  if (o.iterations >= 0) st.iterations = o.iterations;
  if (o.collision_passes >= 0) st.collision_passes = o.collision_passes;
  if (o.smoothing >= 0) st.smoothing_iterations = o.smoothing;
  if (o.no_impact_zones) st.collision.impact_zone_smoothing = false;
  if (o.no_failsafe) st.collision.collision_failsafe = false;
  apply_self_collision(o.self_collision, st.collision.self_collision);
  apply_contact_model(o.contact_model, st.collision.contact_model);
  apply_pair_refresh(o.pair_refresh, st.collision.pair_refresh);
  apply_contact_solver(o.contact_solver, st.collision.contact_solver);
  apply_ccd_span(o.ccd_span, st.collision.ccd_span);
  apply_tethers(o.tethers, st.tether_stretch);
  std::unique_ptr<io::GeoFrameWriter> geo;  // --geo-sequence; a --like file is checked before anything is written
  try {
    if (!o.geo_dir.empty())
      geo = std::make_unique<io::GeoFrameWriter>(o.geo_format, o.like, scene.points.size(), scene.triangles,
                                                 "the scene " + scene.name);
  } catch (const std::exception& e) {
    throw Error(e.what(), 2);
  }
  if (geo)
    for (const std::string& w : geo->warnings()) std::cerr << "weft: warning: " << w << "\n";
  warn_about_thickness(scene);
  if (!o.resume) warn_about_starting_state(b, scene);  // a resumed run starts from its cache's last frame
  if (o.clean) {  // the solvability check (docs/solvability.md) replaces the colliders by cleaned ones
    const BodyCleaning c = clean_body(b, scene);
    scene.colliders = c.colliders;
    if (!c.clean()) std::cerr << "weft: warning: the body is not fully cleaned (see weft check)\n";
    if (!o.quiet) std::printf("%s\n", cleaning_summary(c).c_str());
  }
  auto sim = make_simulation(b, scene);
  if (!o.quiet)
    std::printf("%s: %zu points, %zu triangles, %ld constraint rows in %d colours, %ld tethers, backend %s\n",
                scene.name.c_str(), scene.points.size(), scene.triangles.size(), sim->row_count(), sim->colour_count(),
                sim->tether_count(), backend_name(b));

  const io::CacheHeader header{scene.name, backend_name(b), scene.points.size(), scene.triangles, st,
                               io::overrides_text(overrides)};
  const std::string stem = io::frame_file_stem(scene.name);
  std::unique_ptr<io::CacheWriter> cache;
  const auto write_frame = [&](const FrameStats& fs) {
    if (!cache && !geo) return;
    const std::vector<Vec3> x = sim->positions(), v = sim->velocities();
    if (geo) geo->write(io::frame_file(o.geo_dir, stem, fs.frame, geo->extension()), x, v);
    if (cache) cache->append(fs, x, v);
  };
  const auto make_geo_dir = [&] {
    std::error_code ec;
    if (!o.geo_dir.empty()) std::filesystem::create_directories(o.geo_dir, ec);
    if (ec) throw Error("cannot create " + o.geo_dir + ": " + ec.message());
  };

  const StopOnSignal stop;  // from here on, SIGINT / SIGTERM leave complete files

  // Where the run starts: the scene's initial state, or the last frame of the cache it continues.
  uint64_t h = 0;
  if (o.resume && std::filesystem::exists(o.output)) {
    const io::CacheReader previous(o.output);
    const std::string why = io::resume_mismatch(previous, header, scene.points.position);
    if (!why.empty()) throw Error(o.output + ": cannot resume from this cache: " + why, 2);
    const int k = std::min(previous.frame_count(), st.frame_end - st.frame_start + 1);
    if (o.hash) h = io::cache_hash(previous, k);  // the hash covers every frame, computed now or before
    const int last = previous.frames()[k - 1];
    if (!o.quiet) std::printf("resuming from %s: frames %d-%d are done\n", o.output.c_str(), st.frame_start, last);
    sim->set_state(last, previous.positions(k - 1), previous.velocities(k - 1));
    if (last < st.frame_end) cache = std::make_unique<io::CacheWriter>(o.output, header, previous, k);
    make_geo_dir();
  } else {
    if (o.resume && !o.quiet) std::printf("no cache at %s yet: starting at frame %d\n", o.output.c_str(), st.frame_start);
    h = hash_combine(0, sim->hash_positions());
    // The cache stays under a temporary name until its first frame is in: if the .geo folder or first file
    // cannot be written, the run stops with neither output left behind.
    if (!o.output.empty()) cache = std::make_unique<io::CacheWriter>(o.output, header);
    make_geo_dir();
    write_frame(sim->measure());
  }

  Progress progress(o.quiet, sim->frame(), st.frame_end);
  double total = 0;
  int computed = 0;
  while (sim->frame() < st.frame_end) {
    const FrameStats fs = sim->step_frame();
    if (fs.non_finite) throw Error(scene.name + ": " + std::to_string(fs.non_finite) + " points became non-finite at frame " +
                                   std::to_string(fs.frame), 3);
    total += fs.seconds;
    ++computed;
    if (o.hash) h = hash_combine(h, sim->hash_positions());
    write_frame(fs);
    progress.frame(fs);
    if (stop.signal()) {
      if (cache) cache->close();
      progress.finish();
      std::fflush(stdout);
      std::cerr << "weft: stopped by " << (stop.signal() == SIGINT ? "SIGINT" : "SIGTERM") << " after frame " << fs.frame;
      if (cache)
        std::cerr << "; " << o.output << " holds frames " << st.frame_start << "-" << fs.frame
                  << ". Continue with:\n  " << resume_command(o) << "\n";
      else
        std::cerr << " (without -o CACHE.h5 there is nothing to resume from)\n";
      return 128 + stop.signal();
    }
  }
  if (cache) cache->close();
  progress.finish();
  if (!o.quiet && computed > 0) std::printf("%d frames, %.3f ms per frame\n", computed, 1e3 * total / computed);
  if (o.hash) std::printf("hash %s\n", hash_hex(h).c_str());
  return 0;
}

namespace {

void add_run(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "simulate a scene");
  cmd->add_option("scene", o->scene, "builtin:NAME, a .json scene or a .h5 scene file")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene (quads along a side)")->check(CLI::PositiveNumber);
  cmd->add_option("--frames", o->frames, "frame range A-B (A is the initial state)");
  cmd->add_option("--schedule", o->schedule, schedule_help());
  cmd->add_option("--substeps", o->substeps, "substeps per frame")->check(CLI::PositiveNumber);
  cmd->add_option("--iterations", o->iterations, "constraint iterations per substep")->check(CLI::NonNegativeNumber);
  cmd->add_option("--collision-passes", o->collision_passes, "collision passes per substep")->check(CLI::NonNegativeNumber);
  cmd->add_option("--smoothing", o->smoothing, "Jacobi smoothing iterations per substep")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-impact-zones", o->no_impact_zones, "switch off impact-zone smoothing of velocities (paper 2.3)");
  cmd->add_flag("--no-failsafe", o->no_failsafe, "switch off the crossing fail-safe (docs/collisions.md)");
  add_self_collision_option(cmd, o->self_collision);
  add_contact_model_option(cmd, o->contact_model);
  add_pair_refresh_option(cmd, o->pair_refresh);
  add_contact_solver_option(cmd, o->contact_solver);
  add_ccd_span_option(cmd, o->ccd_span);
  add_tethers_option(cmd, o->tethers);
  cmd->add_option("--set", o->set,
                  "NAME=VALUE: a setting by name, after --schedule and before the options above (repeatable; "
                  "'--set help' lists them)")
      ->allow_extra_args(false);
  cmd->add_flag("--hash", o->hash, "print 'hash <16 hex digits>' of every frame's positions as the last line");
  cmd->add_flag("--quiet", o->quiet, "no per-frame lines");
  cmd->add_option("-o,--output", o->output, "HDF5 cache written frame by frame (readable while the run goes on)");
  auto* geo_sequence =
      cmd->add_option("--geo-sequence", o->geo_dir, "also write each frame as DIR/<scene>.$F4.geo or .bgeo (P and v)");
  cmd->add_option("--like", o->like,
                  "the cloth's simulation geometry (the .geo/.bgeo given to import-vellum): each --geo-sequence frame "
                  "is a copy of it, quads, UVs, groups and attributes kept, with the frame's P and v")
      ->needs(geo_sequence);
  cmd->add_option("--geo-format", o->geo_format,
                  "geo or bgeo for --geo-sequence (default: the --like file's kind, else geo)")
      ->check(CLI::IsMember({"geo", "bgeo"}))
      ->needs(geo_sequence);
  cmd->add_flag("--clean", o->clean, "clean the body colliders first (the solvability check of weft check)");
  cmd->add_flag("--resume", o->resume,
                "continue the -o cache from its last frame (same scene and settings; --frames may extend it)");
  cmd->callback([&g, &action, o] { action = [&g, o] { return run_scene(g, *o); }; });
}

const Register reg("run", add_run);

}  // namespace
}  // namespace weft::cli
