// Linear BVH over boxes (Karras 2012, "Maximizing parallelism in the construction of BVHs, octrees, and k-d
// trees"), built, refitted and queried on the device.
//
// Build: Morton codes of the box centres within the bounds of the centres, made unique by the primitive
// index (collision/morton.hpp), sorted; Karras' construction links the internal nodes from the sorted keys.
// Refit: node boxes bottom-up from new leaf boxes, same topology. Queries: every overlapping pair, written by
// count -> exclusive scan -> fill, so the output order depends on the data only, never on the backend.
//
// Traversal is stackless: every node stores its rope (the next node in depth-first, left-first order once
// its subtree is done), so no stack can overflow whatever the tree's depth, and the leaves are met in
// tree order. (With unique 64-bit keys the depth is at most 64 anyway: prefix lengths grow down the tree.)
// A walk reads one 32-byte node per step: its box rounded outward to floats, its rope and its first child
// (or primitive). The float boxes only prune; a leaf is kept by its exact box, so the pairs are exactly
// those of the exact boxes, and the same on every backend.
#pragma once
#include "collision/aabb.hpp"
#include "collision/morton.hpp"
#include "core/reduce.hpp"
#include "core/scan.hpp"
#include "core/sort.hpp"

#include <Kokkos_Core.hpp>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace weft {

struct IndexPair {
  int first, second;
};

// Query predicate that keeps every pair. A predicate is a copyable device functor with
// `bool operator()(int first, int second) const` (true: keep); it is called twice per pair (count, fill),
// so it must give the same answer both times.
struct KeepAllPairs {
  KOKKOS_INLINE_FUNCTION bool operator()(int, int) const { return true; }
};

// A node as walks read it: one 32-byte sector.
struct alignas(16) LbvhNode {
  float lo[3], hi[3];  // the node's box, rounded outward: it holds the exact box
  int rope;            // next node after this subtree, -1 after the last
  int child;           // internal node: its first child; leaf: its primitive
};

// The box rounded outward to floats. The pads (2^-22 relative, 2^-100 absolute) exceed the conversion's
// rounding, so lo never rises and hi never falls; infinities stay as they are.
struct FloatBox {
  float lo[3], hi[3];
};
KOKKOS_INLINE_FUNCTION float float_below(double d) {
  const double m = d - (d < 0 ? -d : d) * 0x1p-22 - 0x1p-100;
  return static_cast<float>(m < d ? m : d);
}
KOKKOS_INLINE_FUNCTION float float_above(double d) {
  const double m = d + (d < 0 ? -d : d) * 0x1p-22 + 0x1p-100;
  return static_cast<float>(m > d ? m : d);
}
KOKKOS_INLINE_FUNCTION FloatBox outward(const Aabb& b) {
  return {{float_below(b.lo.x), float_below(b.lo.y), float_below(b.lo.z)},
          {float_above(b.hi.x), float_above(b.hi.y), float_above(b.hi.z)}};
}
KOKKOS_INLINE_FUNCTION bool overlaps(const LbvhNode& a, const FloatBox& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// The tree as kernels see it. With n >= 1 leaves: internal nodes 0..n-2, leaves n-1..2n-2, root 0 (the only
// leaf when n == 1). Leaf n-1+k holds the k-th primitive in key order.
template <class Mem>
struct LbvhNodes {
  int n = 0;
  Kokkos::View<const LbvhNode*, Mem> node;       // per node
  Kokkos::View<const Aabb*, Mem> leaf_box;       // per leaf, in tree order: the exact box
  Kokkos::View<const uint32_t*, Mem> primitive;  // per leaf, in tree order

  // A box holding every primitive's box: the root's, rounded outward (n >= 1).
  KOKKOS_INLINE_FUNCTION Aabb bounds() const {
    const LbvhNode r = node(0);
    return {{r.lo[0], r.lo[1], r.lo[2]}, {r.hi[0], r.hi[1], r.hi[2]}};
  }

  // f(j) for every primitive j whose box overlaps q, in tree order.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_overlap(const Aabb& q, F&& f) const {
    walk(n > 0 ? 0 : -1, q, f);
  }

  // f(j) for every primitive j whose leaf comes after leaf k in tree order and whose box overlaps q: a self
  // query meets each overlapping pair once, from its earlier leaf. The walk starts at the leaf's rope, the
  // first node after it in depth-first order, so it never meets the leaves before it.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_later_overlap(int k, const Aabb& q, F&& f) const {
    walk(node(n - 1 + k).rope, q, f);
  }

 private:
  // The depth-first walk from node x to the end, skipping subtrees whose float box misses q's.
  template <class F>
  KOKKOS_INLINE_FUNCTION void walk(int x, const Aabb& q, F&& f) const {
    const int first_leaf = n - 1;
    const FloatBox qf = outward(q);
    while (x >= 0) {
      const LbvhNode nd = node(x);
      if (overlaps(nd, qf)) {
        if (x < first_leaf) {
          x = nd.child;
          continue;
        }
        if (overlaps(leaf_box(x - first_leaf), q)) f(nd.child);
      }
      x = nd.rope;
    }
  }
};

