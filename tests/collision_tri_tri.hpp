// Discrete triangle-triangle intersection on hand-made cases, in every vertex order and on the device too;
// and counting over meshes: flat and smooth sheets have none, sheets through themselves or each other have
// exactly the brute-force pairs, on every backend; a mesh counted at changing positions (MeshIntersections)
// as if counted afresh each time.
#include "collision/mesh_intersections.hpp"
#include "collision/tri_tri.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace {

using weft::IndexPair;
using weft::Vec3;
using Tri = std::array<int, 3>;

template <class Exec>
Kokkos::View<int* [3], typename Exec::memory_space> triangles_to_device(const std::vector<Tri>& t) {
  Kokkos::View<int* [3], typename Exec::memory_space> d("tris", t.size());
  auto h = Kokkos::create_mirror_view(d);
  for (size_t i = 0; i < t.size(); ++i)
    for (int c = 0; c < 3; ++c) h(i, c) = t[i][c];
  Kokkos::deep_copy(d, h);
  return d;
}

struct Case {
  std::string name;
  std::array<Vec3, 3> a, b;
  bool expect;
};

// A generic rotation, so that flat configurations do not lie in coordinate planes.
Vec3 rotate(Vec3 p) {
  const double c1 = std::cos(0.7), s1 = std::sin(0.7), c2 = std::cos(1.1), s2 = std::sin(1.1);
  const Vec3 q{c1 * p.x - s1 * p.y, s1 * p.x + c1 * p.y, p.z};
  return {q.x, c2 * q.y - s2 * q.z, s2 * q.y + c2 * q.z};
}

std::vector<Case> cases() {
  const std::array<Vec3, 3> A{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 2, 0}};
  const Vec3 g0{0.1, 0.2, 0.3}, g1{1.7, -0.4, 0.9}, g2{0.3, 1.5, -0.6};
  const Vec3 gc = (g0 + g1 + g2) / 3, gn = weft::cross(g1 - g0, g2 - g0);
  std::vector<Case> v = {
      {"edge pierces face", A, {Vec3{0.5, 0.5, -1}, Vec3{0.5, 0.5, 1}, Vec3{3, 3, 0}}, true},
      {"face cuts through face", A, {Vec3{-1, 0.5, -1}, Vec3{3, 0.5, -1}, Vec3{1, 0.5, 2}}, true},
      {"parallel, apart", A, {Vec3{0, 0, 1}, Vec3{2, 0, 1}, Vec3{0, 2, 1}}, false},
      {"parallel, 1e-9 apart", A, {Vec3{0, 0, 1e-9}, Vec3{2, 0, 1e-9}, Vec3{0, 2, 1e-9}}, false},
      {"coplanar, separated", A, {Vec3{3, 3, 0}, Vec3{5, 3, 0}, Vec3{3, 5, 0}}, false},
      {"coplanar, overlapping", A, {Vec3{0.5, 0.5, 0}, Vec3{3, 0.5, 0}, Vec3{0.5, 3, 0}}, true},
      {"coplanar, contained", A, {Vec3{0.2, 0.2, 0}, Vec3{0.6, 0.2, 0}, Vec3{0.2, 0.6, 0}}, true},
      {"vertex touches face", A, {Vec3{0.5, 0.5, 0}, Vec3{0.5, 0.5, 1}, Vec3{1, 0.5, 1}}, true},
      {"vertex 1e-9 above face", A, {Vec3{0.5, 0.5, 1e-9}, Vec3{0.5, 0.5, 1}, Vec3{1, 0.5, 1}}, false},
      {"edge touches edge", A, {Vec3{1, 0, -1}, Vec3{1, 0, 1}, Vec3{1, -1, 0}}, true},
      {"edge 1e-9 beside edge", A, {Vec3{1, -1e-9, -1}, Vec3{1, -1e-9, 1}, Vec3{1, -1, 0}}, false},
      {"vertices touch", A, {Vec3{2, 0, 0}, Vec3{3, 0, 1}, Vec3{3, 1, 0}}, true},
      {"tilted, pierced at the centroid", {g0, g1, g2}, {gc - gn, gc + gn, gc + (g1 - g0)}, true},
      {"tilted, parallel above", {g0, g1, g2}, {g0 + 1e-6 * gn, g1 + 1e-6 * gn, g2 + 1e-6 * gn}, false},
  };
  // The separated coplanar cases again in a generic plane, where rounding leaves the points only nearly
  // coplanar. (Overlapping ones are not: rounded, they may truly lie a hair apart.)
  const size_t plain = v.size();
  for (size_t k = 0; k < plain; ++k)
    if (v[k].name.rfind("coplanar", 0) == 0 && !v[k].expect) {
      Case c = v[k];
      c.name += ", tilted";
      for (Vec3& p : c.a) p = rotate(p);
      for (Vec3& p : c.b) p = rotate(p);
      v.push_back(c);
    }
  return v;
}

