// Caches made up in the tests: a small header and frames of pseudo-random positions, velocities and
// statistics whose every bit a reader must give back (io_cache, cli_inspect and cli_import_export).
#pragma once
#include "io/cache_file.hpp"
#include "solver/frame_stats.hpp"
#include "tests/backend_fixture.hpp"

#include <cstring>
#include <vector>

namespace weft::test {

inline bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

inline std::vector<Vec3> random_vectors(TestRng& rng, size_t n) {
  std::vector<Vec3> v(n);
  for (Vec3& p : v) p = {rng.uniform(-1, 1), rng.uniform(-1e-300, 1e-300), rng.uniform(-1e300, 1e300)};
  return v;
}

inline io::CacheHeader small_header(size_t points) {
  io::CacheHeader h;
  h.scene = "builtin:test";
  h.backend = "serial";
  h.points = points;
  for (int i = 0; i + 2 < int(points); ++i) h.triangles.push_back({i, i + 1, i + 2});
  h.settings.frame_start = 7;
  h.settings.frame_end = 20;
  h.settings.fps = 30;
  h.settings.wind = {1.0 / 3, 0, 0};
  return h;
}

inline FrameStats stats_of(int frame) {
  FrameStats s;
  s.frame = frame;
  s.kinetic_energy = 1.0 / frame;
  s.max_speed = 2.0 / frame;
  s.max_strain = 3.0 / frame;
  s.rms_speed = 4.0 / frame;
  s.non_finite = frame + 1;
  s.collision.contacts = frame + 2;
  s.collision.impact_zone_points = frame + 3;
  s.seconds = 0.5 / frame;
  s.schedule.seconds_constraints = 0.25 / frame;
  s.schedule.seconds_collision_passes = 0.125 / frame;
  s.schedule.seconds_contacts = 0.0625 / frame;
  s.schedule.seconds_smoothing = 0.03125 / frame;
  s.schedule.collision_passes = frame + 4;
  return s;
}

// Frames appended to a cache: positions, velocities, statistics.
struct Frames {
  std::vector<std::vector<Vec3>> x, v;
  std::vector<FrameStats> stats;
  Frames(size_t points, int first, int count, uint64_t seed) {
    TestRng rng(seed);
    for (int k = 0; k < count; ++k) {
      x.push_back(random_vectors(rng, points));
      v.push_back(random_vectors(rng, points));
      stats.push_back(stats_of(first + k));
    }
  }
  void append_to(io::CacheWriter& w, int from, int to) const {
    for (int k = from; k < to; ++k) w.append(stats[k], x[k], v[k]);
  }
};

}  // namespace weft::test
