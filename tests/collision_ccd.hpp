// CCD narrow phase: benchmark queries (no false negatives), hand-made and degenerate cases, minimum
// separation, time-of-impact lower bounds, proximity functions, the query-file reader, and device batch
// results equal bit for bit to the host calls.
#include "collision/ccd_batch.hpp"
#include "collision/ccd_proximity.hpp"
#include "collision/ccd_query_file.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>

namespace {

using weft::CcdKind;
using weft::CcdResult;
using weft::CcdSettings;
using weft::real;
using weft::Vec3;

constexpr CcdKind VF = CcdKind::VertexFace;
constexpr CcdKind EE = CcdKind::EdgeEdge;

CcdResult host_ccd(CcdKind k, const Vec3* x, real ms, const CcdSettings& s = {}) {
  return k == VF ? weft::ccd_vertex_face(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], ms, s)
                 : weft::ccd_edge_edge(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], ms, s);
}

// The batch on the device (collision/ccd_batch.hpp), one thread a query.
template <class Exec>
std::vector<CcdResult> device_ccd(CcdKind k, const std::vector<Vec3>& rows, real ms, const CcdSettings& s = {}) {
  return weft::ccd_batch_on<Exec>(k, rows, ms, s);
}

// Queries whose device result differs from the host call in any bit.
template <class Exec>
long count_mismatches(CcdKind k, const std::vector<Vec3>& rows, real ms, const std::vector<CcdResult>& dev) {
  long bad = 0;
  for (size_t q = 0; q < dev.size(); ++q) {
    const CcdResult h = host_ccd(k, &rows[8 * q], ms);
    bad += h.hit != dev[q].hit || weft::test::bits(h.toi) != weft::test::bits(dev[q].toi);
  }
  return bad;
}

// One hand-made query, on the device, checked against the host call.
template <class Exec>
CcdResult ccd1(CcdKind k, std::vector<Vec3> x, real ms) {
  const CcdResult d = device_ccd<Exec>(k, x, ms)[0];
  const CcdResult h = host_ccd(k, x.data(), ms);
  EXPECT_EQ(h.hit, d.hit);
  EXPECT_EQ(weft::test::bits(h.toi), weft::test::bits(d.toi));
  return d;
}

struct Score {
  long queries = 0, positives = 0, false_negatives = 0, false_positives = 0, mismatches = 0;
};

// Scores every file below root, per folder (family/kind), on the device, and compares with the host calls.
template <class Exec>
std::map<std::string, Score> score_dir(const std::string& root, real ms) {
  std::map<std::string, Score> by_family;
  for (const auto& path : weft::find_ccd_query_files(root)) {
    const auto f = weft::read_ccd_query_file(path);
    EXPECT_EQ(long(f.truth.size()), f.size()) << path << ": no truth";
    if (long(f.truth.size()) != f.size()) continue;
    const auto dev = device_ccd<Exec>(f.kind, f.rows, ms);
    const std::string family = std::filesystem::relative(std::filesystem::path(path).parent_path(), root).string();
    Score& s = by_family[family];
    s.queries += f.size();
    s.mismatches += count_mismatches<Exec>(f.kind, f.rows, ms, dev);
    for (long q = 0; q < f.size(); ++q) {
      s.positives += f.truth[q];
      if (f.truth[q] && !dev[q].hit) {
        ++s.false_negatives;
        ADD_FAILURE() << path << " query " << q << " (rows " << 8 * q + 1 << "-" << 8 * q + 8 << ") missed";
      }
      s.false_positives += !f.truth[q] && dev[q].hit;
    }
  }
  return by_family;
}

void report(const std::map<std::string, Score>& by_family, const std::string& tag) {
  for (const auto& [family, s] : by_family) {
    std::printf("[ ccd      ] %s %s: queries %ld positives %ld false-negatives %ld false-positives %ld\n",
                tag.c_str(), family.c_str(), s.queries, s.positives, s.false_negatives, s.false_positives);
    std::string key = "false_positives " + tag + " " + family;  // an XML attribute name in --gtest_output
    for (char& ch : key)
      if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    ::testing::Test::RecordProperty(key, std::to_string(s.false_positives));
    EXPECT_EQ(s.false_negatives, 0) << family;
    EXPECT_EQ(s.mismatches, 0) << family << ": device and host results differ";
  }
}

