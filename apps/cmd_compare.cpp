// `weft compare a.h5 b.h5 [--ulp N]`: whether two caches hold the same frames, bit for bit or within N units
// in the last place; exit 0 when they do, 1 when they differ, 2 when a file cannot be read.
#include "apps/cli.hpp"
#include "io/cache_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace weft::cli {
namespace {

struct CompareOptions {
  std::string a, b;
  uint64_t ulp = 0;
};

uint64_t bits(double x) {
  uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

// Doubles apart along the number line (0 for +0 and -0); NaN is infinitely far from anything but itself.
uint64_t ulp_distance(double x, double y) {
  if (bits(x) == bits(y)) return 0;
  if (std::isnan(x) || std::isnan(y)) return UINT64_MAX;
  // Sign-magnitude bits to a monotonic integer scale.
  const auto ordered = [](double d) {
    const uint64_t u = bits(d);
    const int64_t magnitude = int64_t(u & ~(uint64_t(1) << 63));
    return u >> 63 ? -magnitude : magnitude;
  };
  const int64_t a = ordered(x), b = ordered(y);
  return a > b ? uint64_t(a) - uint64_t(b) : uint64_t(b) - uint64_t(a);
}

struct Difference {
  uint64_t ulps = 0;
  bool found = false;  // first value whose difference exceeds the tolerance
  long point = 0;
  int component = 0;
  double a = 0, b = 0;
};

// Compares one frame's values; returns the first one beyond the tolerance and tracks the largest distance.
Difference compare_values(const std::vector<Vec3>& a, const std::vector<Vec3>& b, uint64_t tolerance, uint64_t& largest) {
  Difference d;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = a[i][c], y = b[i][c];
      if (bits(x) == bits(y)) continue;
      const uint64_t u = ulp_distance(x, y);
      largest = std::max(largest, u);
      if (tolerance == 0 || u > tolerance) return {u, true, long(i), c, x, y};
    }
  return d;
}

std::string distance_string(uint64_t u) { return u == UINT64_MAX ? "NaN" : std::to_string(u) + " ULPs"; }

int compare(const CompareOptions& o) {
  const io::CacheReader a(o.a), b(o.b);
  const io::CacheHeader &ha = a.header(), &hb = b.header();
  if (ha.points != hb.points) {
    std::printf("different: %s has %zu points, %s has %zu\n", o.a.c_str(), ha.points, o.b.c_str(), hb.points);
    return 1;
  }
  if (ha.triangles != hb.triangles) {
    std::printf("different: the triangles differ\n");
    return 1;
  }
  if (a.frame_count() > 0 && b.frame_count() > 0 && a.frames()[0] != b.frames()[0]) {
    std::printf("different: %s starts at frame %d, %s at frame %d\n", o.a.c_str(), a.frames()[0], o.b.c_str(),
                b.frames()[0]);
    return 1;
  }
  const int common = std::min(a.frame_count(), b.frame_count());
  uint64_t largest = 0;
  for (int k = 0; k < common; ++k) {
    const struct { const char* name; std::vector<Vec3> a, b; } values[] = {
        {"position", a.positions(k), b.positions(k)}, {"velocity", a.velocities(k), b.velocities(k)}};
    for (const auto& v : values) {
      const Difference d = compare_values(v.a, v.b, o.ulp, largest);
      if (!d.found) continue;
      std::printf("different: frame %d point %ld %s.%c: %.17g (%s) vs %.17g (%s), %s apart\n", a.frames()[k], d.point,
                  v.name, "xyz"[d.component], d.a, o.a.c_str(), d.b, o.b.c_str(), distance_string(d.ulps).c_str());
      return 1;
    }
  }
  if (a.frame_count() != b.frame_count()) {
    std::printf("different: the first %d frames agree, but %s has %d frames and %s %d\n", common, o.a.c_str(),
                a.frame_count(), o.b.c_str(), b.frame_count());
    return 1;
  }
  if (largest == 0 && o.ulp == 0)
    std::printf("identical (%d frames)\n", common);
  else if (largest == 0)
    std::printf("identical (%d frames; signed zeros aside)\n", common);
  else
    std::printf("within %llu ULPs (%d frames; largest difference %s)\n", (unsigned long long)o.ulp, common,
                distance_string(largest).c_str());
  return 0;
}

void add_compare(CLI::App& app, const GlobalOptions&, Action& run) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand("compare", "compare two caches frame by frame (exit 0 equal, 1 different, 2 error)");
  cmd->add_option("a", o->a, "a cache (.h5)")->required();
  cmd->add_option("b", o->b, "another cache (.h5)")->required();
  cmd->add_option("--ulp", o->ulp, "accept differences of up to N units in the last place (default 0: bitwise)");
  cmd->callback([&run, o] {
    run = [o] {
      try {
        return compare(*o);
      } catch (const std::exception& e) {
        throw Error(e.what(), 2);
      }
    };
  });
}

const Register reg("compare", add_compare);

}  // namespace
}  // namespace weft::cli
