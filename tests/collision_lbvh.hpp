// The LBVH broad phase against brute force: leaf order, tree structure, self and cross queries in their
// documented order (hashes equal to the host's), refit, growing outputs, a degenerate input; and on real
// data, the cloth-funnel step's labelled collisions covered by the swept-box self query.
#include "collision/lbvh.hpp"
#include "core/hash.hpp"
#include "io/ply.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <unordered_set>
#include <vector>

namespace {

using weft::Aabb;
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

// Triangles moving linearly from x0 to x1, each with a margin.
struct Soup {
  std::vector<Vec3> x0, x1;
  std::vector<Tri> tris;
  std::vector<double> margin;
};

// n separate triangles scattered in the unit cube, sized so that each box overlaps a few others.
Soup random_soup(int n, uint64_t seed) {
  weft::test::TestRng rng(seed);
  const double r = 0.5 / std::cbrt(double(n) + 1);
  Soup s;
  for (int t = 0; t < n; ++t) {
    const Vec3 c{rng.uniform(), rng.uniform(), rng.uniform()};
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = c + Vec3{rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r)};
      s.x0.push_back(p);
      s.x1.push_back(p + Vec3{rng.uniform(-r / 2, r / 2), rng.uniform(-r / 2, r / 2), rng.uniform(-r / 2, r / 2)});
    }
    s.tris.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    s.margin.push_back(rng.uniform(0, r / 4));
  }
  return s;
}

// An n x n quad grid over the unit square, folded back over itself about u = 0.5 around a cylinder of
// radius 0.002 (the halves 0.004 apart, about the sum of two margins), moving a little during the step.
Soup folded_grid(int n, uint64_t seed) {
  weft::test::TestRng rng(seed);
  const double rho = 0.002, pi = 3.14159265358979323846;
  Soup s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = n > 0 ? double(i) / n : 0, v = n > 0 ? double(j) / n : 0, d = u - 0.5;
      const Vec3 p = d <= 0 ? Vec3{u, v, 0}
                     : d < pi * rho ? Vec3{0.5 + rho * std::sin(d / rho), v, rho * (1 - std::cos(d / rho))}
                                    : Vec3{0.5 - (d - pi * rho), v, 2 * rho};
      s.x0.push_back(p);
      s.x1.push_back(p + Vec3{rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v00 = j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
      s.tris.push_back({v00, v10, v11});
      s.tris.push_back({v00, v11, v01});
    }
  s.margin.assign(s.tris.size(), 2e-3);
  return s;
}

std::vector<Aabb> host_boxes(const Soup& s) {
  std::vector<Aabb> b;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    const Tri& v = s.tris[t];
    b.push_back(weft::swept_triangle_box(s.x0[v[0]], s.x0[v[1]], s.x0[v[2]], s.x1[v[0]], s.x1[v[1]], s.x1[v[2]],
                                         s.margin[t]));
  }
  return b;
}

template <class Exec>
Kokkos::View<Aabb*, typename Exec::memory_space> device_boxes(const Soup& s) {
  Kokkos::View<Aabb*, typename Exec::memory_space> boxes("boxes", s.tris.size());
  weft::swept_triangle_boxes(Exec(), weft::test::to_device<Exec>(s.x0), weft::test::to_device<Exec>(s.x1),
                             triangles_to_device<Exec>(s.tris), weft::test::to_device<Exec>(s.margin), boxes);
  return boxes;
}

bool same_bits(const Aabb& a, const Aabb& b) {
  for (int c = 0; c < 3; ++c)
    if (weft::test::bits(a.lo[c]) != weft::test::bits(b.lo[c]) || weft::test::bits(a.hi[c]) != weft::test::bits(b.hi[c]))
      return false;
  return true;
}

// Leaf order the build must produce: primitives sorted by (Morton code of the centre, index).
std::vector<uint32_t> expected_leaf_order(const std::vector<Aabb>& boxes) {
  Aabb bounds = weft::empty_aabb();
  for (const Aabb& b : boxes) bounds = weft::expand(bounds, weft::centre(b));
  std::vector<uint64_t> keys;
  for (size_t i = 0; i < boxes.size(); ++i)
    keys.push_back(weft::morton_key(weft::morton30(weft::centre(boxes[i]), bounds), uint32_t(i)));
  std::sort(keys.begin(), keys.end());
  std::vector<uint32_t> order;
  for (uint64_t k : keys) order.push_back(uint32_t(k & 0xFFFFFFFFu));
  return order;
}