TEST(WEFT_TEST_SUITE, ccd_sample_queries_have_no_false_negatives) {
  using Exec = WEFT_TEST_EXECSPACE;
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const std::string root = weft::test::shared_dir() + "/data/ccd/sample-queries";
  auto zero = score_dir<Exec>(root, 0);
  EXPECT_EQ(zero["unit-tests/vertex-face"].queries + zero["unit-tests/edge-edge"].queries, 324);
  report(zero, "ms=0");
  // A minimum separation only adds contacts: still none missed.
  report(score_dir<Exec>(root, 1e-6), "ms=1e-6");
}

TEST(WEFT_TEST_SUITE, ccd_cloth_funnel_queries_have_no_false_negatives) {
  using Exec = WEFT_TEST_EXECSPACE;
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const std::string root = weft::test::shared_dir() + "/data/ccd/scalable/cloth-funnel";
  const auto by_family = score_dir<Exec>(root, 0);
  ASSERT_EQ(by_family.size(), 1u);
  EXPECT_GT(by_family.begin()->second.positives, 0);
  report(by_family, "ms=0 cloth-funnel");
}

// Triangle (0,0,0) (1,0,0) (0,1,0) at rest, in the plane z = 0.
std::vector<Vec3> vf_static_triangle(Vec3 p0, Vec3 p1) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  return {p0, a, b, c, p1, a, b, c};
}

TEST(WEFT_TEST_SUITE, ccd_point_through_triangle_is_hit_and_beside_is_not) {
  using Exec = WEFT_TEST_EXECSPACE;
  const CcdResult through = ccd1<Exec>(VF, vf_static_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1}), 0);
  EXPECT_TRUE(through.hit);
  EXPECT_LE(through.toi, 0.5);
  EXPECT_GE(through.toi, 0.5 - 1e-5);
  // Beside the hypotenuse: 1/sqrt(2) from the triangle, 0.5 per axis; only the Euclidean distance counts.
  const auto beside = vf_static_triangle({1, 1, 1}, {1, 1, -1});
  EXPECT_FALSE(ccd1<Exec>(VF, beside, 0).hit);
  EXPECT_FALSE(ccd1<Exec>(VF, beside, 0.69).hit);
  EXPECT_TRUE(ccd1<Exec>(VF, beside, 0.72).hit);
  // The triangle moves through a resting point instead.
  const Vec3 p{0.2, 0.3, 0}, up{0, 0, 0.5}, down{0, 0, -1.5};
  const CcdResult moving = ccd1<Exec>(
      VF, {p, Vec3{0, 0, 0} + up, Vec3{1, 0, 0} + up, Vec3{0, 1, 0} + up, p, Vec3{0, 0, 0} + down,
           Vec3{1, 0, 0} + down, Vec3{0, 1, 0} + down},
      0);
  EXPECT_TRUE(moving.hit);
  EXPECT_LE(moving.toi, 0.25);
  EXPECT_GE(moving.toi, 0.25 - 1e-5);
}

TEST(WEFT_TEST_SUITE, ccd_crossing_edges_are_hit_at_their_time) {
  using Exec = WEFT_TEST_EXECSPACE;
  const Vec3 a0{0, 0, 0}, a1{1, 0, 0};
  const CcdResult r =
      ccd1<Exec>(EE, {a0, a1, {0.5, -0.5, 1}, {0.5, 0.5, 1}, a0, a1, {0.5, -0.5, -1}, {0.5, 0.5, -1}}, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.5);
  EXPECT_GE(r.toi, 0.5 - 1e-5);
  // In one plane: b moves down onto a end first, touching at t = 1/2.
  const CcdResult p = ccd1<Exec>(EE, {a0, a1, {0.5, 1, 0}, {0.5, 2, 0}, a0, a1, {0.5, -1, 0}, {0.5, 0, 0}}, 0);
  EXPECT_TRUE(p.hit);
  EXPECT_LE(p.toi, 0.5);
  EXPECT_GE(p.toi, 0.5 - 1e-5);
  // Passing beside the end of the other edge.
  EXPECT_FALSE(ccd1<Exec>(EE, {a0, a1, {1.5, -0.5, 1}, {1.5, 0.5, 1}, a0, a1, {1.5, -0.5, -1}, {1.5, 0.5, -1}}, 0).hit);
}