// Triangles (s, a1, a2) and (s, b1, b2).
struct SharedCase {
  std::string name;
  Vec3 s, a1, a2, b1, b2;
  bool expect;
};

std::vector<SharedCase> shared_cases() {
  const Vec3 s{0, 0, 0};
  std::vector<SharedCase> v = {
      {"flat, opposite", s, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, false},
      {"flat, neighbours in a fan", s, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, false},
      {"flat, overlapping", s, {2, 0, 0}, {0, 2, 0}, {1, 0.2, 0}, {0.2, 1, 0}, true},
      {"folded through", s, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 1}, {0.5, 0.5, -1}, true},
      {"hinged apart", s, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 1}, false},
      {"along a common edge line", s, {2, 0, 0}, {0, 2, 0}, {1, 0, 1}, {1, 0, -1}, true},
  };
  const size_t plain = v.size();
  for (size_t k = 0; k < plain; ++k)
    if (v[k].name.rfind("flat", 0) == 0 && !v[k].expect) {
      SharedCase c = v[k];
      c.name += ", tilted";
      c.s = rotate(c.s), c.a1 = rotate(c.a1), c.a2 = rotate(c.a2), c.b1 = rotate(c.b1), c.b2 = rotate(c.b2);
      v.push_back(c);
    }
  return v;
}

// Every order of a case: A and B swapped, each cyclically rotated and reversed (72 orders).
std::vector<std::array<Vec3, 6>> orders(const Case& c) {
  std::vector<std::array<Vec3, 6>> out;
  for (int swap = 0; swap < 2; ++swap)
    for (int ra = 0; ra < 6; ++ra)
      for (int rb = 0; rb < 6; ++rb) {
        const auto& x = swap ? c.b : c.a;
        const auto& y = swap ? c.a : c.b;
        const auto pick = [](const std::array<Vec3, 3>& t, int r, int k) {
          return r < 3 ? t[(r + k) % 3] : t[(r + 3 - k) % 3];
        };
        out.push_back({pick(x, ra, 0), pick(x, ra, 1), pick(x, ra, 2), pick(y, rb, 0), pick(y, rb, 1), pick(y, rb, 2)});
      }
  return out;
}

// Every order of a shared case: triangles swapped, each's two other vertices swapped (8 orders).
std::vector<std::array<Vec3, 5>> orders(const SharedCase& c) {
  std::vector<std::array<Vec3, 5>> out;
  for (int swap = 0; swap < 2; ++swap)
    for (int fa = 0; fa < 2; ++fa)
      for (int fb = 0; fb < 2; ++fb) {
        const Vec3 a1 = swap ? c.b1 : c.a1, a2 = swap ? c.b2 : c.a2, b1 = swap ? c.a1 : c.b1, b2 = swap ? c.a2 : c.b2;
        out.push_back({c.s, fa ? a2 : a1, fa ? a1 : a2, fb ? b2 : b1, fb ? b1 : b2});
      }
  return out;
}

TEST(WEFT_TEST_SUITE, tri_tri_hand_made_cases_on_host_and_device) {
  using Exec = WEFT_TEST_EXECSPACE;
  std::vector<Vec3> pts;
  std::vector<int> expect;
  std::vector<std::string> names;
  for (const Case& c : cases())
    for (const auto& o : orders(c)) {
      EXPECT_EQ(weft::triangles_intersect(o[0], o[1], o[2], o[3], o[4], o[5]), c.expect) << c.name;
      pts.insert(pts.end(), o.begin(), o.end());
      pts.push_back(Vec3{});  // a shared case takes 5 points, a general one 6: pad to 7
      expect.push_back(c.expect);
      names.push_back(c.name);
    }
  const size_t general = expect.size();
  for (const SharedCase& c : shared_cases())
    for (const auto& o : orders(c)) {
      EXPECT_EQ(weft::triangles_intersect_sharing_vertex(o[0], o[1], o[2], o[3], o[4]), c.expect) << c.name;
      EXPECT_TRUE(weft::triangles_intersect(o[0], o[1], o[2], o[0], o[3], o[4])) << c.name << ": they meet at s";
      pts.insert(pts.end(), o.begin(), o.end());
      pts.insert(pts.end(), 2, Vec3{});
      expect.push_back(c.expect);
      names.push_back(c.name);
    }
  // The same answers from a kernel.
  const auto x = weft::test::to_device<Exec>(pts);
  Kokkos::View<int*, Exec::memory_space> got("got", expect.size());
  Kokkos::parallel_for(
      Kokkos::RangePolicy<Exec>(0, expect.size()), KOKKOS_LAMBDA(long k) {
        const long o = 7 * k;
        got(k) = k < long(general) ? weft::triangles_intersect(x(o), x(o + 1), x(o + 2), x(o + 3), x(o + 4), x(o + 5))
                                   : weft::triangles_intersect_sharing_vertex(x(o), x(o + 1), x(o + 2), x(o + 3), x(o + 4));
      });
  const auto h = weft::test::to_host(got);
  for (size_t k = 0; k < expect.size(); ++k) EXPECT_EQ(h[k], expect[k]) << names[k] << " (device)";
}

