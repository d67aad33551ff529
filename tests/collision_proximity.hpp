// Proximity contacts with per-point displacement bounds (the default contact model): no move exceeds its
// bound, nothing crosses in scenes built to tempt a crossing, and pins follow their animation exactly.
#include "collision/contact_jacobi.hpp"
#include "collision/displacement_bounds.hpp"
#include "collision/pin_groups.hpp"
#include "io/builtin_scenes.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <algorithm>
#include <array>

namespace {

using weft::real;
using weft::Vec3;

// Two triangles `gap` apart, one above the other, each with query margin `margin`, and the bounds over
// their one candidate pair.
struct TwoTriangles {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  static constexpr real th = 0.001;
  const real gap;
  const std::vector<Vec3> x0h;
  Kokkos::View<int* [3], Mem> tris{"tris", 2};
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<weft::IndexPair*, Mem> pairs;
  weft::SideMesh<Mem> cloth;
  const weft::BoundSettings bs;
  weft::DisplacementBounds<Exec> b;

  TwoTriangles(real gap_, real margin, const weft::BoundSettings& settings = {})
      : gap(gap_), x0h{{0, 0, 0}, {0.1, 0, 0}, {0, 0, 0.1}, {0.01, gap_, 0.01}, {0.05, gap_, 0.01}, {0.01, gap_, 0.05}},
        x(weft::test::to_device<Exec, Vec3>(x0h, "x")),
        w(weft::test::to_device<Exec, real>(std::vector<real>(6, 1.0), "w")),
        pairs(weft::test::to_device<Exec, weft::IndexPair>({{0, 1}}, "pairs")), bs(settings),
        b(6, weft::test::to_device<Exec, real>({margin, margin}, "margins"),
          weft::test::to_device<Exec, real>({margin, margin}, "margins"), bs) {
    auto tm = Kokkos::create_mirror_view(tris);
    for (int k = 0; k < 3; ++k) { tm(0, k) = k; tm(1, k) = 3 + k; }
    Kokkos::deep_copy(tris, tm);
    cloth.tris = tris;
    cloth.rmask = weft::test::to_device<Exec, uint8_t>({0x3F, 0x3F}, "rmask");
    cloth.thickness = weft::test::to_device<Exec, real>(std::vector<real>(6, th), "th");
  }
  // A query from where the points stand (a full one, or a refresh); the bounds on the host. With
  // `contacts`, the pair's contact bits are taken too, as the collision stage takes a self pair's. A
  // still refresh measures no pair, as in the collision stage.
  auto query(bool refresh = false, bool contacts = false) {
    b.prepare(Exec(), x, x, w, tris, /*first*/ true, refresh);
    cloth.x = cloth.xs = cloth.xo = b.x0();
    if (b.still()) {
    } else if (contacts) {
      weft::NarrowSettings ns;
      ns.self = true;
      b.add_pairs(Exec(), cloth, cloth, pairs, 1, b.relative_end(), w, hits, ns);
    } else {
      b.add_pairs(Exec(), cloth, cloth, pairs, 1, b.relative_end(), w);
    }
    if (!b.still()) b.measured_self(Exec());
    b.finish(Exec(), w);
    return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.bounds());
  }
  Kokkos::View<uint32_t*, Mem> hits{"hits", 1};
  // A full query whose self pair goes through add_self_pairs (with predicted_reference,
  // add_self_pairs_with_references), cut first (the device's way) or tested inline (the host's); the
  // bounds on the host, the pair's contact bits (0 when it was not measured) and the pairs measured. The
  // lower triangle wants to move `apart` along x, the upper one as far the other way.
  std::vector<real> query_self(bool cut_first, uint32_t& hit, long& measured, real apart = 0) {
    std::vector<Vec3> wanted = x0h;
    for (size_t i = 0; i < 6; ++i) wanted[i].x += i < 3 ? apart : -apart;
    const auto xw = weft::test::to_device<Exec, Vec3>(wanted, "wanted");
    b.prepare(Exec(), x, xw, w, tris, /*first*/ true);
    cloth.x = cloth.xs = cloth.xo = b.x0();
    weft::NarrowSettings ns;
    ns.self = true;
    weft::PairCull<Exec> cull;
    Kokkos::View<const weft::IndexPair*, Mem> kept;
    if (b.sweeps())
      b.add_self_pairs_with_references(Exec(), cloth, pairs, 1, w, hits, ns, cull, kept, measured, cut_first);
    else
      b.add_self_pairs(Exec(), cloth, pairs, 1, b.relative_end(), w, hits, ns, cull, kept, measured, cut_first);
    b.measured_self(Exec());
    b.finish(Exec(), w);
    hit = measured > 0 ? weft::test::to_host(hits)[0] : 0;
    const auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.bounds());
    return std::vector<real>(bh.data(), bh.data() + bh.extent(0));
  }
  void move_to(const std::vector<Vec3>& p) { Kokkos::deep_copy(x, weft::test::to_device<Exec, Vec3>(p, "moved")); }
};

