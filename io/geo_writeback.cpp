#include "io/geo_writeback.hpp"

#include "core/error.hpp"

#include <system_error>

namespace weft::io {

namespace {

std::string str(size_t n) { return std::to_string(n); }

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Attribute velocity_attribute(const std::vector<Vec3>& v) {
  std::vector<double> values;
  values.reserve(3 * v.size());
  for (const Vec3& x : v) values.insert(values.end(), {x.x, x.y, x.z});
  Attribute a = float_attribute(3, std::move(values));
  a.qualifier = "vector";
  return a;
}

// P and v of `g` from the frame; the counts are checked by the callers.
void set_frame(Geometry& g, const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities) {
  g.points = positions;
  const auto it = g.point_attributes.find("v");
  if (it == g.point_attributes.end() || !is_float(it->second.storage) || it->second.size != 3) {
    g.point_attributes["v"] = velocity_attribute(velocities);
    return;
  }
  std::vector<double>& f = it->second.floats;
  f.resize(3 * velocities.size());
  for (size_t p = 0; p < velocities.size(); ++p) {
    f[3 * p] = velocities[p].x;
    f[3 * p + 1] = velocities[p].y;
    f[3 * p + 2] = velocities[p].z;
  }
}

void check_counts(size_t points, const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities) {
  if (positions.size() != points || velocities.size() != points)
    throw InputError("a frame of " + str(positions.size()) + " positions and " + str(velocities.size()) +
                     " velocities cannot be written as geometry of " + str(points) + " points");
}

void write_as(const Geometry& g, const std::string& path, GeoFormat format) {
  if (format == GeoFormat::Binary)
    write_bgeo(g, path);
  else
    write_geo(g, path);
}

}  // namespace

GeoFormat geo_format(const std::string& name, const std::string& like) {
  if (name == "geo") return GeoFormat::Text;
  if (name == "bgeo") return GeoFormat::Binary;
  if (!name.empty()) throw InputError("unknown Houdini geometry format '" + name + "' (geo, bgeo)");
  return ends_with(like, ".bgeo") ? GeoFormat::Binary : GeoFormat::Text;
}

const char* geo_extension(GeoFormat format) { return format == GeoFormat::Binary ? "bgeo" : "geo"; }

Geometry frame_like(const Geometry& like, const std::vector<Vec3>& positions, const std::vector<Vec3>& velocities) {
  check_counts(like.points.size(), positions, velocities);
  Geometry g = like;
  set_frame(g, positions, velocities);
  return g;
}

GeoFrameWriter::GeoFrameWriter(const std::string& format, const std::string& like, size_t points,
                               std::vector<std::array<int, 3>> triangles, const std::string& source)
    : format_(geo_format(format, like)), like_(!like.empty()), triangles_(std::move(triangles)) {
  if (!like_) return;
  try {
    frame_ = read_geo(like);
  } catch (const std::system_error& e) {
    throw InputError(e.what());
  }
  if (frame_.points.size() != points)
    throw InputError(like + " has " + str(frame_.points.size()) + " points but " + source + " has " + str(points) +
                     ": frames are written like the simulation geometry the scene was imported from");
  // What the file holds that the frames cannot: refused now rather than at the first frame.
  set_frame(frame_, frame_.points, std::vector<Vec3>(points));
  check_writable(frame_, like);
  for (const std::string& w : frame_.warnings) warnings_.push_back(like + ": " + w);
  const auto widened = [&](const AttributeMap& attrs, const char* cls) {
    for (const auto& [name, a] : attrs)
      if (a.storage == Storage::Float16)
        warnings_.push_back(like + ": " + cls + " attribute '" + name + "': fpreal16, written as fpreal32");
  };
  widened(frame_.point_attributes, "point");
  widened(frame_.vertex_attributes, "vertex");
  widened(frame_.primitive_attributes, "primitive");
  widened(frame_.detail_attributes, "detail");
}

void GeoFrameWriter::write(const std::string& path, const std::vector<Vec3>& positions,
                           const std::vector<Vec3>& velocities) {
  if (!like_) {
    check_counts(positions.size(), positions, velocities);
    Geometry g = from_trimesh(TriMesh{positions, triangles_});
    g.point_attributes["v"] = velocity_attribute(velocities);
    write_as(g, path, format_);
    return;
  }
  check_counts(frame_.points.size(), positions, velocities);
  set_frame(frame_, positions, velocities);
  write_as(frame_, path, format_);
}

}  // namespace weft::io
