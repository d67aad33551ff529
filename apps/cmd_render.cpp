// `weft render cache.h5 -o sheet.png [--frames A-B] [--count N] [--scene SPEC [--res N]] [--view V]
// [--frame-all] [--zoom F]`: a PNG contact sheet of a cache's frames. With the scene it was computed from,
// cloth is coloured by layer and colliders are drawn; without, each connected cloth piece has its own colour.
// The cloth fills the cells unless --frame-all frames the colliders too.
#include "apps/cli.hpp"
#include "io/cache_file.hpp"
#include "io/contact_sheet.hpp"
#include "io/scene_source.hpp"

#include <cstdio>
#include <memory>

namespace weft::cli {
namespace {

struct RenderOptions {
  std::string cache, output, frames, scene, view = "standard";
  int res = 0, count = 8, columns = 4, cell = 360;
  bool frame_all = false;
  double zoom = 1;
};

int render(const RenderOptions& o) {
  std::unique_ptr<io::CacheReader> cache;
  try {
    cache = std::make_unique<io::CacheReader>(o.cache);
  } catch (const std::exception& e) {
    throw Error(e.what(), 2);
  }
  if (cache->frame_count() == 0) throw Error(o.cache + ": the cache holds no frames", 2);
  int a = cache->frames().front(), b = cache->frames().back();
  if (!o.frames.empty()) {
    if (!io::parse_frame_range(o.frames, a, b))
      throw Error("--frames wants A-B with A <= B, got '" + o.frames + "'", 2);
  }
  io::SheetView view;
  if (!io::parse_sheet_angle(o.view, view.angle))
    throw Error("--view wants front, side, top, three-quarter or standard, got '" + o.view + "'", 2);
  view.frame_all = o.frame_all;
  view.zoom = o.zoom;
  std::unique_ptr<Scene> scene;
  if (!o.scene.empty()) scene = std::make_unique<Scene>(io::load_scene(o.scene, io::BuiltinOptions{o.res}));
  io::SheetContent content;
  try {
    content = io::cache_sheet(*cache, scene.get(), a, b, o.count);
  } catch (const std::runtime_error& e) {
    throw Error(e.what(), 2);
  }
  io::write_contact_sheet(o.output, content, o.columns, o.cell, view);
  std::printf("wrote %s: frames", o.output.c_str());
  for (const auto& f : content.frames) std::printf(" %d", f.frame);
  std::printf("\n");
  return 0;
}

void add_render(CLI::App& app, const GlobalOptions&, Action& run) {
  auto o = std::make_shared<RenderOptions>();
  auto* cmd = app.add_subcommand("render", "draw a PNG contact sheet of a cache's frames");
  cmd->add_option("cache", o->cache, "a cache (.h5) written by weft run -o")->required();
  cmd->add_option("-o,--output", o->output, "the PNG to write")->required();
  cmd->add_option("--frames", o->frames, "frame range A-B to pick from (default: every stored frame)");
  cmd->add_option("--count", o->count, "frames on the sheet, spread evenly over the range")->capture_default_str()->check(CLI::Range(1, 64));
  cmd->add_option("--columns", o->columns, "cells per row")->capture_default_str()->check(CLI::Range(1, 16));
  cmd->add_option("--cell", o->cell, "cell size in pixels")->capture_default_str()->check(CLI::Range(64, 2048));
  cmd->add_option("--scene", o->scene, "the scene the cache came from (builtin:NAME, .json, .h5): layer colours, colliders");
  cmd->add_option("--res", o->res, "resolution of a built-in --scene, as given to weft run")->check(CLI::PositiveNumber);
  cmd->add_option("--view", o->view, "where the camera looks from: front, side (from +x), top, three-quarter, or standard "
                 "(in front, a little from the side and above)")
      ->capture_default_str()
      ->check(CLI::IsMember({"standard", "front", "side", "top", "three-quarter"}));
  cmd->add_flag("--frame-all", o->frame_all, "frame the colliders too (default: the cloth of every frame fills the cell)");
  cmd->add_option("--zoom", o->zoom, "multiply the framing's scale (2: twice as large, cropped by the cell)")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 100.0));
  cmd->callback([&run, o] { run = [o] { return render(*o); }; });
}

const Register reg("render", add_render);

}  // namespace
}  // namespace weft::cli