// Two triangles 1 cm apart, one above the other. Every point's bound is gamma times that gap; moves of
// 5 cm towards each other are cut back to the bound, and the gap keeps at least (1 - 2 gamma) of itself.
// Contacts on the same two points project as one row counted as many: one pair seen from either side and
// as an edge-edge pair gives the same bits merged or not, in fewer rows; a contact on four points stays
// a row of its own.
TEST(WEFT_TEST_SUITE, jacobi_contacts_on_the_same_points_project_as_one_row) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  const std::vector<Vec3> xh{{0, 0.005, 0}, {0, 0, 0}, {0.1, 0.004, 0}, {0.1, 0.004, 0.01}};
  std::vector<Vec3> xsh = xh;
  xsh[0].x -= 0.002;  // a tangential move for friction to take back
  auto contact = [](std::array<int, 4> p, std::array<real, 4> b, Vec3 n) {
    weft::Contact c;
    for (int k = 0; k < 4; ++k) { c.p[k] = p[k]; c.b[k] = b[k]; }
    c.n = n;
    c.r = 0.01;
    c.mu_s = c.mu_d = 0.5;
    return c;
  };
  const std::vector<weft::Contact> ch{
      contact({0, 1, 2, 3}, {1, -1, 0, 0}, {0, 1, 0}),                 // 0 on a face corner at 1
      contact({2, 3, 0, 1}, {0.5, 0.5, -0.5, -0.5}, {0, 1, 0}),        // four points
      contact({1, 0, 2, 3}, {1, -1, 0, 0}, {0, -1, 0}),                // 1 on a face corner at 0
      contact({0, 2, 1, 3}, {1, 0, -1, 0}, {0, 1, 0})};                // edges meeting at 0 and 1
  const auto c = weft::test::to_device<Exec>(ch, "contacts");
  auto run = [&](bool merge, long& rows) {
    auto x = weft::test::to_device<Exec>(xh, "x");
    auto xs = weft::test::to_device<Exec>(xsh, "xs");
    auto w = weft::test::to_device<Exec>(std::vector<real>(4, 1.0), "w");
    Kokkos::View<Vec3*, Mem> cx("cx", 0), cxs("cxs", 0);
    weft::JacobiContacts<Exec> j(merge);
    j.contacts_changed();
    for (int it = 0; it < 3; ++it) j.project(Exec(), c, long(ch.size()), x, xs, w, cx, cxs);
    rows = j.rows();
    return weft::test::to_host(x);
  };
  long merged_rows = 0, rows = 0;
  const auto merged = run(true, merged_rows), each = run(false, rows);
  EXPECT_EQ(merged_rows, 2);
  EXPECT_EQ(rows, 4);
  EXPECT_GT(merged[0].y, xh[0].y);  // pushed apart
  for (int p = 0; p < 4; ++p) {
    EXPECT_EQ(weft::test::bits(merged[p].x), weft::test::bits(each[p].x)) << p;
    EXPECT_EQ(weft::test::bits(merged[p].y), weft::test::bits(each[p].y)) << p;
    EXPECT_EQ(weft::test::bits(merged[p].z), weft::test::bits(each[p].z)) << p;
  }
}