TEST(WEFT_TEST_SUITE, ccd_parallel_edges_sliding_past) {
  using Exec = WEFT_TEST_EXECSPACE;
  const real ms = 0.01;
  // Edge b, parallel to a at height h, slides along x from [-2, -1] to [2, 3].
  const auto slide = [](real h) {
    const Vec3 a0{0, 0, 0}, a1{1, 0, 0};
    return std::vector<Vec3>{a0, a1, {-2, 0, h}, {-1, 0, h}, a0, a1, {2, 0, h}, {3, 0, h}};
  };
  EXPECT_FALSE(ccd1<Exec>(EE, slide(0.02), ms).hit);
  EXPECT_FALSE(ccd1<Exec>(EE, slide(1.5 * ms), ms).hit);
  // At h < ms contact starts when the end points come within ms: x_b1(t) = -1 + 4t = -sqrt(ms^2 - h^2).
  const real h = 0.005, t_contact = (1 - weft::sqrt_(ms * ms - h * h)) / 4;
  const CcdResult r = ccd1<Exec>(EE, slide(h), ms);
  EXPECT_TRUE(r.hit);
  EXPECT_LE(r.toi, t_contact);
  EXPECT_GE(r.toi, t_contact - 1e-5);
  // Collinear (h = 0) with zero thickness: contact from the same moment the ends meet, t = 1/4.
  const CcdResult c = ccd1<Exec>(EE, slide(0), 0);
  EXPECT_TRUE(c.hit);
  EXPECT_LE(c.toi, 0.25);
  EXPECT_GE(c.toi, 0.25 - 1e-5);
}

TEST(WEFT_TEST_SUITE, ccd_minimum_separation_on_a_tilted_face) {
  using Exec = WEFT_TEST_EXECSPACE;
  const real ms = 0.01;
  // A frame not aligned with the axes, so that per-axis and Euclidean distances differ.
  const Vec3 n = weft::normalized(Vec3{1, 2, 3});
  const Vec3 e1 = weft::normalized(weft::cross(n, Vec3{1, 0, 0})), e2 = weft::cross(n, e1);
  const Vec3 o{0.3, -0.2, 0.1};
  const auto at = [&](real a, real b, real h) { return o + a * e1 + b * e2 + h * n; };
  const auto stop_at = [&](real h1) {
    const Vec3 q0 = at(0, 0, 0), q1 = at(1, 0, 0), q2 = at(0, 1, 0);
    return std::vector<Vec3>{at(0.25, 0.25, 1), q0, q1, q2, at(0.25, 0.25, h1), q0, q1, q2};
  };
  const CcdResult near = ccd1<Exec>(VF, stop_at(0.9 * ms), ms);
  EXPECT_TRUE(near.hit);
  const real t_contact = (1 - ms) / (1 - 0.9 * ms);  // h(t) = 1 + t (0.9 ms - 1) = ms
  EXPECT_LE(near.toi, t_contact);
  EXPECT_GE(near.toi, t_contact - 1e-5);
  EXPECT_FALSE(ccd1<Exec>(VF, stop_at(1.1 * ms), ms).hit);
  EXPECT_FALSE(ccd1<Exec>(VF, stop_at(0.9 * ms), 0).hit);
}

