#include "io/cache_file.hpp"

#include "core/hash.hpp"
#include "io/hdf5_util.hpp"
#include "io/obj.hpp"
#include "io/scene_file.hpp"

#include <cctype>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace weft::io {
namespace {

using h5::Handle;
using Dims = std::vector<hsize_t>;

// The per-frame statistics table: one compound row per frame, fields named as in FrameStats and the structs
// of its stages (the collision stage's `queries` as `collision_queries`).
static_assert(sizeof(FrameStats) == 232, "FrameStats changed: update kStatsFields");
constexpr size_t in_collision(size_t offset) { return offsetof(FrameStats, collision) + offset; }
constexpr size_t in_schedule(size_t offset) { return offsetof(FrameStats, schedule) + offset; }
enum class Kind { I32, I64, F64 };
struct StatsField {
  const char* name;
  size_t offset;
  Kind kind;
};
const StatsField kStatsFields[] = {
    {"frame", offsetof(FrameStats, frame), Kind::I32},
    {"kinetic_energy", offsetof(FrameStats, kinetic_energy), Kind::F64},
    {"max_speed", offsetof(FrameStats, max_speed), Kind::F64},
    {"max_strain", offsetof(FrameStats, max_strain), Kind::F64},
    {"rms_speed", offsetof(FrameStats, rms_speed), Kind::F64},
    {"non_finite", offsetof(FrameStats, non_finite), Kind::I64},
    {"contacts", in_collision(offsetof(CollisionStats, contacts)), Kind::I64},
    {"impact_zone_points", in_collision(offsetof(CollisionStats, impact_zone_points)), Kind::I64},
    {"failsafe_points", in_collision(offsetof(CollisionStats, failsafe_points)), Kind::I64},
    {"seconds", offsetof(FrameStats, seconds), Kind::F64},
    {"seconds_constraints", in_schedule(offsetof(ScheduleStats, seconds_constraints)), Kind::F64},
    {"seconds_collision_passes", in_schedule(offsetof(ScheduleStats, seconds_collision_passes)), Kind::F64},
    {"seconds_contacts", in_schedule(offsetof(ScheduleStats, seconds_contacts)), Kind::F64},
    {"seconds_smoothing", in_schedule(offsetof(ScheduleStats, seconds_smoothing)), Kind::F64},
    {"seconds_failsafe", in_schedule(offsetof(ScheduleStats, seconds_failsafe)), Kind::F64},
    {"collision_passes", in_schedule(offsetof(ScheduleStats, collision_passes)), Kind::I64},
    {"failsafe_rounds", in_collision(offsetof(CollisionStats, failsafe_rounds)), Kind::I64},
    {"failsafe_pinned", in_collision(offsetof(CollisionStats, failsafe_pinned)), Kind::I64},
    {"max_pin_lag", offsetof(FrameStats, max_pin_lag), Kind::F64},
    {"collision_queries", in_collision(offsetof(CollisionStats, queries)), Kind::I64},
    {"early_passes", in_collision(offsetof(CollisionStats, early_passes)), Kind::I64},
    {"points_cut_back", in_collision(offsetof(CollisionStats, points_cut_back)), Kind::I64},
    {"seconds_lbvh_build", in_collision(offsetof(CollisionStats, seconds_lbvh_build)), Kind::F64},
    {"seconds_broad_phase", in_collision(offsetof(CollisionStats, seconds_broad_phase)), Kind::F64},
    {"seconds_narrow_phase", in_collision(offsetof(CollisionStats, seconds_narrow_phase)), Kind::F64},
    {"seconds_contact_colouring", in_collision(offsetof(CollisionStats, seconds_contact_colouring)), Kind::F64},
    {"p99_strain", offsetof(FrameStats, p99_strain), Kind::F64},
    {"max_edge_strain", offsetof(FrameStats, max_edge_strain), Kind::F64},
    {"still_passes", in_collision(offsetof(CollisionStats, still_passes)), Kind::I64},
};

// In memory: FrameStats. In the file: the same fields packed, little-endian.
Handle stats_type(bool in_file) {
  const auto file_size = [](Kind k) { return k == Kind::I32 ? size_t(4) : size_t(8); };
  size_t size = sizeof(FrameStats);
  if (in_file) {
    size = 0;
    for (const StatsField& f : kStatsFields) size += file_size(f.kind);
  }
  Handle t(h5::check(H5Tcreate(H5T_COMPOUND, size), "cannot make the HDF5 stats type"), H5Tclose);
  size_t at = 0;
  for (const StatsField& f : kStatsFields) {
    const hid_t type = f.kind == Kind::I32   ? (in_file ? H5T_STD_I32LE : H5T_NATIVE_INT)
                       : f.kind == Kind::I64 ? (in_file ? H5T_STD_I64LE : H5T_NATIVE_LONG)
                                             : (in_file ? H5T_IEEE_F64LE : H5T_NATIVE_DOUBLE);
    h5::check(H5Tinsert(t.get(), f.name, in_file ? at : f.offset, type), "cannot make the HDF5 stats type");
    at += file_size(f.kind);
  }
  return t;
}

const double* flat(const std::vector<Vec3>& v) { return v.empty() ? nullptr : &v[0].x; }

std::vector<Vec3> vec3s(const std::vector<double>& d) {
  std::vector<Vec3> v(d.size() / 3);
  std::memcpy(v.data(), d.data(), d.size() * sizeof(double));
  return v;
}

// A dataset that grows by rows along its first dimension: `row` is the shape of one row.
Handle extendible(const h5::File& f, const std::string& name, hid_t type, const Dims& row, hsize_t chunk_rows) {
  Dims dims{0}, max{H5S_UNLIMITED}, chunk{chunk_rows};
  dims.insert(dims.end(), row.begin(), row.end());
  max.insert(max.end(), row.begin(), row.end());
  chunk.insert(chunk.end(), row.begin(), row.end());
  const std::string what = f.path() + ": cannot create " + name;
  const Handle space(h5::check(H5Screate_simple(int(dims.size()), dims.data(), max.data()), what), H5Sclose);
  const Handle dcpl(h5::check(H5Pcreate(H5P_DATASET_CREATE), what), H5Pclose);
  h5::check(H5Pset_chunk(dcpl.get(), int(chunk.size()), chunk.data()), what);
  return Handle(h5::check(H5Dcreate2(f.id(), name.c_str(), type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), what),
                H5Dclose);
}

// Grows the dataset to k + 1 rows and writes row k.
void write_row(const Handle& d, hsize_t k, const void* data, hid_t memory_type, const std::string& what) {
  Handle space(h5::check(H5Dget_space(d.get()), what), H5Sclose);
  Dims dims(H5Sget_simple_extent_ndims(space.get()));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  dims[0] = k + 1;
  h5::check(H5Dset_extent(d.get(), dims.data()), what);
  space = Handle(h5::check(H5Dget_space(d.get()), what), H5Sclose);
  Dims start(dims.size(), 0), count = dims;
  start[0] = k;
  count[0] = 1;
  h5::check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), what);
  const Handle memory(h5::check(H5Screate_simple(int(count.size()), count.data(), nullptr), what), H5Sclose);
  h5::check(H5Dwrite(d.get(), memory_type, memory.get(), space.get(), H5P_DEFAULT, data), what);
}

}  // namespace