TEST(WEFT_TEST_SUITE, proximity_bounds_cut_every_move_back_and_keep_pairs_apart) {
  using Exec = WEFT_TEST_EXECSPACE;
  // Query margins of 2 cm: more than the gap, so the gap decides.
  TwoTriangles s(0.01, 0.02);
  const real gap = s.gap, gamma = s.bs.gamma;
  const auto bound = s.query();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(bound(i), gamma * gap, 1e-12) << "point " << i;
  // Lower triangle moves 5 cm up, upper 5 cm down (and sideways): every move is cut back to its bound.
  std::vector<Vec3> moved = s.x0h;
  for (int i = 0; i < 6; ++i) moved[i] += i < 3 ? Vec3{0.01, 0.05, 0} : Vec3{-0.02, -0.05, 0.01};
  s.move_to(moved);
  s.b.truncate(Exec(), s.x, s.w);
  EXPECT_EQ(s.b.cut_count(Exec()), 6);
  const auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.x);
  real top = -1, bottom = 1;
  for (int i = 0; i < 6; ++i) {
    EXPECT_LE(weft::norm(xh(i) - s.x0h[i]), bound(i) * (1 + 1e-12)) << "point " << i;
    EXPECT_NEAR(weft::norm(xh(i) - s.x0h[i]), bound(i), 1e-12) << "point " << i;
    if (i < 3) top = std::max(top, xh(i).y); else bottom = std::min(bottom, xh(i).y);
  }
  EXPECT_GE(bottom - top, (1 - 2 * gamma) * gap * (1 - 1e-9));
  // A move within the bound is left alone.
  s.move_to(s.x0h);
  s.b.truncate(Exec(), s.x, s.w);
  EXPECT_EQ(s.b.cut_count(Exec()), 0);
}

// A pair that cannot part (two triangles driven into each other query after query, as pinned corners of a
// jammed twist are) keeps (1 - 2 gamma) of its distance per query: without a floor 13 queries take 1 mm to
// below the distances' fixed-point resolution (2^-40 m), where rounding decides on which side a point lies.
// With the separation floor the pair never closes past it, and while it is farther than floor /
// (1 - 2 gamma) its bounds are the same bits as without the floor.
TEST(WEFT_TEST_SUITE, proximity_bounds_never_close_a_pair_past_the_separation_floor) {
  using Exec = WEFT_TEST_EXECSPACE;
  const real gap = 0.001, floor = 1e-7;
  std::vector<std::vector<real>> bounds[2];
  real closest[2];
  for (int with = 0; with < 2; ++with) {
    weft::BoundSettings bs;
    bs.separation = with ? floor : 0;
    TwoTriangles s(gap, 0.02, bs);
    std::vector<Vec3> at = s.x0h;
    for (int q = 0; q < 40; ++q) {
      s.move_to(at);
      const auto b = s.query();
      bounds[with].emplace_back(b.data(), b.data() + 6);
      // Every point wants 1 cm towards the other triangle: each is cut back to its bound.
      std::vector<Vec3> wanted = at;
      for (int i = 0; i < 6; ++i) wanted[size_t(i)].y += i < 3 ? 0.01 : -0.01;
      s.move_to(wanted);
      s.b.truncate(Exec(), s.x, s.w);
      const auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.x);
      for (int i = 0; i < 6; ++i) at[size_t(i)] = xh(i);
    }
    closest[with] = at[3].y - at[0].y;
  }
  EXPECT_LT(closest[0], 1e-12);  // what the floor is for
  EXPECT_GE(closest[1], floor * (1 - 1e-6));
  EXPECT_LT(closest[1], 2 * floor);  // the pair did close up to the floor
  const real gamma = weft::BoundSettings{}.gamma;
  for (size_t q = 0; q < 40; ++q) {
    const real d = bounds[0][q][0] / gamma;  // the pair's distance at query q, the same in both runs so far
    if (!(d > floor / (1 - 2 * gamma))) break;
    for (int i = 0; i < 6; ++i)
      EXPECT_EQ(weft::test::bits(bounds[1][q][size_t(i)]), weft::test::bits(bounds[0][q][size_t(i)]))
          << "query " << q << " point " << i;
  }
}

// Self pairs cut before the bounds kernel (the device's way) or tested inline (the host's) give the same
// bounds and contact bits. Margins of 2 cm, thickness 1 mm: at 2 mm the pair is a contact, at 1 cm it bounds
// every point by gamma 1 cm, at 3 cm it is past every bound (gamma Q = 8 mm whether measured or not) and the
// cut drops it, at 5 cm it is beyond the two margins' reach.
TEST(WEFT_TEST_SUITE, proximity_self_pairs_cut_first_or_inline_give_the_same_bits) {
  for (const real gap : {0.002, 0.01, 0.03, 0.05}) {
    uint32_t hit[2];
    long measured[2];
    std::vector<real> bounds[2];
    for (int cut = 0; cut < 2; ++cut) {
      TwoTriangles s(gap, 0.02);
      bounds[cut] = s.query_self(cut == 1, hit[cut], measured[cut]);
    }
    EXPECT_EQ(measured[0], 1) << gap;
    EXPECT_EQ(measured[1], gap < 0.02 ? 1 : 0) << gap;
    EXPECT_EQ(hit[0], hit[1]) << gap;
    EXPECT_EQ(hit[1] != 0, gap < 0.0025) << gap;
    for (int i = 0; i < 6; ++i) {
      EXPECT_EQ(weft::test::bits(bounds[0][i]), weft::test::bits(bounds[1][i])) << gap << " point " << i;
      EXPECT_NEAR(bounds[1][i], 0.4 * std::min(gap, real(0.02)), 1e-12) << gap << " point " << i;
    }
  }
}