TEST(WEFT_TEST_SUITE, ccd_degenerate_contacts_are_hit) {
  using Exec = WEFT_TEST_EXECSPACE;
  const auto vf = [](Vec3 p0, Vec3 p1) { return vf_static_triangle(p0, p1); };
  // Touching at t = 0 and moving away: contact at once.
  CcdResult r = ccd1<Exec>(VF, vf({0.25, 0.25, 0}, {0.25, 0.25, 1}), 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.toi, 0);
  // Arriving exactly at t = 1.
  EXPECT_TRUE(ccd1<Exec>(VF, vf({0.25, 0.25, 1}, {0.25, 0.25, 0}), 0).hit);
  // No motion at all: resting on the face is a contact, resting above it is not.
  r = ccd1<Exec>(VF, vf({0.1, 0.1, 0}, {0.1, 0.1, 0}), 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.toi, 0);
  EXPECT_FALSE(ccd1<Exec>(VF, vf({0.1, 0.1, 1}, {0.1, 0.1, 1}), 0).hit);
  // Coplanar: sliding in the triangle's plane, entering through the edge x = 0 at t = 2/3.
  r = ccd1<Exec>(VF, vf({-1, 0.25, 0}, {0.5, 0.25, 0}), 0);
  EXPECT_TRUE(r.hit);
  EXPECT_LE(r.toi, 2.0 / 3.0);
  // Grazing along an edge line, and through a corner.
  EXPECT_TRUE(ccd1<Exec>(VF, vf({-1, 0, 0}, {2, 0, 0}), 0).hit);
  EXPECT_TRUE(ccd1<Exec>(VF, vf({0, 0, 1}, {0, 0, -1}), 0).hit);
  EXPECT_TRUE(ccd1<Exec>(VF, vf({1, 0, -1}, {1, 0, 1}), 0).hit);
  // A triangle collapsed to a point and to a segment.
  const Vec3 z{0, 0, 0}, x{1, 0, 0};
  EXPECT_TRUE(ccd1<Exec>(VF, {{0, 0, 1}, z, z, z, {0, 0, -1}, z, z, z}, 0).hit);
  EXPECT_TRUE(ccd1<Exec>(VF, {{0.5, 0, 1}, z, x, x, {0.5, 0, -1}, z, x, x}, 0).hit);
  EXPECT_FALSE(ccd1<Exec>(VF, {{0.5, 0.1, 1}, z, x, x, {0.5, 0.1, -1}, z, x, x}, 0.05).hit);
  // Zero-length edges: a point edge pierced by another edge, and two point edges meeting.
  const Vec3 m{0.5, 0, 0};
  EXPECT_TRUE(ccd1<Exec>(EE, {m, m, {0.5, -1, 1}, {0.5, 1, 1}, m, m, {0.5, -1, -1}, {0.5, 1, -1}}, 0).hit);
  EXPECT_TRUE(ccd1<Exec>(EE, {z, z, x, x, x, x, z, z}, 0).hit);
  // Overlapping collinear edges at rest.
  r = ccd1<Exec>(EE, {z, x, {0.5, 0, 0}, {2, 0, 0}, z, x, {0.5, 0, 0}, {2, 0, 0}}, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.toi, 0);
  // Edges crossing exactly at t = 1.
  EXPECT_TRUE(ccd1<Exec>(EE, {z, x, {0.5, -1, 1}, {0.5, 1, 1}, z, x, {0.5, -1, 0}, {0.5, 1, 0}}, 0).hit);
}

TEST(WEFT_TEST_SUITE, ccd_non_finite_input_is_a_conservative_hit) {
  using Exec = WEFT_TEST_EXECSPACE;
  auto q = vf_static_triangle({5, 5, 5}, {5, 5, 6});
  q[4].x = __builtin_nan("");
  const CcdResult r = ccd1<Exec>(VF, q, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.toi, 0);
}

TEST(WEFT_TEST_SUITE, ccd_out_of_iterations_is_a_conservative_hit) {
  using Exec = WEFT_TEST_EXECSPACE;
  CcdSettings s;
  s.max_iterations = 3;
  const auto q = vf_static_triangle({0.25, 0.25, 1}, {0.25, 0.25, -1});
  const CcdResult r = host_ccd(VF, q.data(), 0, s);
  EXPECT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.5);
  const CcdResult d = device_ccd<Exec>(VF, q, 0, s)[0];
  EXPECT_EQ(d.hit, r.hit);
  EXPECT_EQ(weft::test::bits(d.toi), weft::test::bits(r.toi));
}