struct CacheWriter::Impl {
  h5::File file;
  Handle positions, velocities, frames, stats, stats_memory;
  size_t points = 0;
  int count = 0;
  int publish_at = 1;  // frames written before the file takes its name
  explicit Impl(h5::File f) : file(std::move(f)) {}
};

CacheWriter::CacheWriter(const std::string& path, const CacheHeader& header)
    : impl_(std::make_unique<Impl>(h5::File::create(path, true))) {
  Impl& m = *impl_;
  const h5::File& f = m.file;
  if (header.points == 0) throw std::invalid_argument(path + ": a cache needs at least one point");
  m.points = header.points;
  h5::write_attribute(f, "/", "weft_format", kCacheFormat);
  h5::write_attribute(f, "/", "format_version", kCacheFormatVersion);
  h5::write_attribute(f, "/", "scene", header.scene);
  h5::write_attribute(f, "/", "backend", header.backend);
  h5::write_attribute(f, "/", "point_count", int64_t(header.points));
  if (!header.overrides.empty()) h5::write_attribute(f, "/", "overrides", header.overrides);
  std::vector<int> tris;
  for (const auto& t : header.triangles) tris.insert(tris.end(), t.begin(), t.end());
  h5::write(f, "/triangles", tris.data(), {header.triangles.size(), 3});
  write_settings(f, "/settings", header.settings);
  // One chunk per frame of positions / velocities: a frame is written, and read, whole.
  m.positions = extendible(f, "/positions", H5T_IEEE_F64LE, {m.points, 3}, 1);
  m.velocities = extendible(f, "/velocities", H5T_IEEE_F64LE, {m.points, 3}, 1);
  m.stats = extendible(f, "/stats", stats_type(true).get(), {}, 64);
  m.frames = extendible(f, "/frames", H5T_STD_I32LE, {}, 64);
  m.stats_memory = stats_type(false);
  // Every object exists now; from here on readers may open the file while frames are appended.
  h5::check(H5Fstart_swmr_write(f.id()), path + ": cannot start SWMR writing");
}