namespace lbvh_detail {

// Kernels are named functors, not lambdas (docs/solver.md, "Kernels are functors").

// Karras' delta: common prefix length of keys i and j, -1 when j is outside [0, n).
template <class KeyView>
KOKKOS_INLINE_FUNCTION int delta(const KeyView& keys, long n, long i, long j) {
  return j < 0 || j >= n ? -1 : clz64(keys(i) ^ keys(j));
}

template <class Mem>
struct CentreBoundsBlocks {
  Kokkos::View<const Aabb*, Mem> boxes;
  Kokkos::View<Aabb*, Mem> partial;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kReduceBlock, hi = lo + kReduceBlock < n ? lo + kReduceBlock : n;
    Aabb acc = empty_aabb();
    for (long i = lo; i < hi; ++i) acc = expand(acc, centre(boxes(i)));
    partial(b) = acc;
  }
};

template <class Mem>
struct MergeBoundsBlocks {
  Kokkos::View<Aabb*, Mem> in, next;
  long in_len;
  KOKKOS_INLINE_FUNCTION void operator()(long b) const {
    const long lo = b * kReduceBlock, hi = lo + kReduceBlock < in_len ? lo + kReduceBlock : in_len;
    Aabb acc = in(lo);
    for (long i = lo + 1; i < hi; ++i) acc = merge(acc, in(i));
    next(b) = acc;
  }
};

template <class Mem>
struct StoreBounds {
  Kokkos::View<Aabb, Mem> out;
  Kokkos::View<Aabb*, Mem> partial;
  KOKKOS_INLINE_FUNCTION void operator()(int) const { out() = partial(0); }
};

// Bounds of the box centres, folded in fixed blocks of kReduceBlock (the shape depends on n only).
template <class Exec>
void centre_bounds(const Exec& exec, Kokkos::View<const Aabb*, typename Exec::memory_space> boxes,
                   Kokkos::View<Aabb, typename Exec::memory_space> out) {
  using Mem = typename Exec::memory_space;
  const long n = static_cast<long>(boxes.extent(0));
  long len = (n + kReduceBlock - 1) / kReduceBlock;
  Kokkos::View<Aabb*, Mem> partial(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::lbvh_bounds"), len);
  Kokkos::parallel_for("weft::lbvh_centre_bounds", Kokkos::RangePolicy<Exec>(exec, 0, len),
                       CentreBoundsBlocks<Mem>{boxes, partial, n});
  while (len > 1) {
    const long next_len = (len + kReduceBlock - 1) / kReduceBlock;
    Kokkos::View<Aabb*, Mem> next(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::lbvh_bounds"), next_len);
    Kokkos::parallel_for("weft::lbvh_merge_bounds", Kokkos::RangePolicy<Exec>(exec, 0, next_len),
                         MergeBoundsBlocks<Mem>{partial, next, len});
    partial = next;
    len = next_len;
  }
  Kokkos::parallel_for("weft::lbvh_bounds_out", Kokkos::RangePolicy<Exec>(exec, 0, 1), StoreBounds<Mem>{out, partial});
}

// Internal node i: its key range [min(i, j), max(i, j)] and split gamma, as in Karras' paper.
template <class Mem>
struct LinkNodes {
  Kokkos::View<const uint64_t*, Mem> keys;
  Kokkos::View<int*, Mem> left, right, parent, rope;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    const long first_leaf = n - 1;
    const long d = delta(keys, n, i, i + 1) > delta(keys, n, i, i - 1) ? 1 : -1;
    const int delta_min = delta(keys, n, i, i - d);
    long len_max = 2;
    while (delta(keys, n, i, i + len_max * d) > delta_min) len_max *= 2;
    long len = 0;
    for (long t = len_max / 2; t >= 1; t /= 2)
      if (delta(keys, n, i, i + (len + t) * d) > delta_min) len += t;
    const long j = i + len * d;
    const int delta_node = delta(keys, n, i, j);
    long s = 0, t = len;
    do {
      t = (t + 1) / 2;
      if (delta(keys, n, i, i + (s + t) * d) > delta_node) s += t;
    } while (t > 1);
    const long gamma = i + s * d + (d < 0 ? -1 : 0);
    const long lo = i < j ? i : j, hi = i < j ? j : i;
    const int l = static_cast<int>(lo == gamma ? first_leaf + gamma : gamma);
    const int r = static_cast<int>(hi == gamma + 1 ? first_leaf + gamma + 1 : gamma + 1);
    left(i) = l;
    right(i) = r;
    parent(l) = static_cast<int>(i);
    parent(r) = static_cast<int>(i);
    // A subtree whose key range ends at gamma is followed by the right child of the node split at gamma;
    // leaf gamma is such a subtree. Internal nodes keep their range end until FinishRopes.
    rope(first_leaf + gamma) = r;
    rope(i) = static_cast<int>(hi);
  }
};

// An internal node's subtree ends where its last leaf's does; nothing follows the last leaf.
template <class Mem>
struct FinishRopes {
  Kokkos::View<int*, Mem> parent, rope;
  long first_leaf;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    if (k < first_leaf) {
      const long last = rope(k);
      rope(k) = last == first_leaf ? -1 : rope(first_leaf + last);
    } else {
      rope(first_leaf + first_leaf) = -1;
    }
    if (k == 0) parent(0) = -1;
  }
};