// Random queries against the distance sampled at 1001 times: a sampled contact (distance <= ms) must be
// reported no later than its time, and every reported hit must come near contact at some sample.
void check_against_sampling(CcdKind kind, const std::vector<Vec3>& rows, real ms, const std::vector<CcdResult>& res,
                            long& hits) {
  const int steps = 1000;
  for (size_t q = 0; q < res.size(); ++q) {
    const Vec3* x = &rows[8 * q];
    real first = 2, closest = 1e300;
    for (int k = 0; k <= steps; ++k) {
      const real t = real(k) / steps;
      Vec3 y[4];
      for (int i = 0; i < 4; ++i) y[i] = x[i] + t * (x[i + 4] - x[i]);
      real u, v, w;
      const real d2 = kind == VF ? weft::point_triangle_distance2(y[0], y[1], y[2], y[3], u, v, w)
                                 : weft::segment_segment_distance2(y[0], y[1], y[2], y[3], u, v);
      const real dist = weft::sqrt_(d2);
      closest = weft::min_(closest, dist);
      if (first > 1 && dist < ms * (1 - 1e-9)) first = t;
    }
    if (first <= 1) {
      EXPECT_TRUE(res[q].hit) << "query " << q << " comes within ms at t = " << first;
      EXPECT_LE(res[q].toi, first) << "query " << q;
    }
    // Vertices here move at most 2 sqrt(3) per unit time, F at most twice that: a contact lies within
    // 0.004 of the nearest sample.
    if (res[q].hit) EXPECT_LE(closest, ms + 0.01) << "query " << q << " reported far from any contact";
    hits += res[q].hit;
  }
}

// n random queries in [-1, 1]^3, each moving by up to 1 per axis: 8 points per query (start, then end).
std::vector<Vec3> random_queries(weft::test::TestRng& rng, int n) {
  std::vector<Vec3> rows;
  for (int q = 0; q < n; ++q) {
    Vec3 x0[4];
    for (auto& p : x0) p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    for (const auto& p : x0) rows.push_back(p);
    for (const auto& p : x0) rows.push_back(p + Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
  }
  return rows;
}

TEST(WEFT_TEST_SUITE, ccd_random_queries_match_sampled_distance_and_host) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(2021);
  for (CcdKind kind : {VF, EE}) {
    for (real ms : {0.0, 0.02, 0.2}) {
      const std::vector<Vec3> rows = random_queries(rng, 300);
      const auto res = device_ccd<Exec>(kind, rows, ms);
      EXPECT_EQ(count_mismatches<Exec>(kind, rows, ms, res), 0);
      long hits = 0;
      check_against_sampling(kind, rows, ms, res, hits);
      EXPECT_GT(hits, 10) << "too few contacts to test anything";
      EXPECT_LT(hits, 270) << "too few misses to test anything";
    }
  }
}

// Stopping at the first reported box (what the narrow phase and the fail-safe ask for) answers `hit` as the
// full search does, with a time no earlier than its earliest; on the device as on the host.
TEST(WEFT_TEST_SUITE, ccd_first_hit_gives_the_same_answer) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(7);
  CcdSettings first;
  first.first_hit = true;
  for (CcdKind kind : {VF, EE}) {
    for (real ms : {0.0, 0.05}) {
      const std::vector<Vec3> rows = random_queries(rng, 300);
      const auto full = device_ccd<Exec>(kind, rows, ms), fast = device_ccd<Exec>(kind, rows, ms, first);
      long hits = 0, later = 0;
      for (size_t q = 0; q < full.size(); ++q) {
        const CcdResult h = host_ccd(kind, &rows[8 * q], ms, first);
        EXPECT_EQ(fast[q].hit, full[q].hit) << "query " << q;
        EXPECT_EQ(h.hit, fast[q].hit) << "query " << q;
        EXPECT_EQ(weft::test::bits(h.toi), weft::test::bits(fast[q].toi)) << "query " << q;
        if (full[q].hit) EXPECT_GE(fast[q].toi, full[q].toi) << "query " << q;
        hits += full[q].hit;
        later += full[q].hit && fast[q].toi > full[q].toi;
      }
      EXPECT_GT(hits, 10) << "too few contacts to test anything";
      std::printf("ccd first_hit: %ld of %ld hits stopped before the earliest box\n", later, hits);
    }
  }
}