// Brute force in the documented orders. Self: each pair from its earlier leaf, by that leaf, then the later
// one (leaf order), written (smaller index, larger). Cross: by query, then the primitive's leaf.
template <class Pred>
std::vector<IndexPair> brute_self(const std::vector<Aabb>& boxes, const std::vector<uint32_t>& leaves, Pred pred) {
  std::vector<IndexPair> out;
  for (size_t k = 0; k < leaves.size(); ++k)
    for (size_t l = k + 1; l < leaves.size(); ++l) {
      const int i = int(std::min(leaves[k], leaves[l])), j = int(std::max(leaves[k], leaves[l]));
      if (weft::overlaps(boxes[i], boxes[j]) && pred(i, j)) out.push_back({i, j});
    }
  return out;
}

template <class Pred>
std::vector<IndexPair> brute_cross(const std::vector<Aabb>& queries, const std::vector<Aabb>& boxes,
                                   const std::vector<uint32_t>& leaves, Pred pred) {
  std::vector<IndexPair> out;
  for (int q = 0; q < int(queries.size()); ++q)
    for (uint32_t j : leaves)
      if (weft::overlaps(queries[q], boxes[j]) && pred(q, int(j))) out.push_back({q, int(j)});
  return out;
}

struct DropSumMultipleOf3 {
  KOKKOS_INLINE_FUNCTION bool operator()(int a, int b) const { return (a + b) % 3 != 0; }
};

// pairs[0, count) equals expect exactly, and so does its hash (the same on every backend).
template <class Exec>
void expect_pairs(const Kokkos::View<IndexPair*, typename Exec::memory_space>& pairs, long count,
                  const std::vector<IndexPair>& expect, const std::string& what) {
  ASSERT_EQ(count, long(expect.size())) << what;
  ASSERT_GE(long(pairs.extent(0)), count) << what;
  const auto got = Kokkos::subview(pairs, std::make_pair(0L, count));
  const auto h = weft::test::to_host(got);
  for (long k = 0; k < count; ++k)
    ASSERT_TRUE(h[k].first == expect[k].first && h[k].second == expect[k].second)
        << what << " pair " << k << ": (" << h[k].first << ", " << h[k].second << ") expected (" << expect[k].first
        << ", " << expect[k].second << ")";
  const Kokkos::View<const IndexPair*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> ref(expect.data(),
                                                                                                      expect.size());
  EXPECT_EQ(weft::hash_view(Exec(), got), weft::hash_view(Kokkos::DefaultHostExecutionSpace(), ref)) << what;
}

// The tree's structure: leaves in key order with their exact boxes, each float box holding its exact box
// (leaves) or the merge of its children's (internal nodes), every node met once by a walk along first-child
// links and ropes (leaves in tree order), depth at most 64. Returns the depth.
template <class Exec>
int check_tree(const weft::Lbvh<Exec>& bvh, const std::vector<Aabb>& boxes, const std::string& what) {
  const auto t = bvh.nodes();
  const int n = t.n;
  EXPECT_EQ(n, int(boxes.size())) << what;
  if (n == 0) return 0;
  const auto node = weft::test::to_host(t.node);
  const auto leaf_box = weft::test::to_host(t.leaf_box);
  const auto prim = weft::test::to_host(t.primitive);
  const int first_leaf = n - 1;
  const auto holds = [](const weft::LbvhNode& f, const Aabb& b) {
    for (int c = 0; c < 3; ++c)
      if (!(f.lo[c] <= b.lo[c] && b.hi[c] <= f.hi[c])) return false;
    return true;
  };
  for (int k = 0; k < n; ++k) {
    EXPECT_TRUE(same_bits(leaf_box[k], boxes[prim[k]])) << what << " leaf " << k;
    EXPECT_EQ(node[first_leaf + k].child, int(prim[k])) << what << " leaf " << k;
    EXPECT_TRUE(holds(node[first_leaf + k], leaf_box[k])) << what << " leaf " << k;
  }
  for (int i = 0; i < first_leaf; ++i) {
    const int l = node[i].child, r = node[l].rope;  // the right child follows the left child's subtree
    if (r < 0) {
      ADD_FAILURE() << what << " node " << i << ": no right child";
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(node[i].lo[c], std::min(node[l].lo[c], node[r].lo[c])) << what << " node " << i;
      EXPECT_EQ(node[i].hi[c], std::max(node[l].hi[c], node[r].hi[c])) << what << " node " << i;
    }
  }
  std::vector<int> depth(2 * n - 1, -1);
  depth[0] = 0;
  int visited = 0, next_leaf = first_leaf, max_depth = 0;
  for (int x = 0; x >= 0; x = x < first_leaf ? node[x].child : node[x].rope) {
    ++visited;
    EXPECT_GE(depth[x], 0) << what;
    max_depth = std::max(max_depth, depth[x]);
    if (x < first_leaf) {
      depth[node[x].child] = depth[node[node[x].child].rope] = depth[x] + 1;
    } else {
      EXPECT_EQ(x, next_leaf++) << what;
    }
    if (visited > 2 * n) break;
  }
  EXPECT_EQ(visited, 2 * n - 1) << what;
  EXPECT_LE(max_depth, 64) << what;
  return max_depth;
}

