// The narrow phase's kernels (collision/narrow_pipeline.hpp) give the contacts of testing each pair's
// feature pairs one after another, CCD included, whatever the chunk size.
#include "collision/crossing_failsafe.hpp"
#include "collision/narrow_pipeline.hpp"
#include "collision/pair_cull.hpp"
#include "collision/representative.hpp"

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace {

using weft::real;
using weft::Vec3;

// Two sheets of n x n quads (1 cm), the upper 5 mm above the lower and offset by a third of a cell; over the
// substep the upper one's columns fall 4 and 8 mm in turn, so some of its features end in proximity of the
// lower sheet and some cross it (the CCD's). Every triangle pair is a candidate.
struct Sheets {
  int n = 6;
  std::vector<Vec3> xs, x;
  std::vector<std::array<int, 3>> tris;
  std::vector<weft::IndexPair> pairs;
  Sheets() {
    const int side = n + 1;
    for (int layer = 0; layer < 2; ++layer)
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
          const real shift = layer ? real(0.0033) : real(0);
          const Vec3 p{real(0.01) * i + shift, real(0.01) * j + shift, layer ? real(0.005) : real(0)};
          xs.push_back(p);
          // A little shear so the motion is not the same for every point.
          x.push_back(layer ? p + Vec3{real(0.0004) * (i % 3), real(-0.0003) * (j % 2), real(-0.004) - real(0.004) * (i % 2)} : p);
        }
    for (int layer = 0; layer < 2; ++layer)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int a = layer * side * side + j * side + i;
          tris.push_back({a, a + 1, a + side + 1});
          tris.push_back({a, a + side + 1, a + side});
        }
    for (int a = 0; a < int(tris.size()); ++a)
      for (int b = a + 1; b < int(tris.size()); ++b) pairs.push_back({a, b});
  }
};

// The sheets as one cloth side in Exec's memory.
template <class Exec>
weft::SideMesh<typename Exec::memory_space> side_of(const Sheets& s) {
  using Mem = typename Exec::memory_space;
  using weft::test::to_device;
  Kokkos::View<int* [3], Mem> tris(std::string("tris"), s.tris.size());
  auto m = Kokkos::create_mirror_view(tris);
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) m(t, k) = s.tris[t][k];
  Kokkos::deep_copy(tris, m);
  const size_t np = s.x.size();
  std::vector<int> layer(np);
  for (size_t i = 0; i < np; ++i) layer[i] = i < np / 2 ? 0 : 1;
  weft::SideMesh<Mem> side;
  side.x = to_device<Exec>(s.x, "x");
  side.xs = to_device<Exec>(s.xs, "xs");
  side.xo = side.xs;
  side.tris = tris;
  side.rmask = to_device<Exec>(weft::representative_features(s.tris, int(np)), "rmask");
  side.thickness = to_device<Exec>(std::vector<real>(np, real(0.001)), "thickness");
  side.friction = to_device<Exec>(std::vector<real>(np, real(1)), "friction");
  side.dfriction = to_device<Exec>(std::vector<real>(np, real(1)), "dfriction");
  side.layer = to_device<Exec>(layer, "layer");
  return side;
}

template <class Exec>
std::vector<weft::Contact> narrow(const Sheets& s, long chunk, long& total) {
  using Mem = typename Exec::memory_space;
  const weft::SideMesh<Mem> side = side_of<Exec>(s);
  Kokkos::View<weft::IndexPair*, Mem> pairs = weft::test::to_device<Exec>(s.pairs, "pairs");
  Kokkos::View<weft::Contact*, Mem> contacts("contacts", 0);
  weft::NarrowPipeline<Exec> pipeline(chunk);
  total = pipeline.run(Exec(), side, side, weft::NarrowSettings{}, pairs, long(s.pairs.size()), contacts, 0);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), contacts);
  return std::vector<weft::Contact>(h.data(), h.data() + total);
}