// Positions on a coarse grid, many of them coplanar, parallel or coincident, against the sampled distance.
TEST(WEFT_TEST_SUITE, ccd_degenerate_grid_queries_match_sampled_distance) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(77);
  const auto grid = [&] { return real(int(rng.next() % 9) - 4) / 4; };
  for (CcdKind kind : {VF, EE}) {
    for (real ms : {0.05, 0.3}) {
      std::vector<Vec3> rows;
      for (int q = 0; q < 400; ++q) {
        const int mode = q % 4;  // general; flat static face; one moving vertex; all in one plane
        Vec3 x[8];
        for (auto& p : x) p = {grid(), grid(), grid()};
        if (mode == 1)
          for (int i = 0; i < 8; ++i) x[i].z = i % 4 == 0 ? x[i].z : 0;
        if (mode == 2)
          for (int i = 1; i < 4; ++i) x[i + 4] = x[i];
        if (mode == 3)
          for (auto& p : x) p.z = 0;
        rows.insert(rows.end(), x, x + 8);
      }
      const auto res = device_ccd<Exec>(kind, rows, ms);
      EXPECT_EQ(count_mismatches<Exec>(kind, rows, ms, res), 0);
      long hits = 0;
      check_against_sampling(kind, rows, ms, res, hits);
    }
  }
}

TEST(WEFT_TEST_SUITE, proximity_known_distances) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  real u, v, w;
  EXPECT_DOUBLE_EQ(weft::point_triangle_distance2({0.25, 0.25, 2}, a, b, c, u, v, w), 4);  // face
  EXPECT_DOUBLE_EQ(u, 0.5);
  EXPECT_DOUBLE_EQ(v, 0.25);
  EXPECT_DOUBLE_EQ(w, 0.25);
  EXPECT_DOUBLE_EQ(weft::point_triangle_distance2({0.5, -1, 0}, a, b, c, u, v, w), 1);  // edge ab
  EXPECT_DOUBLE_EQ(v, 0.5);
  EXPECT_DOUBLE_EQ(w, 0);
  EXPECT_DOUBLE_EQ(weft::point_triangle_distance2({2, 1, 0}, a, b, c, u, v, w), 2);  // vertex b
  EXPECT_DOUBLE_EQ(v, 1);
  EXPECT_DOUBLE_EQ(weft::point_triangle_distance2({1, 1, 1}, a, b, c, u, v, w), 1.5);  // edge bc
  EXPECT_DOUBLE_EQ(v, 0.5);
  EXPECT_DOUBLE_EQ(w, 0.5);
  // Degenerate triangle (a segment): the distance to the segment.
  EXPECT_DOUBLE_EQ(weft::point_triangle_distance2({0.5, 1, 0}, a, b, b, u, v, w), 1);
  EXPECT_DOUBLE_EQ(u * a.x + v * b.x + w * b.x, 0.5);

  real s, t;
  // Skew segments crossing at distance 1.
  EXPECT_DOUBLE_EQ(weft::segment_segment_distance2(a, b, {0.25, -1, 1}, {0.25, 1, 1}, s, t), 1);
  EXPECT_DOUBLE_EQ(s, 0.25);
  EXPECT_DOUBLE_EQ(t, 0.5);
  // Parallel, overlapping: distance 2 whatever the pair chosen.
  EXPECT_DOUBLE_EQ(weft::segment_segment_distance2(a, b, {0.5, 2, 0}, {1.5, 2, 0}, s, t), 4);
  EXPECT_DOUBLE_EQ(s - (0.5 + t), 0);
  // Both segments points.
  EXPECT_DOUBLE_EQ(weft::segment_segment_distance2(a, a, b, b, s, t), 1);
  // Ends nearest.
  EXPECT_DOUBLE_EQ(weft::segment_segment_distance2(a, b, {2, 1, 0}, {3, 1, 0}, s, t), 2);
  EXPECT_DOUBLE_EQ(s, 1);
  EXPECT_DOUBLE_EQ(t, 0);
}