// The same with reference moves, the two triangles wanting 2 mm each along x, opposite ways (their
// references differ by 4 mm): at 3 cm the pair is past every bound even after the references (2.6 cm of
// distance left against Q = 2 cm, and 4 mm is less than half the gap, so it anchors nothing), and the cut
// drops it; at 1 cm it bounds, at 2 mm it is a contact, at 5 cm it is beyond reach.
TEST(WEFT_TEST_SUITE, proximity_self_pairs_with_references_cut_first_or_inline_give_the_same_bits) {
  weft::BoundSettings settings;
  settings.predicted_reference = true;
  for (const real gap : {0.002, 0.01, 0.03, 0.05}) {
    uint32_t hit[2];
    long measured[2];
    std::vector<real> bounds[2];
    for (int cut = 0; cut < 2; ++cut) {
      TwoTriangles s(gap, 0.02, settings);
      bounds[cut] = s.query_self(cut == 1, hit[cut], measured[cut], 0.002);
      EXPECT_TRUE(s.b.sweeps()) << gap;
    }
    EXPECT_EQ(measured[0], 1) << gap;
    EXPECT_EQ(measured[1], gap < 0.02 ? 1 : 0) << gap;
    EXPECT_EQ(hit[0], hit[1]) << gap;
    EXPECT_EQ(hit[1] != 0, gap < 0.0025) << gap;
    for (int i = 0; i < 6; ++i)
      EXPECT_EQ(weft::test::bits(bounds[0][i]), weft::test::bits(bounds[1][i])) << gap << " point " << i;
  }
}

// A refresh keeps the last full query's pairs and margins, and spends what each point moved since. Two
// triangles 1 cm apart with margins of 1.1 cm: the full query bounds every point by gamma 1 cm. The lower
// triangle then moves 3.9 mm up (within its bound): at a refresh it has spent that much of gamma 1.1 cm,
// and the narrower gap bounds the upper one.
TEST(WEFT_TEST_SUITE, proximity_refresh_spends_what_points_moved_since_the_full_query) {
  using Exec = WEFT_TEST_EXECSPACE;
  const real q = 0.011, up = 0.0039;
  TwoTriangles s(0.01, q);
  const real gap = s.gap, gamma = s.bs.gamma;
  EXPECT_GT(s.b.spent(Exec(), s.x, s.w), 6);  // before any full query: more than every point
  const auto full = s.query();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(full(i), gamma * gap, 1e-12) << "point " << i;
  std::vector<Vec3> moved = s.x0h;
  for (int i = 0; i < 3; ++i) moved[i].y += up;
  s.move_to(moved);
  s.b.truncate(Exec(), s.x, s.w);
  EXPECT_EQ(s.b.cut_count(Exec()), 0);
  EXPECT_EQ(s.b.spent(Exec(), s.x, s.w), 3);  // the lower points moved more than half of gamma q
  const auto kept = s.query(true);
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(kept(i), i < 3 ? gamma * q - up : gamma * (gap - up), 1e-9) << "point " << i;
  // A full query again starts the budget afresh.
  const auto again = s.query();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(again(i), gamma * (gap - up), 1e-9) << "point " << i;
}