// Links the nodes from n >= 1 sorted unique keys: children, parents and ropes.
template <class Exec>
void link_nodes(const Exec& exec, Kokkos::View<const uint64_t*, typename Exec::memory_space> keys,
                Kokkos::View<int*, typename Exec::memory_space> left,
                Kokkos::View<int*, typename Exec::memory_space> right,
                Kokkos::View<int*, typename Exec::memory_space> parent,
                Kokkos::View<int*, typename Exec::memory_space> rope) {
  using Mem = typename Exec::memory_space;
  const long n = static_cast<long>(keys.extent(0));
  Kokkos::parallel_for("weft::lbvh_link", Kokkos::RangePolicy<Exec>(exec, 0, n - 1),
                       LinkNodes<Mem>{keys, left, right, parent, rope, n});
  Kokkos::parallel_for("weft::lbvh_ropes", Kokkos::RangePolicy<Exec>(exec, 0, n), FinishRopes<Mem>{parent, rope, n - 1});
}

template <class Mem>
struct MortonCodes {
  Kokkos::View<const Aabb*, Mem> boxes;
  Kokkos::View<Aabb, Mem> bounds;
  Kokkos::View<uint64_t*, Mem> keys;
  Kokkos::View<uint32_t*, Mem> primitive;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    keys(i) = morton30(centre(boxes(i)), bounds());
    primitive(i) = static_cast<uint32_t>(i);
  }
};

template <class Mem>
struct UniqueKeys {
  Kokkos::View<uint64_t*, Mem> keys;
  Kokkos::View<uint32_t*, Mem> primitive;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const { keys(k) = morton_key(static_cast<uint32_t>(keys(k)), primitive(k)); }
};

// Rope and first child (primitive, for a leaf) of every node; boxes come with the refit.
template <class Mem>
struct PackNodes {
  Kokkos::View<const int*, Mem> left, rope;
  Kokkos::View<const uint32_t*, Mem> primitive;
  Kokkos::View<LbvhNode*, Mem> node;
  long first_leaf;
  KOKKOS_INLINE_FUNCTION void operator()(long x) const {
    node(x).rope = rope(x);
    node(x).child = x < first_leaf ? left(x) : static_cast<int>(primitive(x - first_leaf));
  }
};

KOKKOS_INLINE_FUNCTION void set_box(LbvhNode& nd, const FloatBox& b) {
  for (int i = 0; i < 3; ++i) {
    nd.lo[i] = b.lo[i];
    nd.hi[i] = b.hi[i];
  }
}