TEST(WEFT_TEST_SUITE, proximity_is_no_farther_than_sampled_points_on_device) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(7);
  const int n = 200, g = 40;
  std::vector<Vec3> pts(5 * n);
  for (auto& p : pts) p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
  // The device computes; the host checks against a grid over each primitive.
  auto d_pts = weft::test::to_device<Exec>(pts, "pts");
  Kokkos::View<real* [6], typename Exec::memory_space> d_out("out", n);
  Kokkos::parallel_for(
      "proximity", Kokkos::RangePolicy<Exec>(0, n), KOKKOS_LAMBDA(int i) {
        const Vec3* x = &d_pts(5 * i);
        real u, v, w, s, t;
        d_out(i, 0) = weft::point_triangle_distance2(x[0], x[1], x[2], x[3], u, v, w);
        d_out(i, 1) = u;
        d_out(i, 2) = v;
        d_out(i, 3) = weft::segment_segment_distance2(x[0], x[1], x[2], x[3], s, t);
        d_out(i, 4) = s;
        d_out(i, 5) = t;
      });
  auto out = Kokkos::create_mirror_view(d_out);
  Kokkos::deep_copy(out, d_out);
  for (int i = 0; i < n; ++i) {
    const Vec3* x = &pts[5 * i];
    real u, v, w, s, t;
    const real pt = weft::point_triangle_distance2(x[0], x[1], x[2], x[3], u, v, w);
    const real ss = weft::segment_segment_distance2(x[0], x[1], x[2], x[3], s, t);
    EXPECT_EQ(weft::test::bits(pt), weft::test::bits(out(i, 0)));
    EXPECT_EQ(weft::test::bits(u), weft::test::bits(out(i, 1)));
    EXPECT_EQ(weft::test::bits(v), weft::test::bits(out(i, 2)));
    EXPECT_EQ(weft::test::bits(ss), weft::test::bits(out(i, 3)));
    EXPECT_EQ(weft::test::bits(s), weft::test::bits(out(i, 4)));
    EXPECT_EQ(weft::test::bits(t), weft::test::bits(out(i, 5)));
    // The parameters name the reported closest points.
    EXPECT_GE(u, 0);
    EXPECT_GE(v, 0);
    EXPECT_GE(w, 0);
    EXPECT_NEAR(u + v + w, 1, 1e-12);
    EXPECT_NEAR(weft::norm2(x[0] - (u * x[1] + v * x[2] + w * x[3])), pt, 1e-12);
    EXPECT_NEAR(weft::norm2((x[0] + s * (x[1] - x[0])) - (x[2] + t * (x[3] - x[2]))), ss, 1e-12);
    real grid_pt = 1e300, grid_ss = 1e300;
    for (int j = 0; j <= g; ++j)
      for (int k = 0; k <= g; ++k) {
        const real a = real(j) / g, b = real(k) / g;
        grid_ss = weft::min_(grid_ss, weft::norm2((x[0] + a * (x[1] - x[0])) - (x[2] + b * (x[3] - x[2]))));
        if (j + k <= g)
          grid_pt = weft::min_(grid_pt, weft::norm2(x[0] - (x[1] + a * (x[2] - x[1]) + b * (x[3] - x[1]))));
      }
    EXPECT_LE(pt, grid_pt + 1e-12) << i;
    EXPECT_LE(ss, grid_ss + 1e-12) << i;
  }
}

using weft::test::ScratchDir;