// A refresh skips a kept pair only while its distance at the full query, less what its corners moved
// since, stays beyond its reach. Two triangles 3 cm apart with margins of 1.1 cm are out of reach at the
// full query; the lower one then moves up by 0.5 cm (the pair stays out of reach: nothing bounds the
// points but their margins' budget) and by 1.5 cm more (now 1 cm apart: the refresh must measure the
// pair again, and the upper points are bounded by gamma times the new gap).
TEST(WEFT_TEST_SUITE, proximity_refresh_measures_again_the_pairs_that_came_within_reach) {
  using Exec = WEFT_TEST_EXECSPACE;
  const real q = 0.011;
  TwoTriangles s(0.03, q);
  const real gamma = s.bs.gamma;
  const auto full = s.query(false, true);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(full(i), gamma * q, 1e-12) << "point " << i;
  for (const real up : {0.005, 0.02}) {
    std::vector<Vec3> moved = s.x0h;
    for (int i = 0; i < 3; ++i) moved[i].y += up;
    s.move_to(moved);
    const auto kept = s.query(true, true);
    for (int i = 3; i < 6; ++i) {
      const real expected = up < 0.01 ? gamma * q : gamma * (s.gap - up);
      EXPECT_NEAR(kept(i), expected, 1e-9) << "point " << i << " after " << up << " m";
    }
  }
}

// A still refresh (docs/collisions.md, "Still passes") measures no pair: while no point has moved more than
// still_distance since the last measured pass, its nearest distances, less four times the largest move R,
// bound the points. Two triangles 1 cm apart: the lower one moves up 50 µm (R, within 100 µm): the bounds
// are gamma (1 cm - 4 R), below gamma times the true gap. Moved 300 µm, the refresh measures the pair
// again.
TEST(WEFT_TEST_SUITE, proximity_still_refresh_bounds_by_the_last_distances_less_what_moved) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::BoundSettings settings;
  settings.still_distance = 1e-4;
  const real q = 0.011;
  TwoTriangles s(0.01, q, settings);
  const real gap = s.gap, gamma = s.bs.gamma;
  const auto full = s.query();
  EXPECT_FALSE(s.b.still());
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(full(i), gamma * gap, 1e-12) << "point " << i;
  for (const real up : {5e-5, 3e-4}) {
    std::vector<Vec3> moved = s.x0h;
    for (int i = 0; i < 3; ++i) moved[i].y += up;
    s.move_to(moved);
    const auto kept = s.query(true);
    const bool still = up <= settings.still_distance;
    EXPECT_EQ(s.b.still(), still) << up << " m";
    for (int i = 0; i < 6; ++i) {
      const real expected = still ? gamma * (gap - 4 * up) : gamma * (gap - up);
      EXPECT_NEAR(kept(i), std::min(expected, gamma * q - (i < 3 ? up : 0)), 1e-9) << "point " << i << " after " << up << " m";
      EXPECT_LE(kept(i), gamma * (gap - up) * (1 + 1e-12));
    }
  }
  // The distances of the pass that measured (3e-4 m) are the new reference: moving back down by 50 µm is still.
  std::vector<Vec3> back = s.x0h;
  for (int i = 0; i < 3; ++i) back[i].y += 2.5e-4;
  s.move_to(back);
  const auto again = s.query(true);
  EXPECT_TRUE(s.b.still());
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(again(i), gamma * (gap - 3e-4 - 4 * 5e-5), 1e-9) << "point " << i;
}

