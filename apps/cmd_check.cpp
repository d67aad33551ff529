// `weft check <scene> [-o cleaned.h5] [--report report.json]`: the animation solvability check (paper
// sec. 3, docs/solvability.md). Lists the cloth's triangle pairs that intersect where it starts, cleans the
// body colliders frame by frame, prints a line per frame that needed work, optionally writes the cleaned
// scene and a JSON report; the last line is the summary. Exit code 0 when the cloth starts untangled and
// every frame ends clean, 1 otherwise.
#include "apps/cli.hpp"
#include "backends/body_cleaning.hpp"
#include "io/cleaning_report.hpp"
#include "io/scene_file.hpp"
#include "io/scene_source.hpp"

#include <cstdio>

namespace weft::cli {
namespace {

struct Options {
  std::string scene, output, report;
  int res = 0;
  CleaningSettings settings;
};

int check(const GlobalOptions& g, const Options& o) {
  const Backend b = resolve_backend(g);
  Runtime rt(g.threads);
  Scene scene = io::load_scene(o.scene, io::BuiltinOptions{o.res});
  // The cloth where it starts: pairs already crossed stay crossed in the proximity contact model. Listed
  // whatever the scene's self collision, since a user switching it on needs them untangled.
  const std::vector<std::array<int, 2>> crossed = starting_intersections(b, scene);
  std::printf("%s: the cloth starts with %zu intersecting triangle pairs\n", scene.name.c_str(), crossed.size());
  constexpr size_t kListed = 20;
  for (size_t k = 0; k < crossed.size() && k < kListed; ++k)
    std::printf("  %s\n", describe_triangle_pair(scene, crossed[k]).c_str());
  if (crossed.size() > kListed) std::printf("  ... and %zu more (--report lists every one)\n", crossed.size() - kListed);
  const BodyCleaning c = clean_body(b, scene, o.settings);
  std::printf("%s: %zu body frames, %ld of %zu body points carry layers (largest reserved thickness %.3g m)\n",
              scene.name.c_str(), c.frames.size(), c.reserved_points, c.reserved.size(), c.max_reserved);
  for (const FrameCleaning& f : c.frames)
    if (f.points_moved > 0 || !f.clean())
      std::printf("frame %d  intersections %ld -> %ld  inside %ld -> %ld  gap violations %ld -> %ld  "
                  "moved %ld (largest %.3g m)  steps %d  iterations %d\n",
                  f.frame, f.intersections_before, f.intersections_left, f.interior_before, f.interior_left,
                  f.gap_violations_before, f.gap_violations_left, f.points_moved, f.max_displacement, f.self_steps,
                  f.gap_iterations);
  if (!o.output.empty()) {
    scene.colliders = c.colliders;
    io::write_scene(scene, o.output);
  }
  if (!o.report.empty()) io::write_cleaning_report(o.report, scene.name, o.settings, c, crossed);
  std::printf("%s\n", cleaning_summary(c, long(crossed.size())).c_str());
  return c.clean() && crossed.empty() ? 0 : 1;
}

void add_check(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<Options>();
  CleaningSettings& s = o->settings;
  auto* cmd = app.add_subcommand("check", "animation solvability check: clean the body colliders for the cloth layers");
  cmd->add_option("scene", o->scene, "builtin:NAME, scene.json or scene.h5")->required();
  cmd->add_option("--res", o->res, "resolution of a built-in scene")->check(CLI::PositiveNumber);
  cmd->add_option("-o,--output", o->output, "write the scene with the cleaned colliders (HDF5)");
  cmd->add_option("--report", o->report, "write a JSON report");
  cmd->add_option("--reach", s.reach, "m: cloth farther along a body normal does not lie on the body")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--step", s.step, "m: inward step of points inside the body")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--max-steps", s.max_steps, "self-intersection steps per frame")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-iterations", s.max_iterations, "gap-resolution iterations per frame")->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->callback([&g, &action, o] { action = [&g, o] { return check(g, *o); }; });
}

const Register reg("check", add_check);

}  // namespace
}  // namespace weft::cli