// Each leaf walks up; at every node the second child to finish (an integer atomic count) merges both
// children, so each node is merged once. Float min and max are exact, so the boxes are the same on every
// backend.
template <class Mem>
struct Refit {
  Kokkos::View<const Aabb*, Mem> boxes;
  Kokkos::View<const uint32_t*, Mem> primitive;
  Kokkos::View<const int*, Mem> left, right, parent;
  Kokkos::View<LbvhNode*, Mem> node;
  Kokkos::View<Aabb*, Mem> leaf_box;
  Kokkos::View<int*, Mem> visits;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    int x = static_cast<int>(n - 1 + k);
    const Aabb b = boxes(primitive(k));
    leaf_box(k) = b;
    set_box(node(x), outward(b));
    while (true) {
      const int p = parent(x);
      if (p < 0) break;
      Kokkos::memory_fence();  // publish node(x)'s box before the count that lets the sibling's thread read it
      if (Kokkos::atomic_fetch_add(&visits(p), 1) == 0) break;  // the sibling's thread finishes p
      Kokkos::memory_fence();  // and see the sibling's box
      const LbvhNode l = node(left(p)), r = node(right(p));
      FloatBox m;
      for (int i = 0; i < 3; ++i) {
        m.lo[i] = r.lo[i] < l.lo[i] ? r.lo[i] : l.lo[i];
        m.hi[i] = l.hi[i] < r.hi[i] ? r.hi[i] : l.hi[i];
      }
      set_box(node(p), m);
      x = p;
    }
  }
};

// Pair queries. Self: query k is leaf k in tree order (neighbouring threads traverse alike); it meets the
// primitives of the later leaves that overlap it, and a pair is written as (i, j), i < j. Otherwise query q
// is the box queries(q) against every primitive. visit(k, f) calls f(first, second) for each kept pair.
template <class Mem, class Pred, bool Self>
struct PairQuery {
  LbvhNodes<Mem> tree;
  Kokkos::View<const Aabb*, Mem> queries;
  Pred pred;
  template <class F>
  KOKKOS_INLINE_FUNCTION void visit(long k, F&& f) const {
    if (Self) {
      const int i = static_cast<int>(tree.primitive(k));
      tree.for_each_later_overlap(static_cast<int>(k), tree.leaf_box(k), [&](int j) {
        const int a = i < j ? i : j, b = i < j ? j : i;
        if (pred(a, b)) f(a, b);
      });
    } else {
      const int q = static_cast<int>(k);
      tree.for_each_overlap(queries(k), [&](int j) {
        if (pred(q, j)) f(q, j);
      });
    }
  }
};

// Counts per query into offsets(k).
template <class Mem, class Pred, bool Self>
struct PairCount {
  PairQuery<Mem, Pred, Self> q;
  Kokkos::View<long*, Mem> offsets;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    long c = 0;
    q.visit(k, [&](int, int) { ++c; });
    offsets(k) = c;
  }
};

// The total of PairCount, as a reduction.
template <class Mem, class Pred, bool Self>
struct PairTotal {
  PairQuery<Mem, Pred, Self> q;
  KOKKOS_INLINE_FUNCTION void operator()(long k, long& acc) const {
    q.visit(k, [&](int, int) { ++acc; });
  }
};

template <class Mem, class Pred, bool Self>
struct PairFill {
  PairQuery<Mem, Pred, Self> q;
  Kokkos::View<long*, Mem> offsets;
  Kokkos::View<IndexPair*, Mem> out;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    long o = offsets(k);
    q.visit(k, [&](int a, int b) { out(o++) = IndexPair{a, b}; });
  }
};

// A self query's capacity for leaf k from its count at the last self query.
KOKKOS_INLINE_FUNCTION long fill_capacity(long last) { return 2 * last + 8; }
// The capacities of m leaves whose last counts sum to `total`: fill_capacity summed.
inline long fill_capacity_sum(long total, long m) { return 2 * total + 8 * m; }

// Per leaf: its primitive's pair count, kept by primitive for the next self query (the tree is rebuilt
// each frame, and a primitive's count changes little from query to query).
template <class Mem>
struct KeepCounts {
  Kokkos::View<const uint32_t*, Mem> primitive;
  Kokkos::View<long*, Mem> by_leaf, by_primitive;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const { by_primitive(primitive(k)) = by_leaf(k); }
};

template <class Mem>
struct FillCapacity {
  Kokkos::View<const uint32_t*, Mem> primitive;
  Kokkos::View<long*, Mem> last, cap;  // last: by primitive; cap: by leaf
  KOKKOS_INLINE_FUNCTION void operator()(long k) const { cap(k) = fill_capacity(last(primitive(k))); }
};