// Field by field (the struct has padding).
bool same_bits(const weft::Contact& a, const weft::Contact& b) {
  const auto eq = [](const real& u, const real& v) { return std::memcmp(&u, &v, sizeof u) == 0; };
  bool same = a.kind == b.kind && eq(a.n.x, b.n.x) && eq(a.n.y, b.n.y) && eq(a.n.z, b.n.z) && eq(a.r, b.r) &&
              eq(a.mu_s, b.mu_s) && eq(a.mu_d, b.mu_d);
  for (int k = 0; k < 4; ++k) same = same && a.p[k] == b.p[k] && eq(a.b[k], b.b[k]) && eq(a.wscale[k], b.wscale[k]);
  return same;
}

TEST(WEFT_TEST_SUITE, narrow_phase_kernels_match_testing_pair_by_pair) {
  using Exec = WEFT_TEST_EXECSPACE;
  const Sheets s;
  // The reference: every pair's tests and CCDs in turn, on the host.
  const weft::SideMesh<Kokkos::HostSpace> host = side_of<Kokkos::DefaultHostExecutionSpace>(s);
  const weft::NarrowSettings ns;
  std::vector<uint32_t> masks;
  long by_ccd = 0, n = 0;
  for (const weft::IndexPair& p : s.pairs) {
    const weft::FeatureTests t = weft::feature_tests(host, p.first, host, p.second, ns);
    uint32_t m = t.hit;
    for (int bit = 0; bit < 15; ++bit)
      if (((t.ccd >> bit) & 1) && weft::feature_ccd(host, p.first, host, p.second, bit, (t.touching >> bit) & 1, ns)) {
        m |= 1u << bit;
        ++by_ccd;
      }
    masks.push_back(m);
    n += weft::popcount32(m);
  }
  Kokkos::View<weft::Contact*, Kokkos::HostSpace> expected("expected", n);
  long o = 0;
  for (size_t i = 0; i < s.pairs.size(); ++i) {
    weft::fill_contacts(host, s.pairs[i].first, host, s.pairs[i].second, masks[i], ns, expected, o);
    o += weft::popcount32(masks[i]);
  }
  ASSERT_GT(by_ccd, 0) << "the scene must need the CCD";
  ASSERT_LT(by_ccd, n) << "and proximity";
  for (long chunk : {1L << 23, 97L, 1L}) {
    long total = 0;
    const std::vector<weft::Contact> got = narrow<Exec>(s, chunk, total);
    ASSERT_EQ(total, n) << "chunk " << chunk;
    for (long i = 0; i < n; ++i) ASSERT_TRUE(same_bits(got[i], expected(i))) << "contact " << i << ", chunk " << chunk;
  }
}