CacheWriter::CacheWriter(const std::string& path, const CacheHeader& header, const CacheReader& previous, int frames)
    : CacheWriter(path, header) {
  if (frames < 1 || frames > previous.frame_count())
    throw std::invalid_argument(previous.path() + ": cannot copy " + std::to_string(frames) + " of its " +
                                std::to_string(previous.frame_count()) + " frames");
  impl_->publish_at = frames;
  for (int k = 0; k < frames; ++k) append(previous.stats()[k], previous.positions(k), previous.velocities(k));
}

CacheWriter::~CacheWriter() = default;

void CacheWriter::append(const FrameStats& stats, const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
  Impl& m = *impl_;
  const std::string what = m.file.path() + ": cannot write frame " + std::to_string(stats.frame);
  if (x.size() != m.points || v.size() != m.points)
    throw std::invalid_argument(what + ": " + std::to_string(x.size()) + " positions and " + std::to_string(v.size()) +
                                " velocities for " + std::to_string(m.points) + " points");
  const hsize_t k = hsize_t(m.count);
  write_row(m.positions, k, flat(x), H5T_NATIVE_DOUBLE, what);
  write_row(m.velocities, k, flat(v), H5T_NATIVE_DOUBLE, what);
  write_row(m.stats, k, &stats, m.stats_memory.get(), what);
  h5::check(H5Fflush(m.file.id(), H5F_SCOPE_LOCAL), what);
  // The frame counts only once its data is on disk: readers take the extent of /frames as the frame count.
  write_row(m.frames, k, &stats.frame, H5T_NATIVE_INT, what);
  h5::check(H5Fflush(m.file.id(), H5F_SCOPE_LOCAL), what);
  if (++m.count == m.publish_at) m.file.publish();
}

int CacheWriter::frame_count() const { return impl_->count; }

void CacheWriter::close() {
  Impl& m = *impl_;
  for (Handle* h : {&m.positions, &m.velocities, &m.frames, &m.stats, &m.stats_memory}) h->reset();
  m.file.close();
}

struct CacheReader::Impl {
  h5::File file;
  CacheHeader header;
  std::vector<int> frames;
  std::vector<FrameStats> stats;
  Handle positions, velocities;
  explicit Impl(h5::File f) : file(std::move(f)) {}

  // A [frames x points x 3] dataset holding at least every listed frame (a run may be writing the next).
  Handle per_frame(const std::string& name) const {
    Handle d = h5::open_dataset(file, name);
    const Dims dims = h5::shape(file, d);
    if (dims.size() != 3 || dims[1] != header.points || dims[2] != 3 || dims[0] < frames.size())
      h5::fail(file, name, "has shape " + h5::shape_string(dims) + ", expected [" + std::to_string(frames.size()) +
                               " x " + std::to_string(header.points) + " x 3]");
    return d;
  }
};

CacheReader::CacheReader(const std::string& path) : impl_(std::make_unique<Impl>(h5::File::open(path))) {
  Impl& m = *impl_;
  const h5::File& f = m.file;
  h5::check_format(f, kCacheFormat, kCacheFormatVersion);
  CacheHeader& h = m.header;
  h.scene = h5::read_string_attribute(f, "/", "scene");
  h.backend = h5::read_string_attribute(f, "/", "backend");
  if (h5::has_attribute(f, "/", "overrides")) h.overrides = h5::read_string_attribute(f, "/", "overrides");
  const int64_t points = h5::read_attribute<int64_t>(f, "/", "point_count");
  if (points < 1) h5::fail(f, "/", "point_count is " + std::to_string(points));
  h.points = size_t(points);
  const std::vector<int> tris = h5::read<int>(f, "/triangles", {-1, 3});
  for (size_t t = 0; t < tris.size() / 3; ++t) {
    h.triangles.push_back({tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]});
    for (int c : h.triangles.back())
      if (c < 0 || size_t(c) >= h.points)
        h5::fail(f, "/triangles", "triangle " + std::to_string(t) + " refers to point " + std::to_string(c) +
                                      ", out of range [0, " + std::to_string(h.points) + ")");
  }
  h.settings = read_settings(f, "/settings");
  m.frames = h5::read<int>(f, "/frames", {-1});
  for (size_t k = 0; k < m.frames.size(); ++k)
    if (m.frames[k] != h.settings.frame_start + int(k))
      h5::fail(f, "/frames", "stored frame " + std::to_string(k) + " is frame " + std::to_string(m.frames[k]) +
                                 ", expected " + std::to_string(h.settings.frame_start + int(k)));
  m.positions = m.per_frame("/positions");
  m.velocities = m.per_frame("/velocities");
  const Handle stats = h5::open_dataset(f, "/stats");
  const Dims dims = h5::shape(f, stats);
  if (dims.size() != 1 || dims[0] < m.frames.size())
    h5::fail(f, "/stats", "has shape " + h5::shape_string(dims) + ", expected [" + std::to_string(m.frames.size()) + "]");
  m.stats.resize(dims[0]);
  if (dims[0] > 0 && H5Dread(stats.get(), stats_type(false).get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, m.stats.data()) < 0)
    h5::fail(f, "/stats", "cannot be read (" + h5::last_error() + ")");
  m.stats.resize(m.frames.size());
}