// Self query in one traversal: leaf k writes its pairs, in PairFill's order, to staging from slot(k) on,
// up to its capacity (from its primitive's count at the last self query, which it then replaces), and its
// count; overflow(k) = 1 when the capacity was short.
template <class Mem, class Pred>
struct PairCountFill {
  PairQuery<Mem, Pred, true> q;
  Kokkos::View<long*, Mem> slot, counts, last;
  Kokkos::View<int*, Mem> overflow;
  Kokkos::View<IndexPair*, Mem> staging;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    const uint32_t p = q.tree.primitive(k);
    const long cap = fill_capacity(last(p)), base = slot(k);
    long c = 0;
    q.visit(k, [&](int a, int b) {
      if (c < cap) staging(base + c) = IndexPair{a, b};
      ++c;
    });
    counts(k) = c;
    last(p) = c;
    overflow(k) = c > cap ? 1 : 0;
  }
};

// Leaf k's pairs to their place in the output: from its staging slots, or, where they overflowed, by
// walking the tree again as PairFill does.
template <class Mem, class Pred>
struct GatherPairs {
  PairQuery<Mem, Pred, true> q;
  Kokkos::View<long*, Mem> slot, offsets, counts;
  Kokkos::View<int*, Mem> overflow;
  Kokkos::View<IndexPair*, Mem> staging, out;
  KOKKOS_INLINE_FUNCTION void operator()(long k) const {
    long to = offsets(k);
    if (overflow(k)) {
      q.visit(k, [&](int a, int b) { out(to++) = IndexPair{a, b}; });
      return;
    }
    const long from = slot(k), c = counts(k);
    for (long i = 0; i < c; ++i) out(to + i) = staging(from + i);
  }
};

// Small trees on the device: leaf k against every later leaf in the chunk [c C, c C + C) (C =
// kAllPairsChunk) of leaves, thread t = c n + k, so that a warp's threads read the same chunk's boxes. The
// walk meets leaf k's later leaves in tree order, and so does this: counts and pairs per (leaf, chunk) in
// leaf-major order are the walk's, pair for pair. Count (out empty) or fill (offsets from the counts' scan).
constexpr long kAllPairsChunk = 128;
template <class Mem, class Pred>
struct AllLaterPairs {
  Kokkos::View<const LbvhNode*, Mem> node;       // per node: a leaf's float box first, as the walk tests it
  Kokkos::View<const Aabb*, Mem> box;            // per leaf, in tree order: the exact box
  Kokkos::View<const uint32_t*, Mem> primitive;  // per leaf, in tree order
  Pred pred;
  Kokkos::View<long*, Mem> offsets;  // per (leaf, chunk): the count, or the first output slot
  Kokkos::View<IndexPair*, Mem> out;
  long n, chunks;
  bool fill;
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const long c = t / n, k = t - c * n;
    const long first = c * kAllPairsChunk, end = first + kAllPairsChunk < n ? first + kAllPairsChunk : n;
    const long lo = first > k ? first : k + 1;
    long o = fill ? offsets(k * chunks + c) : 0;
    if (lo < end) {
      const Aabb q = box(k);
      const FloatBox qf = outward(q);
      const int i = static_cast<int>(primitive(k));
      for (long j = lo; j < end; ++j) {
        if (!overlaps(node(n - 1 + j), qf) || !overlaps(box(j), q)) continue;
        const int p = static_cast<int>(primitive(j));
        const int a = i < p ? i : p, b = i < p ? p : i;
        if (!pred(a, b)) continue;
        if (fill) out(o) = IndexPair{a, b};
        ++o;
      }
    }
    if (!fill) offsets(k * chunks + c) = o;
  }
};

// Grow v (contents dropped) to hold at least `size` items, with some slack so counts that creep up from
// call to call do not reallocate every time.
template <class View>
void reserve(View& v, long size, const char* label) {
  if (static_cast<long>(v.extent(0)) >= size) return;
  v = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label().empty() ? std::string(label) : v.label()),
           size + size / 8);
}

// v resized to exactly `size` (contents dropped) unless it already is.
template <class View>
void resize_exact(View& v, long size, const char* label) {
  if (static_cast<long>(v.extent(0)) != size)
    v = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)), size);
}

}  // namespace lbvh_detail

// An LBVH and its buffers, reused from call to call: build() when the primitives change, refit() when only
// their boxes move, then any number of queries. Pair queries return the pair count and write the pairs to
// pairs[0, count), growing `pairs` when it is too small (never dropping a pair).
template <class Exec>
class Lbvh {
 public:
  using Mem = typename Exec::memory_space;
  using BoxView = Kokkos::View<const Aabb*, Mem>;
  using PairView = Kokkos::View<IndexPair*, Mem>;