struct Mesh {
  std::vector<Vec3> x;
  std::vector<Tri> tris;
};

// (nu x nv) quads, vertex (i, j) at f(i / nu, j / nv), split along alternating diagonals.
template <class F>
Mesh grid(int nu, int nv, F f) {
  Mesh m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) m.x.push_back(f(double(i) / nu, double(j) / nv));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int v00 = j * (nu + 1) + i, v10 = v00 + 1, v01 = v00 + nu + 1, v11 = v01 + 1;
      if ((i + j) % 2 == 0) {
        m.tris.push_back({v00, v10, v11});
        m.tris.push_back({v00, v11, v01});
      } else {
        m.tris.push_back({v00, v10, v01});
        m.tris.push_back({v10, v11, v01});
      }
    }
  return m;
}

// Brute force over every pair with the same rules, as (i, j) lists in the order the query documents.
std::vector<IndexPair> brute_self(const Mesh& m, const std::vector<uint32_t>& leaves) {
  Kokkos::View<Vec3*, Kokkos::HostSpace> x("x", m.x.size());
  Kokkos::View<int* [3], Kokkos::HostSpace> t("t", m.tris.size());
  for (size_t i = 0; i < m.x.size(); ++i) x(i) = m.x[i];
  for (size_t i = 0; i < m.tris.size(); ++i)
    for (int c = 0; c < 3; ++c) t(i, c) = m.tris[i][c];
  const weft::MeshTrianglesMeet<Kokkos::HostSpace> meet{x, t};
  std::vector<IndexPair> out;
  for (size_t k = 0; k < leaves.size(); ++k)  // each pair from its earlier leaf, written (smaller, larger)
    for (size_t l = k + 1; l < leaves.size(); ++l) {
      const int i = int(std::min(leaves[k], leaves[l])), j = int(std::max(leaves[k], leaves[l]));
      if (meet(i, j)) out.push_back({i, j});
    }
  return out;
}

template <class Exec>
void expect_self_count(const Mesh& m, long expect_count, const std::string& what) {
  using Mem = typename Exec::memory_space;
  const auto x = weft::test::to_device<Exec>(m.x);
  const auto t = triangles_to_device<Exec>(m.tris);
  weft::Lbvh<Exec> bvh;
  Kokkos::View<IndexPair*, Mem> pairs;
  const long count = weft::count_intersections(bvh, x, t, pairs);
  const auto expect = brute_self(m, weft::test::to_host(bvh.leaf_primitives()));
  ASSERT_EQ(count, long(expect.size())) << what;
  const auto h = weft::test::to_host(pairs);
  for (long k = 0; k < count; ++k)
    EXPECT_TRUE(h[k].first == expect[k].first && h[k].second == expect[k].second) << what << " pair " << k;
  EXPECT_EQ(weft::count_intersections(bvh, x, t), count) << what;
  if (expect_count >= 0) EXPECT_EQ(count, expect_count) << what;
  else EXPECT_GT(count, 0) << what;
}