// With predicted_reference a point is bounded beside its own wanted move, not only the common translation.
// Two triangles 1 cm apart and a third 1 m away that stands still (it pulls the common translation down):
// - the two near ones both want 2 cm sideways: their moves differ by nothing, so they keep them (and the
//   far one stays), where without references every point is cut back beside the common translation;
// - they want 8 mm towards each other: their moves differ by more than half the gap, so the pair anchors
//   all six corners to the common translation, and the gap keeps (1 - 2 gamma) of itself.
struct ThreeTriangles {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  static constexpr real gap = 0.01, th = 0.001;
  std::vector<Vec3> x0h{{0, 0, 0},   {0.1, 0, 0},   {0, 0, 0.1},   {0.01, gap, 0.01}, {0.05, gap, 0.01},
                        {0.01, gap, 0.05}, {0, 1, 0}, {0.1, 1, 0}, {0, 1, 0.1}};
  Kokkos::View<int* [3], Mem> tris{"tris", 3};
  Kokkos::View<Vec3*, Mem> x0 = weft::test::to_device<Exec, Vec3>(x0h, "x0");
  Kokkos::View<real*, Mem> w = weft::test::to_device<Exec, real>(std::vector<real>(9, 1.0), "w");
  Kokkos::View<weft::IndexPair*, Mem> pairs = weft::test::to_device<Exec, weft::IndexPair>({{0, 1}}, "pairs");
  Kokkos::View<uint32_t*, Mem> hits{"hits", 1};
  weft::SideMesh<Mem> cloth;
  ThreeTriangles() {
    auto tm = Kokkos::create_mirror_view(tris);
    for (int t = 0; t < 3; ++t)
      for (int k = 0; k < 3; ++k) tm(t, k) = 3 * t + k;
    Kokkos::deep_copy(tris, tm);
    cloth.tris = tris;
    cloth.rmask = weft::test::to_device<Exec, uint8_t>({0x3F, 0x3F, 0x3F}, "rmask");
    cloth.thickness = weft::test::to_device<Exec, real>(std::vector<real>(9, th), "th");
  }
  // The first query of a substep whose prediction moves the near points by `lower` and `upper`: where the
  // points stand after its truncation, the points cut back and the points anchored.
  struct Result {
    std::vector<Vec3> x;
    long cut, anchored;
  };
  Result query(bool references, Vec3 lower, Vec3 upper) {
    weft::BoundSettings bs;
    bs.predicted_reference = references;
    const auto margins = weft::test::to_device<Exec, real>({0.02, 0.02, 0.02}, "margins");
    weft::DisplacementBounds<Exec> b(9, margins, margins, bs);
    std::vector<Vec3> wanted = x0h;
    for (int i = 0; i < 6; ++i) wanted[i] += i < 3 ? lower : upper;
    auto x = weft::test::to_device<Exec, Vec3>(wanted, "x");
    b.prepare(Exec(), x0, x, w, tris, /*first*/ true);
    cloth.x = cloth.xs = cloth.xo = b.x0();
    weft::NarrowSettings ns;
    ns.self = true;
    weft::PairCull<Exec> cull;
    Kokkos::View<const weft::IndexPair*, Mem> kept;
    long measured = 0;
    if (references) b.add_self_pairs_with_references(Exec(), cloth, pairs, 1, w, hits, ns, cull, kept, measured);
    else b.add_pairs(Exec(), cloth, cloth, pairs, 1, b.relative_end(), w, hits, ns);
    b.finish(Exec(), w);
    b.truncate_prediction(Exec(), x, w);
    Result r{std::vector<Vec3>(9), b.cut_count(Exec()), b.take_anchored()};
    const auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
    for (int i = 0; i < 9; ++i) r.x[size_t(i)] = xh(i);
    return r;
  }
};

TEST(WEFT_TEST_SUITE, proximity_references_keep_moves_that_keep_pairs_apart_and_anchor_those_that_close) {
  ThreeTriangles s;
  const real gamma = weft::BoundSettings{}.gamma;
  const Vec3 side{0.02, 0, 0};
  const auto with = s.query(true, side, side);
  EXPECT_EQ(with.cut, 0);
  EXPECT_EQ(with.anchored, 0);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(with.x[size_t(i)], s.x0h[size_t(i)] + side) << "point " << i;
  const auto without = s.query(false, side, side);
  EXPECT_EQ(without.cut, 9);  // the far triangle too: it stays, 1.3 cm beside the common translation
  const auto closing = s.query(true, Vec3{0, 0.008, 0}, Vec3{0, -0.008, 0});
  EXPECT_EQ(closing.anchored, 6);
  EXPECT_EQ(closing.cut, 6);
  real top = -1, bottom = 1;
  for (int i = 0; i < 6; ++i) {
    EXPECT_LE(weft::norm(closing.x[size_t(i)] - s.x0h[size_t(i)]), gamma * s.gap * (1 + 1e-9)) << "point " << i;
    if (i < 3) top = std::max(top, closing.x[size_t(i)].y); else bottom = std::min(bottom, closing.x[size_t(i)].y);
  }
  EXPECT_GE(bottom - top, (1 - 2 * gamma) * s.gap * (1 - 1e-9));
}

// Pinned points joined by the cloth's edges form a group, numbered by its lowest point; a pin with no
// pinned neighbour is in none. A 3 x 3 grid of points (8 triangles): the top row and the corner below it
// pinned, and the opposite corner alone.
TEST(WEFT_TEST_SUITE, pin_groups_join_pins_along_the_cloth_edges) {
  std::vector<std::array<int, 3>> tris;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      const int a = 3 * r + c;
      tris.push_back({a, a + 1, a + 4});
      tris.push_back({a, a + 4, a + 3});
    }
  std::vector<char> pinned{1, 1, 1, 0, 0, 1, 0, 0, 0};
  weft::PinGroups g = weft::pin_groups(tris, pinned);
  EXPECT_EQ(g.count, 1);
  EXPECT_EQ(g.group, (std::vector<int>{0, 0, 0, -1, -1, 0, -1, -1, -1}));
  pinned = {0, 0, 0, 0, 0, 0, 1, 0, 1};  // two corners of the bottom row, not joined by an edge
  g = weft::pin_groups(tris, pinned);
  EXPECT_EQ(g.count, 0);
  pinned = {0, 0, 1, 0, 0, 1, 1, 1, 0};  // two groups: {2, 5} and {6, 7}
  g = weft::pin_groups(tris, pinned);
  EXPECT_EQ(g.count, 2);
  EXPECT_EQ(g.group, (std::vector<int>{-1, -1, 0, -1, -1, 0, 1, 1, -1}));
}