  explicit Lbvh(const Exec& exec = Exec()) : exec_(exec) {}

  const Exec& execution_space() const { return exec_; }
  long size() const { return n_; }
  LbvhNodes<Mem> nodes() const { return {static_cast<int>(n_), node_, leaf_box_, primitive_}; }
  // Primitive of each leaf in tree order: the order in which queries meet a query's overlapping primitives.
  Kokkos::View<const uint32_t*, Mem> leaf_primitives() const { return primitive_; }

  // A new tree over boxes(0..n), n < 2^31.
  void build(BoxView boxes) {
    const long n = static_cast<long>(boxes.extent(0));
    if (n >= (1L << 31) - 1) throw std::length_error("weft::Lbvh: too many primitives");
    n_ = n;
    const long internal = n > 0 ? n - 1 : 0, nodes = n > 0 ? 2 * n - 1 : 0;
    lbvh_detail::resize_exact(keys_, n, "weft::lbvh_keys");
    lbvh_detail::resize_exact(primitive_, n, "weft::lbvh_primitive");
    lbvh_detail::resize_exact(left_, internal, "weft::lbvh_left");
    lbvh_detail::resize_exact(right_, internal, "weft::lbvh_right");
    lbvh_detail::resize_exact(visits_, internal, "weft::lbvh_visits");
    lbvh_detail::resize_exact(parent_, nodes, "weft::lbvh_parent");
    lbvh_detail::resize_exact(rope_, nodes, "weft::lbvh_rope");
    lbvh_detail::resize_exact(node_, nodes, "weft::lbvh_nodes");
    lbvh_detail::resize_exact(leaf_box_, n, "weft::lbvh_leaf_box");
    if (n == 0) return;

    Kokkos::View<Aabb, Mem> bounds(Kokkos::view_alloc(exec_, std::string("weft::lbvh_scene")));
    lbvh_detail::centre_bounds(exec_, boxes, bounds);
    Kokkos::parallel_for("weft::lbvh_codes", Kokkos::RangePolicy<Exec>(exec_, 0, n),
                         lbvh_detail::MortonCodes<Mem>{boxes, bounds, keys_, primitive_});
    // The sort is stable and starts in index order, so sorting the codes alone gives the order of the unique
    // keys (code, index) at half the passes.
    radix_sort_pairs(exec_, keys_, primitive_, 32);
    Kokkos::parallel_for("weft::lbvh_keys", Kokkos::RangePolicy<Exec>(exec_, 0, n),
                         lbvh_detail::UniqueKeys<Mem>{keys_, primitive_});
    lbvh_detail::link_nodes(exec_, Kokkos::View<const uint64_t*, Mem>(keys_), left_, right_, parent_, rope_);
    Kokkos::parallel_for("weft::lbvh_pack", Kokkos::RangePolicy<Exec>(exec_, 0, nodes),
                         lbvh_detail::PackNodes<Mem>{left_, rope_, primitive_, node_, n - 1});
    refit(boxes);
  }

  // New boxes for the same primitives (boxes.extent(0) == size()).
  void refit(BoxView boxes) {
    const long n = n_;
    if (static_cast<long>(boxes.extent(0)) != n) throw std::invalid_argument("weft::Lbvh::refit: box count changed");
    if (n == 0) return;
    Kokkos::deep_copy(exec_, visits_, 0);
    Kokkos::parallel_for("weft::lbvh_refit", Kokkos::RangePolicy<Exec>(exec_, 0, n),
                         lbvh_detail::Refit<Mem>{boxes, primitive_, left_, right_, parent_, node_, leaf_box_, visits_, n});
  }

  // Pairs (i, j), i < j, of primitives whose boxes overlap and that pred(i, j) keeps, each once; sorted by
  // the position in tree order of whichever of i and j comes first there, then by the other's.
  template <class Pred>
  long query_self(Pred pred, PairView& pairs) {
    if (!kHost && n_ <= kAllPairsLeaves) return query_self_all_later(pred, pairs);
    return pairs_of<Pred, true>(n_, BoxView(), pred, pairs);
  }