TEST(WEFT_TEST_SUITE, tri_tri_sheets_without_intersections) {
  using Exec = WEFT_TEST_EXECSPACE;
  expect_self_count<Exec>(grid(20, 20, [](double u, double v) { return Vec3{u, v, 0}; }), 0, "flat grid");
  expect_self_count<Exec>(grid(17, 23, [](double u, double v) { return rotate(Vec3{1.3 * u, 0.7 * v, 0.25}); }), 0,
                          "tilted flat grid");
  expect_self_count<Exec>(
      grid(30, 30, [](double u, double v) { return Vec3{u, v, 0.1 * std::sin(6 * u) * std::cos(4 * v)}; }), 0,
      "smooth bumpy sheet");
  expect_self_count<Exec>(Mesh{}, 0, "no triangles");
  expect_self_count<Exec>(grid(1, 1, [](double u, double v) { return Vec3{u, v, 0}; }), 0, "two triangles");
}

TEST(WEFT_TEST_SUITE, tri_tri_sheet_through_itself) {
  using Exec = WEFT_TEST_EXECSPACE;
  // The nodal cubic x = t^2 - 1, z = t^3 - t crosses itself at t = +-1, swept along y; no grid line falls on
  // the crossing.
  expect_self_count<Exec>(grid(41, 6,
                               [](double u, double v) {
                                 const double t = -1.6 + 3.2 * u;
                                 return Vec3{t * t - 1, v, t * t * t - t};
                               }),
                          -1, "looped sheet");
  // A grid folded back through itself: the far half dives through the near one (between grid lines).
  expect_self_count<Exec>(grid(24, 8,
                               [](double u, double v) {
                                 return u < 0.5 ? Vec3{u, v, 0} : Vec3{1 - u + 0.1 * (u - 0.5), v, 0.1 - 0.55 * (u - 0.5)};
                               }),
                          -1, "grid folded through itself");
}

// MeshIntersections keeps the triangles and the tree from call to call: flat, looped, flat again give the
// counts of a fresh tree each time.
TEST(WEFT_TEST_SUITE, tri_tri_mesh_counted_at_changing_positions) {
  using Exec = WEFT_TEST_EXECSPACE;
  const Mesh flat = grid(41, 6, [](double u, double v) { return Vec3{u, v, 0}; });
  const Mesh looped = grid(41, 6, [](double u, double v) {
    const double t = -1.6 + 3.2 * u;
    return Vec3{t * t - 1, v, t * t * t - t};
  });
  weft::MeshIntersections<Exec> mesh(flat.tris);
  EXPECT_EQ(mesh.count(flat.x), 0);
  weft::Lbvh<Exec> fresh;
  const long loops = weft::count_intersections(fresh, weft::test::to_device<Exec>(looped.x),
                                               triangles_to_device<Exec>(looped.tris));
  EXPECT_GT(loops, 0);
  EXPECT_EQ(mesh.count(looped.x), loops);
  EXPECT_EQ(mesh.count(flat.x), 0);
}

TEST(WEFT_TEST_SUITE, tri_tri_two_meshes) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  const Mesh a = grid(12, 12, [](double u, double v) { return Vec3{u, v, 0}; });
  for (const double shift : {0.0, 2.0}) {
    const Mesh b = grid(5, 7, [shift](double u, double v) { return Vec3{0.13 + 0.7 * u + shift, 0.45, -0.5 + 1.1 * v}; });
    const std::string what = "vertical sheet shifted by " + std::to_string(shift);
    const auto xa = weft::test::to_device<Exec>(a.x), xb = weft::test::to_device<Exec>(b.x);
    const auto ta = triangles_to_device<Exec>(a.tris), tb = triangles_to_device<Exec>(b.tris);
    weft::Lbvh<Exec> bvh;
    Kokkos::View<IndexPair*, Mem> pairs;
    const long count = weft::count_intersections(bvh, xa, ta, xb, tb, pairs);
    const auto leaves = weft::test::to_host(bvh.leaf_primitives());
    std::vector<IndexPair> expect;
    for (int i = 0; i < int(a.tris.size()); ++i)
      for (uint32_t j : leaves) {
        const Tri &p = a.tris[i], &q = b.tris[j];
        if (weft::triangles_intersect(a.x[p[0]], a.x[p[1]], a.x[p[2]], b.x[q[0]], b.x[q[1]], b.x[q[2]]))
          expect.push_back({i, int(j)});
      }
    ASSERT_EQ(count, long(expect.size())) << what;
    const auto h = weft::test::to_host(pairs);
    for (long k = 0; k < count; ++k)
      EXPECT_TRUE(h[k].first == expect[k].first && h[k].second == expect[k].second) << what << " pair " << k;
    EXPECT_EQ(weft::count_intersections(bvh, xa, ta, xb, tb), count) << what;
    if (shift == 0) EXPECT_GT(count, 0) << what;
    else EXPECT_EQ(count, 0) << what;
  }
}

}  // namespace
