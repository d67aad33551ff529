// `weft demo [--out DIR] [--size N] [--frames A-B]`: runs the built-in demo (a capsule figure in a sewn three-layer
// skirt, io/demo_scene.cpp) at about N cloth triangles, writes DIR/demo.h5 and a PNG contact sheet of it.
#include "apps/run_scene.hpp"
#include "io/cache_file.hpp"
#include "io/contact_sheet.hpp"
#include "io/demo_scene.hpp"
#include "io/scene_source.hpp"

#include <cstdio>
#include <filesystem>

namespace weft::cli {
namespace {

struct DemoOptions {
  std::string out = "demo";
  long size = 20000;
  std::string frames;
};

int demo(const GlobalOptions& g, const DemoOptions& o) {
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw Error("cannot create " + o.out + ": " + ec.message());
  RunOptions run;
  run.scene = "builtin:demo";
  run.res = io::demo_res_for_triangles(o.size);
  run.frames = o.frames;
  run.output = (std::filesystem::path(o.out) / "demo.h5").string();
  std::filesystem::remove(run.output, ec);  // a fresh run, not a continuation of an older one
  std::printf("weft demo: about %ld cloth triangles (builtin:demo --res %d)\n", o.size, run.res);
  std::fflush(stdout);
  if (const int rc = run_scene(g, run)) return rc;

  const Scene scene = io::load_scene(run.scene, io::BuiltinOptions{run.res});
  const io::CacheReader cache(run.output);
  const std::string sheet = (std::filesystem::path(o.out) / "contact-sheet.png").string();
  io::write_contact_sheet(sheet, io::cache_sheet(cache, &scene, cache.frames().front(), cache.frames().back(), 8));
  std::printf("wrote %s (cache) and %s (contact sheet)\n", run.output.c_str(), sheet.c_str());
  return 0;
}

void add_demo(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<DemoOptions>();
  auto* cmd = app.add_subcommand("demo", "run the demo scene (a figure in a sewn three-layer skirt): cache and PNG contact sheet");
  cmd->add_option("--out", o->out, "folder for demo.h5 and contact-sheet.png (created if missing)")->capture_default_str();
  cmd->add_option("--size", o->size, "about this many cloth triangles")->capture_default_str()->check(CLI::Range(500L, 20000000L));
  cmd->add_option("--frames", o->frames, "frame range A-B (default: the scene's 1-49)");
  cmd->callback([&g, &action, o] { action = [&g, o] { return demo(g, *o); }; });
}

const Register reg("demo", add_demo);

}  // namespace
}  // namespace weft::cli