// The twist winds the sheet into a rope: the contacts never converge in the schedule's iterations, yet
// nothing crosses and nothing is moved back. Pins reach their targets within their bounds like every other
// point, so they sit exactly on their animation until the rope jams next to them (from frame 28 at this
// coarse size with one early pass a substep, from frame 35 with four), and then trail it rather than drive
// the rope through itself. Each pinned edge is one pin
// group: held back, it stalls as a whole and stays straight, as its animation keeps it.
TEST(WEFT_TEST_SUITE, proximity_twist_never_crosses_and_pins_follow_until_it_jams) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("twist", {12});
  ASSERT_EQ(s.settings.collision.contact_model, weft::ContactModel::Proximity);  // the default
  std::vector<char> pinned(s.points.size(), 0);
  for (int k : s.kinematic_point) pinned[size_t(k)] = 1;
  const weft::PinGroups groups = weft::pin_groups(s.triangles, pinned);
  ASSERT_EQ(groups.count, 2);  // the two pinned edges
  std::vector<std::vector<int>> edge(2);
  for (size_t i = 0; i < s.points.size(); ++i)
    if (groups.group[i] >= 0) edge[size_t(groups.group[i])].push_back(int(i));
  weft::SimulationOn<Exec> sim(s);
  long passes = 0;
  weft::real lag = 0;
  for (int f = 0; f < 45; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    ASSERT_EQ(fs.collision.failsafe_points, 0);
    if (fs.frame <= 27) ASSERT_EQ(fs.max_pin_lag, 0.0) << "frame " << fs.frame;
    lag = std::max(lag, fs.max_pin_lag);
    passes += fs.schedule.collision_passes;
    if (f % 3 == 2 || f >= 33) ASSERT_EQ(sim.intersections(), 0) << "frame " << fs.frame;
    // Every pin of an edge on the line through its two ends (a lag under 1e-6 m snaps to the target).
    const std::vector<Vec3> x = sim.positions();
    for (const std::vector<int>& e : edge) {
      const Vec3 a = x[size_t(e.front())], u = weft::normalized(x[size_t(e.back())] - a);
      for (int p : e) {
        const Vec3 r = x[size_t(p)] - a;
        EXPECT_LT(weft::norm(r - weft::dot(r, u) * u), 1e-5) << "frame " << fs.frame << " pin " << p;
      }
    }
  }
  std::printf("twist at 12 x 12: largest pin lag over 45 frames %.3e m\n", lag);
  EXPECT_GT(lag, 0.0);
  EXPECT_GE(passes, 45 * s.settings.substeps * s.settings.collision_passes);
}

// The skirt's waistband is pinned to the swaying body: it tracks the body exactly, and the five layers
// stay free of intersections.
TEST(WEFT_TEST_SUITE, proximity_skirt_waistband_tracks_the_body_exactly) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("skirt", {6});
  weft::SimulationOn<Exec> sim(s);
  for (int f = 0; f < 12; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    ASSERT_EQ(fs.max_pin_lag, 0.0) << "frame " << fs.frame;
  }
  EXPECT_EQ(sim.intersections(), 0);
}