std::string error_of(const std::string& path) {
  try {
    weft::read_ccd_query_file(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::string rows_text(int n, const std::string& row) {
  std::string s;
  for (int i = 0; i < n; ++i) s += row + "\n";
  return s;
}

TEST(WEFT_TEST_SUITE, ccd_query_file_reader) {
  const ScratchDir dir("ccd_query_file");
  // Exact rationals (a 2^111 denominator, a 53-bit numerator), the truth column, the kind from the folder.
  const std::string good = dir.write("fam/edge-edge/q.csv",
                                     "1,2,-3,2596148429267413814265248164610048,9007199254740991,4,1\r\n" +
                                         rows_text(7, "0,1,0,1,0,1,1") + rows_text(8, " 1, 1,1,1,1,1,0") + "\n");
  const auto f = weft::read_ccd_query_file(good);
  EXPECT_EQ(f.kind, EE);
  ASSERT_EQ(f.size(), 2);
  EXPECT_EQ(f.truth, (std::vector<uint8_t>{1, 0}));
  EXPECT_EQ(f.truth_source, "csv");
  EXPECT_EQ(f.rows[0].x, 0.5);
  EXPECT_EQ(f.rows[0].y, -3 * 0x1p-111);
  EXPECT_EQ(f.rows[0].z, 2251799813685247.75);
  EXPECT_EQ(f.rows[15].z, 1);

  // Six columns: the truth comes from ../mma_bool/<name>_mma_bool.json, the kind from the name.
  const std::string scal = dir.write("case/queries/7vf.csv", rows_text(16, "0,1,0,1,0,1"));
  EXPECT_TRUE(weft::read_ccd_query_file(scal).truth.empty());
  const std::string json = dir.write("case/mma_bool/7vf_mma_bool.json", "[false, true]");
  const auto g = weft::read_ccd_query_file(scal);
  EXPECT_EQ(g.kind, VF);
  EXPECT_EQ(g.truth, (std::vector<uint8_t>{0, 1}));
  EXPECT_EQ(g.truth_source, json);
  dir.write("case/mma_bool/7vf_mma_bool.json", "[false]");
  EXPECT_NE(error_of(scal).find("1 labels for 2 queries"), std::string::npos) << error_of(scal);
  EXPECT_NE(error_of(scal).find("7vf_mma_bool.json"), std::string::npos) << error_of(scal);

  EXPECT_EQ(weft::read_ccd_query_file(dir.write("x/vertex-face/data_0_0.csv", "")).kind, VF);
  EXPECT_EQ(weft::ccd_kind_from_path("a/edge-edge/sub/q.csv"), EE);
  EXPECT_THROW(weft::ccd_kind_from_path("a/coffee.csv"), std::runtime_error);

  // Bad files: the message names the file and the line.
  const auto expect_error = [&](const std::string& rel, const std::string& text, const std::string& what) {
    const std::string path = dir.write(rel, text);
    const std::string e = error_of(path);
    EXPECT_EQ(e.rfind(path + what, 0), 0u) << "got: " << e;
  };
  expect_error("e/vf/a_vf.csv", "0,1,0,1,0,1\n0,1,0,1\n", ":2: 4 columns");
  expect_error("e/vf/b_vf.csv", rows_text(2, "0,1,0,1,0,1") + "0,1,0,1,0,1,0\n", ":3: 7 columns where earlier");
  expect_error("e/vf/c_vf.csv", "0,1,x,1,0,1\n", ":1: numerator 'x'");
  expect_error("e/vf/d_vf.csv", "0,1,0,0,0,1\n", ":1: denominator '0'");
  expect_error("e/vf/e_vf.csv", "0,1,9007199254740993,1,0,1\n", ":1: numerator '9007199254740993' is not exactly");
  expect_error("e/vf/f_vf.csv", "0,1,0,1,0,1,2\n", ":1: truth '2'");
  expect_error("e/vf/g_vf.csv", rows_text(3, "0,1,0,1,0,1,1") + "0,1,0,1,0,1,0\n", ":4: truth differs");
  expect_error("e/vf/h_vf.csv", rows_text(9, "0,1,0,1,0,1"), ":9: incomplete query");
  EXPECT_NE(error_of(dir.file("missing_vf.csv")).find("cannot open"), std::string::npos);

  // Listing: every *.csv below the folder, sorted.
  const auto files = weft::find_ccd_query_files(dir.file("case"));
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0], scal);
  EXPECT_THROW(weft::find_ccd_query_files(dir.file("nowhere")), std::runtime_error);
}

}  // namespace