CacheReader::~CacheReader() = default;

const std::string& CacheReader::path() const { return impl_->file.path(); }
const CacheHeader& CacheReader::header() const { return impl_->header; }
int CacheReader::frame_count() const { return int(impl_->frames.size()); }
const std::vector<int>& CacheReader::frames() const { return impl_->frames; }
const std::vector<FrameStats>& CacheReader::stats() const { return impl_->stats; }

std::vector<Vec3> CacheReader::positions(int k) const {
  if (k < 0 || k >= frame_count()) throw std::out_of_range(path() + ": no stored frame " + std::to_string(k));
  return vec3s(h5::read_rows<double>(impl_->file, impl_->positions, hsize_t(k), 1));
}

std::vector<Vec3> CacheReader::velocities(int k) const {
  if (k < 0 || k >= frame_count()) throw std::out_of_range(path() + ": no stored frame " + std::to_string(k));
  return vec3s(h5::read_rows<double>(impl_->file, impl_->velocities, hsize_t(k), 1));
}

// Why the cache cannot be continued by this run ("" when it can): it must come from the same points,
// triangles, settings (the last frame aside) and initial state, or the result would differ from a straight run.
std::string resume_mismatch(const CacheReader& c, const CacheHeader& run, const std::vector<Vec3>& initial) {
  const io::CacheHeader& h = c.header();
  if (c.frame_count() == 0) return "it holds no frames";
  if (h.points != run.points)
    return "it has " + std::to_string(h.points) + " points, the scene " + std::to_string(run.points);
  if (h.triangles != run.triangles) return "its triangles differ from the scene's";
  if (h.overrides != run.overrides)
    return "it was computed with --set '" + h.overrides + "', this run with '" + run.overrides + "'";
  for (const std::string& field : differing_settings(h.settings, run.settings))
    if (field != "frame_end" && field != "profile") return "it was computed with another " + field + " setting";
  const std::vector<Vec3> first = c.positions(0);
  if (std::memcmp(first.data(), initial.data(), initial.size() * sizeof(Vec3)) != 0)
    return "its first frame is not the scene's initial state";
  return "";
}

uint64_t positions_hash(const std::vector<Vec3>& x) {
  // hash_view's arithmetic on the positions' bytes as 32-bit words, in one thread.
  const size_t words = x.size() * sizeof(Vec3) / 4;
  const unsigned char* bytes = reinterpret_cast<const unsigned char*>(x.data());
  uint64_t sum = 0;
  for (size_t i = 0; i < words; ++i) {
    uint32_t w;
    std::memcpy(&w, bytes + 4 * i, 4);
    sum += splitmix64((uint64_t(i) << 32) ^ w);
  }
  return splitmix64(sum ^ splitmix64(uint64_t(words)));
}

uint64_t cache_hash(const CacheReader& cache, int frames) {
  const int n = frames < 0 ? cache.frame_count() : frames;
  uint64_t h = 0;
  for (int k = 0; k < n; ++k) h = hash_combine(h, positions_hash(cache.positions(k)));
  return h;
}

std::string frame_file_stem(const std::string& scene_name) {
  std::string s = scene_name.substr(scene_name.find_last_of(":/\\") + 1);
  const size_t dot = s.find_last_of('.');
  if (dot != std::string::npos && dot > 0) s.erase(dot);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s.empty() ? "cloth" : s;
}

std::string frame_file(const std::string& dir, const std::string& stem, int frame, const std::string& ext) {
  return (std::filesystem::path(dir) / expand_frame_pattern(stem + ".$F4." + ext, frame, frame)[0]).string();
}

void write_frame_obj(const std::string& path, const std::vector<std::array<int, 3>>& triangles,
                     const std::vector<Vec3>& positions) {
  write_obj(TriMesh{positions, triangles}, path);
}

}  // namespace weft::io