template <class Exec>
void check_self_and_cross(const Soup& s, const Soup& queries_soup, const std::string& what) {
  using Mem = typename Exec::memory_space;
  const auto boxes = device_boxes<Exec>(s);
  const auto hboxes = host_boxes(s);
  const auto dboxes = weft::test::to_host(boxes);
  for (size_t t = 0; t < hboxes.size(); ++t) ASSERT_TRUE(same_bits(dboxes[t], hboxes[t])) << what << " box " << t;

  weft::Lbvh<Exec> bvh;
  bvh.build(boxes);
  const auto leaves = weft::test::to_host(bvh.leaf_primitives());
  EXPECT_EQ(leaves, expected_leaf_order(hboxes)) << what;
  check_tree(bvh, hboxes, what);

  Kokkos::View<IndexPair*, Mem> pairs;
  long count = bvh.query_self(weft::KeepAllPairs{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_self(hboxes, leaves, weft::KeepAllPairs{}), what + " self");
  EXPECT_EQ(bvh.count_self(weft::KeepAllPairs{}), count) << what;
  count = bvh.query_self(DropSumMultipleOf3{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_self(hboxes, leaves, DropSumMultipleOf3{}), what + " self filtered");
  EXPECT_EQ(bvh.count_self(DropSumMultipleOf3{}), count) << what;
  // Every leaf against every later one (the device's self query for small trees): the same pairs in order.
  count = bvh.query_self_all_later(weft::KeepAllPairs{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_self(hboxes, leaves, weft::KeepAllPairs{}), what + " self, all later leaves");
  count = bvh.query_self_all_later(DropSumMultipleOf3{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_self(hboxes, leaves, DropSumMultipleOf3{}),
                     what + " self filtered, all later leaves");

  const auto qboxes = device_boxes<Exec>(queries_soup);
  const auto hq = host_boxes(queries_soup);
  count = bvh.query(qboxes, weft::KeepAllPairs{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_cross(hq, hboxes, leaves, weft::KeepAllPairs{}), what + " cross");
  EXPECT_EQ(bvh.count(qboxes, weft::KeepAllPairs{}), count) << what;
  count = bvh.query(qboxes, DropSumMultipleOf3{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_cross(hq, hboxes, leaves, DropSumMultipleOf3{}), what + " cross filtered");
}

TEST(WEFT_TEST_SUITE, lbvh_morton_codes) {
  EXPECT_EQ(weft::morton_spread10(0x3FFu), 0x09249249u);
  EXPECT_EQ(weft::morton_spread10(0b101u), 0b1000001u);
  const Aabb unit{{0, 0, 0}, {1, 1, 1}};
  EXPECT_EQ(weft::morton30({0, 0, 0}, unit), 0u);
  EXPECT_EQ(weft::morton30({1, 1, 1}, unit), 0x3FFFFFFFu);
  EXPECT_EQ(weft::morton30({1, 0, 0}, unit), 0x24924924u);  // x takes the highest bit of each triple
  EXPECT_EQ(weft::morton30({0, 0, 1}, unit), 0x09249249u);
  EXPECT_EQ(weft::morton30({-5, 7, std::nan("")}, unit), weft::morton30({0, 1, 0}, unit));  // clamped; NaN -> 0
  EXPECT_EQ(weft::morton30({3, 3, 3}, Aabb{{3, 3, 3}, {3, 3, 3}}), 0u);                    // flat bounds
  EXPECT_EQ(weft::morton_key(5u, 7u), (uint64_t(5) << 32) | 7u);
  EXPECT_EQ(weft::clz64(0), 64);
  EXPECT_EQ(weft::clz64(1), 63);
  EXPECT_EQ(weft::clz64(uint64_t(1) << 63), 0);
}

TEST(WEFT_TEST_SUITE, lbvh_swept_boxes_hold_both_positions) {
  using Exec = WEFT_TEST_EXECSPACE;
  const Soup s = random_soup(200, 11);
  const auto dboxes = weft::test::to_host(device_boxes<Exec>(s));
  for (size_t t = 0; t < s.tris.size(); ++t) {
    const double m = s.margin[t];
    for (int k = 0; k < 3; ++k)
      for (const Vec3& p : {s.x0[s.tris[t][k]], s.x1[s.tris[t][k]]})
        for (int c = 0; c < 3; ++c) {
          EXPECT_LE(dboxes[t].lo[c], p[c] - m);
          EXPECT_GE(dboxes[t].hi[c], p[c] + m);
        }
  }
  // One margin for all: the per-triangle kernel with that margin everywhere.
  Kokkos::View<Aabb*, Exec::memory_space> boxes("boxes", s.tris.size());
  weft::swept_triangle_boxes(Exec(), weft::test::to_device<Exec>(s.x0), weft::test::to_device<Exec>(s.x1),
                             triangles_to_device<Exec>(s.tris), 0.25, boxes);
  Soup same = s;
  same.margin.assign(s.tris.size(), 0.25);
  const auto expect = host_boxes(same);
  const auto got = weft::test::to_host(boxes);
  for (size_t t = 0; t < s.tris.size(); ++t) EXPECT_TRUE(same_bits(got[t], expect[t])) << t;
}

TEST(WEFT_TEST_SUITE, lbvh_queries_match_brute_force_on_triangle_soups) {
  using Exec = WEFT_TEST_EXECSPACE;
  for (int n : {0, 1, 2, 3, 5, 64, 1000, 2500})
    check_self_and_cross<Exec>(random_soup(n, 100 + n), random_soup(n / 2 + 3, 900 + n), "soup n=" + std::to_string(n));
  // Boxes that overlap most others: queries with more pairs than the counting walk keeps (32).
  Soup dense = random_soup(150, 5), dense_queries = random_soup(60, 6);
  dense.margin.assign(dense.margin.size(), 0.3);
  dense_queries.margin.assign(dense_queries.margin.size(), 0.2);
  check_self_and_cross<Exec>(dense, dense_queries, "dense soup");
  // Queries against an empty tree, and no queries at all.
  check_self_and_cross<Exec>(random_soup(0, 1), random_soup(10, 2), "empty tree");
  check_self_and_cross<Exec>(random_soup(50, 3), random_soup(0, 4), "no queries");
}

TEST(WEFT_TEST_SUITE, lbvh_queries_match_brute_force_on_folded_grids) {
  using Exec = WEFT_TEST_EXECSPACE;
  for (int n : {0, 1, 2, 9, 32})
    check_self_and_cross<Exec>(folded_grid(n, 7 + n), random_soup(40, 70 + n), "grid n=" + std::to_string(n));
}

TEST(WEFT_TEST_SUITE, lbvh_refit_matches_rebuild) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  const std::vector<std::pair<std::string, Soup>> cases = {{"one triangle", random_soup(1, 5)},
                                                           {"grid 1", folded_grid(1, 5)},
                                                           {"grid 18", folded_grid(18, 6)},
                                                           {"soup 700", random_soup(700, 7)}};
  for (const auto& [what, before] : cases) {
    Soup after = before;  // the next step: starts where this one ends
    weft::test::TestRng rng(77);
    after.x0 = before.x1;
    for (Vec3& p : after.x1) p = p + Vec3{rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)};

    weft::Lbvh<Exec> refitted;
    refitted.build(device_boxes<Exec>(before));
    const auto leaves = weft::test::to_host(refitted.leaf_primitives());
    refitted.refit(device_boxes<Exec>(after));
    EXPECT_EQ(weft::test::to_host(refitted.leaf_primitives()), leaves) << what;  // same topology
    const auto hafter = host_boxes(after);
    check_tree(refitted, hafter, what);
    Kokkos::View<IndexPair*, Mem> pairs;
    const long count = refitted.query_self(weft::KeepAllPairs{}, pairs);
    expect_pairs<Exec>(pairs, count, brute_self(hafter, leaves, weft::KeepAllPairs{}), what);

    // A tree built on the new boxes finds the same pairs (in its own leaf order).
    weft::Lbvh<Exec> rebuilt;
    rebuilt.build(device_boxes<Exec>(after));
    Kokkos::View<IndexPair*, Mem> rebuilt_pairs;
    const long rebuilt_count = rebuilt.query_self(weft::KeepAllPairs{}, rebuilt_pairs);
    ASSERT_EQ(rebuilt_count, count) << what;
    const auto key = [](const IndexPair& p) { return (uint64_t(p.first) << 32) | uint32_t(p.second); };
    std::vector<uint64_t> a, b;
    const auto ha = weft::test::to_host(pairs), hb = weft::test::to_host(rebuilt_pairs);
    for (long k = 0; k < count; ++k) {
      a.push_back(key(ha[k]));
      b.push_back(key(hb[k]));
    }
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << what;
  }
}

TEST(WEFT_TEST_SUITE, lbvh_output_buffer_grows_and_is_reused) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  const Soup s = random_soup(300, 21);
  weft::Lbvh<Exec> bvh;
  bvh.build(device_boxes<Exec>(s));
  const auto leaves = weft::test::to_host(bvh.leaf_primitives());
  const auto expect = brute_self(host_boxes(s), leaves, weft::KeepAllPairs{});
  ASSERT_GT(expect.size(), 10u);
  Kokkos::View<IndexPair*, Mem> pairs("pairs", 1);  // too small: grows, drops nothing
  const long count = bvh.query_self(weft::KeepAllPairs{}, pairs);
  expect_pairs<Exec>(pairs, count, expect, "grown");
  const IndexPair* storage = pairs.data();
  EXPECT_EQ(bvh.query_self(DropSumMultipleOf3{}, pairs), long(brute_self(host_boxes(s), leaves, DropSumMultipleOf3{}).size()));
  EXPECT_EQ(pairs.data(), storage);  // large enough: kept
  EXPECT_EQ(pairs.label(), "pairs");
}

// Keeps about one pair in 97.
struct KeepSumMultipleOf97 {
  KOKKOS_INLINE_FUNCTION bool operator()(int a, int b) const { return (a + b) % 97 == 0; }
};

// A self query after another on the same tree walks once, into slots sized from the last query's counts;
// leaves that find more than their slots hold walk again. Either way the pairs and their order are those
// of a first query.
TEST(WEFT_TEST_SUITE, lbvh_self_query_after_another_finds_the_same_pairs) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  const Soup s = random_soup(700, 7);
  weft::Lbvh<Exec> bvh;
  bvh.build(device_boxes<Exec>(s));
  const auto leaves = weft::test::to_host(bvh.leaf_primitives());
  const auto all = brute_self(host_boxes(s), leaves, weft::KeepAllPairs{});
  const auto sparse = brute_self(host_boxes(s), leaves, KeepSumMultipleOf97{});
  ASSERT_GT(all.size(), 8 * sparse.size() + 100);
  Kokkos::View<IndexPair*, Mem> pairs;
  long count = bvh.query_self(KeepSumMultipleOf97{}, pairs);  // small counts: the next query overflows
  expect_pairs<Exec>(pairs, count, sparse, "sparse first");
  count = bvh.query_self(weft::KeepAllPairs{}, pairs);
  expect_pairs<Exec>(pairs, count, all, "all after sparse");
  count = bvh.query_self(weft::KeepAllPairs{}, pairs);  // room for every leaf now
  expect_pairs<Exec>(pairs, count, all, "all again");
  count = bvh.query_self(DropSumMultipleOf3{}, pairs);
  expect_pairs<Exec>(pairs, count, brute_self(host_boxes(s), leaves, DropSumMultipleOf3{}), "filtered after all");
}

// All boxes identical: every code is equal, the index bits alone shape the tree. Each query meets every
// leaf; the predicate keeps a sparse, known subset.
struct SumMultipleOf997 {
  KOKKOS_INLINE_FUNCTION bool operator()(int a, int b) const { return (a + b) % 997 == 0; }
};

TEST(WEFT_TEST_SUITE, lbvh_identical_boxes) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  const int n = 10000;
  const std::vector<Aabb> hboxes(n, Aabb{{0.25, 0.5, 0.75}, {1, 1, 1}});
  weft::Lbvh<Exec> bvh;
  bvh.build(weft::test::to_device<Exec>(hboxes));
  const auto leaves = weft::test::to_host(bvh.leaf_primitives());
  for (int k = 0; k < n; ++k) ASSERT_EQ(leaves[k], uint32_t(k));  // equal codes: index order
  const int depth = check_tree(bvh, hboxes, "identical");
  EXPECT_LE(depth, 15);  // 14 index bits: a balanced tree
  Kokkos::View<IndexPair*, Mem> pairs;
  const long count = bvh.query_self(SumMultipleOf997{}, pairs);
  std::vector<IndexPair> expect;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if ((i + j) % 997 == 0) expect.push_back({i, j});
  expect_pairs<Exec>(pairs, count, expect, "identical");
}

// Real data: one step of a cloth falling into a funnel, with exact collision labels for candidate
// vertex-face and edge-edge pairs (see the README beside the data). Every pair labelled colliding must have
// a triangle holding each of its elements whose swept boxes overlap (or one triangle holding both).
TEST(WEFT_TEST_SUITE, lbvh_covers_labelled_collisions_of_cloth_funnel) {
  using Exec = WEFT_TEST_EXECSPACE;
  using Mem = Exec::memory_space;
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "../shared absent";
  const std::string dir = weft::test::shared_dir() + "/data/ccd/scalable/cloth-funnel/";
  const weft::io::TriMesh m0 = weft::io::read_ply(dir + "frames/227.ply");
  const weft::io::TriMesh m1 = weft::io::read_ply(dir + "frames/228.ply");
  ASSERT_EQ(m0.positions.size(), m1.positions.size());
  ASSERT_EQ(m0.triangles, m1.triangles);
  const int nv = int(m0.positions.size()), nf = int(m0.triangles.size());

  // Edges numbered by (larger vertex, smaller vertex); the triangles around each edge and vertex.
  std::map<std::pair<int, int>, std::vector<int>> edge_tris;
  std::vector<std::vector<int>> vertex_tris(nv);
  for (int t = 0; t < nf; ++t)
    for (int c = 0; c < 3; ++c) {
      const int a = m0.triangles[t][c], b = m0.triangles[t][(c + 1) % 3];
      edge_tris[{std::max(a, b), std::min(a, b)}].push_back(t);
      vertex_tris[a].push_back(t);
    }
  std::vector<std::vector<int>> tris_of_edge;
  for (const auto& e : edge_tris) tris_of_edge.push_back(e.second);
  const int ne = int(tris_of_edge.size());

  Soup s{m0.positions, m1.positions, {}, std::vector<double>(nf, 0.0)};
  for (const auto& t : m0.triangles) s.tris.push_back(t);
  weft::Lbvh<Exec> bvh;
  bvh.build(device_boxes<Exec>(s));
  Kokkos::View<IndexPair*, Mem> pairs;
  const long count = bvh.query_self(weft::KeepAllPairs{}, pairs);
  const auto h = weft::test::to_host(pairs);
  std::unordered_set<uint64_t> overlapping;
  for (long k = 0; k < count; ++k) overlapping.insert((uint64_t(h[k].first) << 32) | uint32_t(h[k].second));
  const auto covered = [&](const std::vector<int>& ta, const std::vector<int>& tb) {
    for (int a : ta)
      for (int b : tb)
        if (a == b || overlapping.count((uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b)))) return true;
    return false;
  };

  const auto load = [&](const std::string& f) {
    std::ifstream in(dir + f);
    EXPECT_TRUE(in.good()) << f;
    return nlohmann::json::parse(in);
  };
  int labelled = 0;
  for (const std::string kind : {"vf", "ee"}) {
    const auto candidates = load("boxes/227" + kind + ".json");
    const auto truth = load("mma_bool/227" + kind + "_mma_bool.json");
    ASSERT_EQ(candidates.size(), truth.size()) << kind;
    for (size_t k = 0; k < truth.size(); ++k) {
      if (!truth[k].get<bool>()) continue;
      ++labelled;
      const long a = candidates[k][0].get<long>(), b = candidates[k][1].get<long>();
      if (kind == "vf") {
        ASSERT_TRUE(a >= 0 && a < nv && b >= nv + ne && b < nv + ne + nf) << kind << " " << k;
        EXPECT_TRUE(covered(vertex_tris[a], {int(b - nv - ne)})) << "vf pair " << k << " (" << a << ", " << b << ")";
      } else {
        ASSERT_TRUE(a >= nv && a < nv + ne && b >= nv && b < nv + ne) << kind << " " << k;
        EXPECT_TRUE(covered(tris_of_edge[a - nv], tris_of_edge[b - nv])) << "ee pair " << k << " (" << a << ", " << b << ")";
      }
    }
  }
  EXPECT_GT(labelled, 0);
}

}  // namespace