  // query_self's pairs in its order, found by testing every leaf against every later one: what query_self
  // runs on the device for trees of at most kAllPairsLeaves leaves. There a walk is one thread per leaf
  // whose steps each wait on a load, and the twist's jammed rope (4,608 triangles, up to 930 steps a leaf)
  // took 0.45 ms a query on an H200, 0.13 ms this way (two passes of n^2 / 256 threads, each testing a
  // chunk of leaves' float boxes, then the exact ones, as the walk does). On the host the walk is the faster.
  template <class Pred>
  long query_self_all_later(Pred pred, PairView& pairs) {
    const long n = n_;
    if (n < 2) return 0;
    const long chunks = (n + lbvh_detail::kAllPairsChunk - 1) / lbvh_detail::kAllPairsChunk, cells = n * chunks;
    lbvh_detail::reserve(offsets_, cells, "weft::lbvh_offsets");
    const auto range = std::make_pair(0L, cells);
    lbvh_detail::AllLaterPairs<Mem, Pred> all{node_, leaf_box_, primitive_, pred, offsets_, pairs, n, chunks, false};
    Kokkos::parallel_for("weft::lbvh_all_pairs_count", Kokkos::RangePolicy<Exec>(exec_, 0, cells), all);
    const long total = exclusive_scan(exec_, Kokkos::subview(offsets_, range), offsets_);
    lbvh_detail::reserve(pairs, total, "weft::lbvh_pairs");
    all.out = pairs;
    all.fill = true;
    Kokkos::parallel_for("weft::lbvh_all_pairs_fill", Kokkos::RangePolicy<Exec>(exec_, 0, cells), all);
    return total;
  }

  // Pairs (q, j) of query boxes q and primitives j whose boxes overlap and that pred(q, j) keeps; sorted by
  // q, then by j in tree order.
  template <class Pred>
  long query(BoxView queries, Pred pred, PairView& pairs) {
    return pairs_of<Pred, false>(static_cast<long>(queries.extent(0)), queries, pred, pairs);
  }

  // The number of pairs query_self would return, in one traversal and without writing them.
  template <class Pred>
  long count_self(Pred pred) const {
    return count_of<Pred, true>(n_, BoxView(), pred);
  }

  // The number of pairs query would return.
  template <class Pred>
  long count(BoxView queries, Pred pred) const {
    return count_of<Pred, false>(static_cast<long>(queries.extent(0)), queries, pred);
  }

 private:
  // Count, scan, fill: two traversals. A self query after another of the same size traverses once instead
  // (self_pairs_in_one_walk); the pairs and their order are the same either way.
  template <class Pred, bool Self>
  long pairs_of(long m, BoxView queries, const Pred& pred, PairView& pairs) {
    if constexpr (Self)
      if (m == last_self_ && lbvh_detail::fill_capacity_sum(last_self_total_, m) <= kOneWalkPairs)
        return self_pairs_in_one_walk(m, pred, pairs);
    lbvh_detail::reserve(offsets_, m, "weft::lbvh_offsets");
    const lbvh_detail::PairQuery<Mem, Pred, Self> q{nodes(), queries, pred};
    Kokkos::parallel_for(Self ? "weft::lbvh_self_count" : "weft::lbvh_query_count",
                         Kokkos::RangePolicy<Exec>(exec_, 0, m), lbvh_detail::PairCount<Mem, Pred, Self>{q, offsets_});
    if constexpr (Self) {  // the counts give the next self query its capacities
      lbvh_detail::reserve(primitive_counts_, m, "weft::lbvh_primitive_counts");
      Kokkos::parallel_for("weft::lbvh_keep_counts", Kokkos::RangePolicy<Exec>(exec_, 0, m),
                           lbvh_detail::KeepCounts<Mem>{primitive_, offsets_, primitive_counts_});
    }
    const long total = exclusive_scan(exec_, Kokkos::subview(offsets_, std::make_pair(0L, m)), offsets_);
    lbvh_detail::reserve(pairs, total, "weft::lbvh_pairs");
    Kokkos::parallel_for(Self ? "weft::lbvh_self_fill" : "weft::lbvh_query_fill", Kokkos::RangePolicy<Exec>(exec_, 0, m),
                         lbvh_detail::PairFill<Mem, Pred, Self>{q, offsets_, pairs});
    if constexpr (Self) {
      last_self_ = m;
      last_self_total_ = total;
    }
    return total;
  }