// swept_apart, the narrow phase's and the fail-safe's cut of candidate pairs (collision/pair_cull.hpp): whenever it says two
// moving triangles stay farther apart than the reach, no vertex-face or edge-edge pair of them comes that
// close at any time of the motion (sampled); and it does cut layers apart, never touching neighbours.
TEST(WEFT_TEST_SUITE, swept_apart_pairs_never_come_within_reach) {
  using Host = Kokkos::HostSpace;
  std::vector<Vec3> xs(6), x(6);
  Kokkos::View<int* [3], Host> tris("tris", 2);
  for (int k = 0; k < 3; ++k) { tris(0, k) = k; tris(1, k) = 3 + k; }
  weft::SideMesh<Host> m;
  m.tris = tris;
  const int ta[3] = {0, 1, 2}, tb[3] = {3, 4, 5};
  const auto apart = [&](real reach) {
    m.x = Kokkos::View<const Vec3*, Host>(x.data(), 6);
    m.xs = Kokkos::View<const Vec3*, Host>(xs.data(), 6);
    return weft::pair_cull_detail::swept_apart(m, ta, m, tb, reach);
  };
  // The closest any feature pair of the two comes, at 65 times of the motion.
  const auto closest = [&] {
    real d2 = 1e300, u, v, w;
    for (int i = 0; i <= 64; ++i) {
      const real t = real(i) / 64;
      Vec3 p[6];
      for (int k = 0; k < 6; ++k) p[k] = xs[k] + t * (x[k] - xs[k]);
      for (int k = 0; k < 3; ++k) {
        d2 = std::min(d2, weft::point_triangle_distance2(p[k], p[3], p[4], p[5], u, v, w));
        d2 = std::min(d2, weft::point_triangle_distance2(p[3 + k], p[0], p[1], p[2], u, v, w));
        for (int j = 0; j < 3; ++j)
          d2 = std::min(d2, weft::segment_segment_distance2(p[k], p[(k + 1) % 3], p[3 + j], p[3 + (j + 1) % 3], u, v));
      }
    }
    return std::sqrt(d2);
  };
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<real> U(-1, 1);
  const auto rand3 = [&](real s) { return Vec3{s * U(rng), s * U(rng), s * U(rng)}; };
  int cut = 0, kept = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 ca = rand3(0.01), cb = ca + rand3(0.01) + Vec3{0, 0, real(0.004) * U(rng)};
    for (int k = 0; k < 3; ++k) {
      xs[k] = ca + rand3(0.005);
      xs[3 + k] = cb + rand3(0.005);
    }
    const Vec3 ma = rand3(trial % 2 ? 0.001 : 0.01), mb = rand3(trial % 2 ? 0.001 : 0.01);
    for (int k = 0; k < 3; ++k) {
      x[k] = xs[k] + ma + rand3(0.0005);
      x[3 + k] = xs[3 + k] + mb + rand3(0.0005);
    }
    const real reach = real(0.0005) + real(0.002) * (U(rng) + 1);
    if (apart(reach)) {
      ++cut;
      ASSERT_GT(closest(), reach) << "trial " << trial;
    } else {
      ++kept;
    }
  }
  EXPECT_GT(cut, 1000);
  EXPECT_GT(kept, 1000);
  // Two resting layers 3 thicknesses apart are cut at a reach of 2.5; neighbours sharing a corner never are.
  for (int k = 0; k < 3; ++k) {
    xs[k] = x[k] = Vec3{real(0.01) * (k == 1), real(0.01) * (k == 2), 0};
    xs[3 + k] = x[3 + k] = xs[k] + Vec3{real(0.003), real(0.002), real(0.003)};
  }
  EXPECT_TRUE(apart(0.0025));
  EXPECT_FALSE(apart(0.0031));
  for (int k = 0; k < 3; ++k) xs[3 + k] = x[3 + k] = Vec3{real(0.01) * (k != 0), real(0.01) * (k == 1), 0} * real(-1);
  xs[3] = x[3] = xs[0];
  EXPECT_FALSE(apart(1e-9));
}

// The fail-safe's later rounds grow the flagged points by the other corners of their triangles, never by
// pinned points: a strip of four triangles, 0-1-2 over 3-4-5, with point 3 pinned.
TEST(WEFT_TEST_SUITE, failsafe_flags_grow_by_one_ring_but_not_to_pinned_points) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = typename Exec::memory_space;
  const int tri[4][3] = {{0, 1, 3}, {1, 4, 3}, {1, 2, 4}, {2, 5, 4}};
  Kokkos::View<int* [3], Mem> tris("tris", 4);
  auto th = Kokkos::create_mirror_view(tris);
  for (int t = 0; t < 4; ++t)
    for (int k = 0; k < 3; ++k) th(t, k) = tri[t][k];
  Kokkos::deep_copy(tris, th);
  const auto w = weft::test::to_device<Exec>(std::vector<real>{1, 1, 1, 0, 1, 1}, "w");
  const auto grow = [&](std::vector<int> flagged) {
    const auto flag = weft::test::to_device<Exec>(flagged, "flag");
    const auto grown = weft::test::to_device<Exec>(flagged, "grown");
    Kokkos::parallel_for(Kokkos::RangePolicy<Exec>(0, 4), weft::failsafe_detail::GrowFlags<Mem>{tris, flag, w, grown});
    return weft::test::to_host(grown);
  };
  EXPECT_EQ(grow({1, 0, 0, 0, 0, 0}), (std::vector<int>{1, 1, 0, 0, 0, 0}));  // 3 is pinned
  EXPECT_EQ(grow({0, 0, 0, 0, 0, 1}), (std::vector<int>{0, 0, 1, 0, 1, 1}));
  EXPECT_EQ(grow({0, 0, 0, 1, 0, 0}), (std::vector<int>{1, 1, 0, 1, 1, 0}));  // a flagged pinned point still grows
  EXPECT_EQ(grow({0, 0, 0, 0, 0, 0}), (std::vector<int>(6, 0)));
}

}  // namespace
