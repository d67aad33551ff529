// `weft export cache.h5 --format geo|obj DIR [--frames A-B]`: a cache's frames as one file per frame,
// DIR/<scene>.$F4.geo or .obj, for Houdini (File node) or any OBJ reader.
#include "apps/cli.hpp"
#include "io/cache_file.hpp"
#include "io/scene_source.hpp"

#include <cstdio>
#include <filesystem>

namespace weft::cli {
namespace {

struct ExportOptions {
  std::string cache, dir, format = "geo", frames;
};

int export_frames(const ExportOptions& o) {
  std::unique_ptr<io::CacheReader> cache;
  try {
    cache = std::make_unique<io::CacheReader>(o.cache);
  } catch (const std::exception& e) {
    throw Error(e.what(), 2);
  }
  if (cache->frame_count() == 0) throw Error(o.cache + ": the cache holds no frames", 2);
  const int first = cache->frames().front(), last = cache->frames().back();
  int a = first, b = last;
  if (!o.frames.empty()) {
    if (!io::parse_frame_range(o.frames, a, b))
      throw Error("--frames wants A-B with A <= B, got '" + o.frames + "'", 2);
    if (a < first || b > last)
      throw Error(o.cache + " holds frames " + std::to_string(first) + "-" + std::to_string(last) + ", not all of " +
                      o.frames, 2);
  }
  std::error_code ec;
  std::filesystem::create_directories(o.dir, ec);
  if (ec) throw Error("cannot create " + o.dir + ": " + ec.message());
  const std::string stem = io::frame_file_stem(cache->header().scene);
  const auto& tris = cache->header().triangles;
  for (int frame = a; frame <= b; ++frame) {
    const int k = frame - first;  // stored frames are consecutive from the first
    const std::string path = io::frame_file(o.dir, stem, frame, o.format);
    if (o.format == "geo")
      io::write_frame_geo(path, tris, cache->positions(k), cache->velocities(k));
    else
      io::write_frame_obj(path, tris, cache->positions(k));
  }
  const std::string pattern = (std::filesystem::path(o.dir) / (stem + ".$F4." + o.format)).string();
  std::printf("wrote frames %d-%d to %s\n", a, b, pattern.c_str());
  return 0;
}

void add_export(CLI::App& app, const GlobalOptions&, Action& run) {
  auto o = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand("export", "write a cache's frames as DIR/<scene>.$F4.geo or .obj files");
  cmd->add_option("cache", o->cache, "a cache (.h5) written by weft run -o")->required();
  cmd->add_option("dir", o->dir, "folder for the files (created if missing)")->required();
  cmd->add_option("--format", o->format, "geo (Houdini: P and v) or obj (positions)")->check(CLI::IsMember({"geo", "obj"}));
  cmd->add_option("--frames", o->frames, "frame range A-B (default: every stored frame)");
  cmd->callback([&run, o] { run = [o] { return export_frames(*o); }; });
}

const Register reg("export", add_export);

}  // namespace
}  // namespace weft::cli
