// Caches (HDF5, layout in docs/formats.md): a run's frames, written as they are computed and readable while
// the run goes on (single-writer / multiple-reader), positions and velocities stored exactly; and the names
// of per-frame files, and OBJ frames, that `weft export` makes of them.
#pragma once
#include "scene/scene.hpp"
#include "solver/frame_stats.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace weft::io {

inline constexpr const char* kCacheFormat = "weft-cache";
inline constexpr int kCacheFormatVersion = 1;

// What a cache says about its run, written when it is created.
struct CacheHeader {
  std::string scene;    // Scene::name
  std::string backend;  // that computed the frames (every backend gives the same bits)
  size_t points = 0;
  std::vector<std::array<int, 3>> triangles;
  SolverSettings settings;  // frame_start: the first frame (the initial state); frame_end: the last planned
  std::string overrides;  // the settings given by name (`weft run --set`), io::overrides_text; "" for none
};

class CacheReader;

// Writes a cache frame by frame. The file is made under a temporary name and takes its final name once its
// first frame is in, so a failure before then leaves nothing. append() returns once the frame is flushed;
// the frame count (the extent of /frames) grows only after the frame's data is on disk, so a cache cut short
// by a crash or a kill holds every frame completed before it.
class CacheWriter {
 public:
  CacheWriter(const std::string& path, const CacheHeader& header);
  // Starts with the first `frames` frames of `previous` (a cache of the same run; it may be the file at
  // `path`, which is replaced once they are copied): how `weft run --resume` continues a cache.
  CacheWriter(const std::string& path, const CacheHeader& header, const CacheReader& previous, int frames);
  ~CacheWriter();  // closes, without reporting failures: call close() to learn of them
  CacheWriter(const CacheWriter&) = delete;
  CacheWriter& operator=(const CacheWriter&) = delete;

  void append(const FrameStats& stats, const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities);
  int frame_count() const;
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Reads a cache, including one a run is still writing (the frames complete when it was opened). Malformed
// files throw FormatError naming the file and the dataset.
class CacheReader {
 public:
  explicit CacheReader(const std::string& path);
  ~CacheReader();
  CacheReader(const CacheReader&) = delete;
  CacheReader& operator=(const CacheReader&) = delete;

  const std::string& path() const;
  const CacheHeader& header() const;
  int frame_count() const;
  const std::vector<int>& frames() const;  // the frame number of each stored frame
  std::vector<Vec3> positions(int k) const;   // of stored frame k, 0 <= k < frame_count()
  std::vector<Vec3> velocities(int k) const;
  const std::vector<FrameStats>& stats() const;  // one per stored frame

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Why `cache` cannot be continued by a run with this header and initial state ("" when it can): it must come
// from the same points, triangles, settings (the last frame aside), named settings and initial state, or the
// result would differ from a straight run. What `weft run --resume` and `weft batch` check.
std::string resume_mismatch(const CacheReader& cache, const CacheHeader& run, const std::vector<Vec3>& initial);

// Simulation::hash_positions computed on the host: the same value for the same positions.
uint64_t positions_hash(const std::vector<Vec3>& positions);
// The hash `weft run --hash` prints for the frames of a cache: frame hashes combined in order, from 0. Of
// the first `frames` stored frames; -1: all.
uint64_t cache_hash(const CacheReader& cache, int frames = -1);

// Per-frame files: `<dir>/<stem>.<frame as $F4>.<ext>`, where the stem is the scene name without a
// builtin: prefix, folders or extension ("builtin:hanging-sheet" -> "hanging-sheet").
std::string frame_file_stem(const std::string& scene_name);
std::string frame_file(const std::string& dir, const std::string& stem, int frame, const std::string& ext);
// One cloth frame as an OBJ with exact positions, written atomically. (Houdini frames: io/geo_writeback.hpp.)
void write_frame_obj(const std::string& path, const std::vector<std::array<int, 3>>& triangles,
                     const std::vector<Vec3>& positions);

}  // namespace weft::io