// A sheet hanging from two still corners, self collision on, swings below them: the corners never move
// (the bounds' common translation is the pins', 0 here). With the free points' mean instead, the swinging
// sheet dragged its corners 9 mm down within six frames at 24 x 24, and at 71 x 71 it came off its pins.
// Returns the positions' hash over the frames; `last`: the positions at the end.
uint64_t still_pins_stay(const weft::Scene& s, std::vector<Vec3>* last = nullptr) {
  using Exec = WEFT_TEST_EXECSPACE;
  const std::vector<int> corners = {0, 16};
  weft::SimulationOn<Exec> sim(s);
  uint64_t h = weft::hash_combine(0, sim.hash_positions());
  for (int f = 0; f < 12; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    h = weft::hash_combine(h, sim.hash_positions());
    EXPECT_EQ(fs.non_finite, 0);
    EXPECT_EQ(fs.max_pin_lag, 0.0) << "frame " << fs.frame;
    EXPECT_GT(fs.collision.queries, 0);
    const std::vector<Vec3> x = sim.positions();
    for (int c : corners)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(x[size_t(c)][k], s.points.position[size_t(c)][k]) << "frame " << fs.frame;
  }
  const std::vector<Vec3> x = sim.positions();
  EXPECT_LT(x[16 * 17][1], 0.9);  // the free edge has swung down
  if (last) *last = x;
  return h;
}

weft::Scene sheet_on_still_pins() {
  weft::Scene s = weft::io::make_builtin_scene("hanging-sheet", {16});
  s.settings.collision.self_collision = true;
  return s;
}

// Serial and OpenMP (the CLI hashes of this scene: CUDA too).
constexpr const char* kStillPinsHash = "417923cf2273fa43";

TEST(WEFT_TEST_SUITE, proximity_sheet_on_still_pins_never_moves_them) {
  EXPECT_EQ(weft::hash_hex(still_pins_stay(sheet_on_still_pins())), kStillPinsHash);
}

// The same with a still box in the sheet's way: colliders that do not move keep the pins' frame (only
// moving ones, which may push the cloth faster than its bounds let it follow, take the free points').
TEST(WEFT_TEST_SUITE, proximity_sheet_on_still_pins_beside_a_still_box_never_moves_them) {
  weft::Scene s = sheet_on_still_pins();
  const Vec3 lo{-0.3, 0.3, -0.45}, hi{0.3, 0.6, -0.25};
  const weft::io::Mesh box = weft::io::box(lo, hi);
  weft::Collider c;
  c.name = "box";
  c.triangles = box.tris;
  c.motion.frames = {box.x, box.x};  // stored twice, standing still
  c.thickness = 0.005;
  s.colliders.push_back(c);
  std::vector<Vec3> x;
  EXPECT_NE(weft::hash_hex(still_pins_stay(s, &x)), kStillPinsHash);  // the box was met
  for (const Vec3& p : x) {
    const real depth = std::min({p.x - lo.x, hi.x - p.x, p.y - lo.y, hi.y - p.y, p.z - lo.z, hi.z - p.z});
    EXPECT_LT(depth, 1e-3) << "point (" << p.x << ", " << p.y << ", " << p.z << ") inside the box";
  }
}

// A sheet dropped onto a sphere folds over it and onto itself.
void fold_sheet_without_intersections(weft::Scene s) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::SimulationOn<Exec> sim(s);
  ASSERT_TRUE(s.settings.collision.pair_refresh);  // the default
  long contacts = 0, passes = 0, queries = 0;
  for (int f = 0; f < 36; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    contacts = std::max(contacts, fs.collision.contacts);
    passes += fs.schedule.collision_passes;
    queries += fs.collision.queries;
    if (f % 6 == 5) ASSERT_EQ(sim.intersections(), 0) << "frame " << fs.frame;
  }
  EXPECT_GT(contacts, 0);
  EXPECT_LT(queries, passes);  // passes kept their pairs, and nothing crossed
}

TEST(WEFT_TEST_SUITE, proximity_folding_sheet_stays_free_of_intersections) {
  fold_sheet_without_intersections(weft::io::make_builtin_scene("drape-sphere", {14}));
}

// Query margins that grow no further than the nearest features (nearest_margins) give smaller bounds where
// the cloth is far from everything, never a crossing.
TEST(WEFT_TEST_SUITE, proximity_nearest_margins_fold_the_sheet_without_intersections) {
  weft::Scene s = weft::io::make_builtin_scene("drape-sphere", {14});
  s.settings.collision.nearest_margins = true;
  fold_sheet_without_intersections(s);
}

// Bounds beside each point's own wanted move (predicted_reference) let the falling sheet follow its
// prediction, and the pairs that close anchor their points: nothing crosses.
TEST(WEFT_TEST_SUITE, proximity_predicted_reference_folds_the_sheet_without_intersections) {
  weft::Scene s = weft::io::make_builtin_scene("drape-sphere", {14});
  s.settings.collision.predicted_reference = true;
  fold_sheet_without_intersections(s);
}

}  // namespace