  // Staged pairs at most (8 bytes each, 32 MiB). One walk pays where the walks are long and the pairs few,
  // as in the twist's jammed rope (1.29 -> 0.92 ms a query on an H200); the 300K skirt's queries gained no
  // time from it (within 1%).
  static constexpr long kOneWalkPairs = 4L << 20;
  static constexpr bool kHost = Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
  // n^2 / 2 = 34M box tests at most. On an H200 the 10K hanging sheet's walks (0.11 ms) beat its 50M tests.
  static constexpr long kAllPairsLeaves = 8192;

  // A self query in one traversal: each leaf writes its pairs into staging slots sized from its primitive's
  // count at the last self query (twice as many, plus 8), then they are gathered in place; a leaf that found
  // more than its slots hold walks again for them. On the twist's jammed rope the count walk was half of the
  // tree's time (0.56 ms of 1.1 ms a query on an H200); one walk takes its frame from 138.5 to 113.7 ms.
  template <class Pred>
  long self_pairs_in_one_walk(long m, const Pred& pred, PairView& pairs) {
    const auto range = std::make_pair(0L, m);
    lbvh_detail::reserve(offsets_, m, "weft::lbvh_offsets");
    lbvh_detail::reserve(leaf_counts_, m, "weft::lbvh_leaf_counts");
    lbvh_detail::reserve(slots_, m, "weft::lbvh_slots");
    lbvh_detail::reserve(overflow_, m, "weft::lbvh_overflow");
    Kokkos::parallel_for("weft::lbvh_self_capacity", Kokkos::RangePolicy<Exec>(exec_, 0, m),
                         lbvh_detail::FillCapacity<Mem>{primitive_, primitive_counts_, slots_});
    // The capacities' sum is known: no total to read back.
    exclusive_scan_on_device(exec_, Kokkos::subview(slots_, range), slots_);
    lbvh_detail::reserve(staging_, lbvh_detail::fill_capacity_sum(last_self_total_, m), "weft::lbvh_staging");
    const lbvh_detail::PairQuery<Mem, Pred, true> q{nodes(), BoxView(), pred};
    Kokkos::parallel_for("weft::lbvh_self_walk", Kokkos::RangePolicy<Exec>(exec_, 0, m),
                         lbvh_detail::PairCountFill<Mem, Pred>{q, slots_, leaf_counts_, primitive_counts_, overflow_,
                                                               staging_});
    const long total = exclusive_scan(exec_, Kokkos::subview(leaf_counts_, range), offsets_);
    lbvh_detail::reserve(pairs, total, "weft::lbvh_pairs");
    Kokkos::parallel_for("weft::lbvh_self_gather", Kokkos::RangePolicy<Exec>(exec_, 0, m),
                         lbvh_detail::GatherPairs<Mem, Pred>{q, slots_, offsets_, leaf_counts_, overflow_, staging_, pairs});
    last_self_total_ = total;
    return total;
  }

  template <class Pred, bool Self>
  long count_of(long m, BoxView queries, const Pred& pred) const {
    long total = 0;
    const lbvh_detail::PairQuery<Mem, Pred, Self> q{nodes(), queries, pred};
    Kokkos::parallel_reduce(Self ? "weft::lbvh_self_total" : "weft::lbvh_query_total",
                            Kokkos::RangePolicy<Exec>(exec_, 0, m), lbvh_detail::PairTotal<Mem, Pred, Self>{q}, total);
    return total;
  }

  Exec exec_;
  long n_ = 0;
  Kokkos::View<uint64_t*, Mem> keys_;      // sorted unique keys
  Kokkos::View<uint32_t*, Mem> primitive_;  // per leaf
  Kokkos::View<int*, Mem> left_, right_;    // per internal node
  Kokkos::View<int*, Mem> visits_;          // per internal node, refit's arrival counts
  Kokkos::View<int*, Mem> parent_, rope_;   // per node
  Kokkos::View<LbvhNode*, Mem> node_;      // per node: float box, rope, first child or primitive
  Kokkos::View<Aabb*, Mem> leaf_box_;       // per leaf: exact box
  Kokkos::View<long*, Mem> offsets_;        // per query, first output slot
  // Self queries in one walk: per primitive its count at the last self query (of last_self_ primitives,
  // last_self_total_ pairs in all); per leaf its count, first staging slot and whether its slots overflowed;
  // the staged pairs.
  long last_self_ = -1, last_self_total_ = 0;
  Kokkos::View<long*, Mem> primitive_counts_, leaf_counts_, slots_;
  Kokkos::View<int*, Mem> overflow_;
  PairView staging_;
};

}  // namespace weft
