// Simulated frames back into Houdini: each frame as a copy of the cloth's own simulation geometry (the file
// given to `weft import-vellum`; its points are the scene's points, in order) with P and v replaced, or as
// the triangulated mesh with P and v; ASCII .geo or binary .bgeo. What `weft run --geo-sequence` and
// `weft export` write (docs/formats.md, "Frame files").
#pragma once
#include "io/houdini_geo.hpp"

#include <array>
#include <string>
#include <vector>

namespace weft::io {

enum class GeoFormat { Text, Binary };  // .geo, .bgeo

// "geo" or "bgeo"; "" chooses by `like`: Binary when its name ends in .bgeo, else (and without it) Text.
// Anything else throws InputError.
GeoFormat geo_format(const std::string& name, const std::string& like = "");
const char* geo_extension(GeoFormat format);  // "geo", "bgeo"

// `like` as a frame: P replaced by `positions` (stored as like's P is), the point attribute v set to
// `velocities` (kept as stored when it is a float triple, else replaced by a float32 vector), every other
// element, attribute and group as it is. The counts must equal like's point count.
Geometry frame_like(const Geometry& like, const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities);

// Writes the frames of one run or cache, each file atomically.
class GeoFrameWriter {
 public:
  // `format` as geo_format takes it. Without `like`: the triangulated mesh with P and v (float32), as
  // weft always wrote. With it: copies of that geometry. Throws InputError, before anything is written, when
  // the file cannot be read or written back, or its point count is not `points` (the message names the
  // file, both counts and `source`, e.g. "the cache c.h5").
  GeoFrameWriter(const std::string& format, const std::string& like, size_t points,
                 std::vector<std::array<int, 3>> triangles, const std::string& source);

  GeoFormat format() const { return format_; }
  const char* extension() const { return geo_extension(format_); }
  // What the frames do not keep of the --like file as it is (skipped attribute types, edge groups, the
  // order of ordered groups, fpreal16 widened to fpreal32), one line each naming the file.
  const std::vector<std::string>& warnings() const { return warnings_; }
  void write(const std::string& path, const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities);

 private:
  GeoFormat format_;
  bool like_ = false;
  Geometry frame_;  // the --like geometry, its P and v overwritten by each frame
  std::vector<std::array<int, 3>> triangles_;
  std::vector<std::string> warnings_;
};

}  // namespace weft::io
