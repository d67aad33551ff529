// `weft export cache.h5 --format geo|bgeo|obj DIR [--like cloth.bgeo] [--frames A-B]`: a cache's frames as one
// file per frame, DIR/<scene>.$F4.geo, .bgeo or .obj, for Houdini (File node) or any OBJ reader. With --like,
// each Houdini frame is a copy of the cloth's simulation geometry with the frame's P and v.
// `weft export cache.h5 --format usd OUT.usd|.usda|.usdc`: one time-sampled USD mesh (io/usd_export.hpp).
#include "apps/cli.hpp"
#include "io/cache_file.hpp"
#include "io/geo_writeback.hpp"
#include "io/scene_source.hpp"
#include "io/usd_export.hpp"

#include <cstdio>
#include <filesystem>

namespace weft::cli {
namespace {

struct ExportOptions {
  std::string cache, dir, format, frames, like;  // format "": the --like file's kind (geo or bgeo), else geo
};

// --format usd: frames a-b as one time-sampled USD mesh, the file o.dir (.usd, .usda or .usdc).
int export_usd(const ExportOptions& o, const io::CacheReader& cache, int a, int b) {
  if (!io::usd_export_built()) throw Error(io::kNoUsdExport, 2);
  if (!io::is_usd_path(o.dir)) throw Error("--format usd writes one file, OUT.usd, .usda or .usdc; got " + o.dir, 2);
  const std::filesystem::path parent = std::filesystem::path(o.dir).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) throw Error("cannot create " + parent.string() + ": " + ec.message());
  io::write_usd_cache(o.dir, cache, a, b);
  std::printf("wrote frames %d-%d to %s\n", a, b, o.dir.c_str());
  return 0;
}

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
  const auto& tris = cache->header().triangles;
  const bool houdini = o.format.empty() || o.format == "geo" || o.format == "bgeo";
  if (!houdini && !o.like.empty()) throw Error("--like goes with --format geo or bgeo", 2);
  if (o.format == "usd") return export_usd(o, *cache, a, b);
  std::unique_ptr<io::GeoFrameWriter> geo;  // checks the --like file before anything is written
  try {
    if (houdini)
      geo = std::make_unique<io::GeoFrameWriter>(o.format, o.like, cache->header().points, tris,
                                                 "the cache " + o.cache);
  } catch (const std::exception& e) {
    throw Error(e.what(), 2);
  }
  if (geo)
    for (const std::string& w : geo->warnings()) std::fprintf(stderr, "weft: warning: %s\n", w.c_str());
  const std::string ext = geo ? geo->extension() : o.format;
  std::error_code ec;
  std::filesystem::create_directories(o.dir, ec);
  if (ec) throw Error("cannot create " + o.dir + ": " + ec.message());
  const std::string stem = io::frame_file_stem(cache->header().scene);
  for (int frame = a; frame <= b; ++frame) {
    const int k = frame - first;  // stored frames are consecutive from the first
    const std::string path = io::frame_file(o.dir, stem, frame, ext);
    if (geo)
      geo->write(path, cache->positions(k), cache->velocities(k));
    else
      io::write_frame_obj(path, tris, cache->positions(k));
  }
  const std::string pattern = (std::filesystem::path(o.dir) / (stem + ".$F4." + ext)).string();
  std::printf("wrote frames %d-%d to %s\n", a, b, pattern.c_str());
  return 0;
}

void add_export(CLI::App& app, const GlobalOptions&, Action& run) {
  auto o = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand("export", "write a cache's frames as DIR/<scene>.$F4.geo, .bgeo or .obj files");
  cmd->add_option("cache", o->cache, "a cache (.h5) written by weft run -o")->required();
  cmd->add_option("dir", o->dir, "folder for the files (created if missing); with --format usd, the USD file")
      ->required();
  cmd->add_option("--format", o->format,
                  "geo or bgeo (Houdini: P and v; default: the --like file's kind, else geo) or obj (positions); "
                  "usd: one time-sampled mesh, the file DIR (.usd, .usda or .usdc)")
      ->check(CLI::IsMember({"geo", "bgeo", "obj", "usd"}));
  cmd->add_option("--like", o->like,
                  "the cloth's simulation geometry (the .geo/.bgeo given to import-vellum): each frame is a copy of "
                  "it, quads, UVs, groups and attributes kept, with the frame's P and v");
  cmd->add_option("--frames", o->frames, "frame range A-B (default: every stored frame)");
  cmd->callback([&run, o] { run = [o] { return export_frames(*o); }; });
}

const Register reg("export", add_export);

}  // namespace
}  // namespace weft::cli
