// The animation solvability check (paper sec. 3, "Data cleaning"; docs/solvability.md): the body (all
// colliders) is cleaned frame by frame so that it never intersects itself and keeps, wherever cloth layers
// lie on it, a gap wide enough for them.
//
// 1. Reserved thickness R(v): the ray from body vertex v along its normal, up to `reach` or the first body
//    triangle it meets, crosses cloth layers; R(v) sums their thickness (each layer once). It is found once,
//    on the first body frame against the cloth's initial positions (the garment as dressed), and kept for
//    every frame: the layers move with the body.
// 2. Self-intersection: points inside the body (odd ray crossings of the closed colliders, majority of
//    three rays) and the corners of intersecting triangle pairs step `step` against their normal until no
//    pair intersects and no point is inside, at most `max_steps` times.
// 3. Gap: a body vertex whose normal ray meets the body within G = 2 R(v) + both sides' collider thickness
//    (every layer takes twice its thickness, the solver's contact distance between layers) forms a
//    vertex-face contact; contacts are resolved together, pushing the vertex and the face's corners into the
//    body, Jacobi-averaged per point, at most `max_iterations` times.
//
// Every kernel is a functor, every sum runs in a fixed order, the nearest hit is chosen by (distance,
// triangle), and the contacts are sorted on unique keys: the result is the same on every backend.
#pragma once
#include "collision/aabb.hpp"
#include "collision/body_cleaning_input.hpp"
#include "collision/body_cleaning_result.hpp"
#include "collision/lbvh.hpp"
#include "collision/ray_triangle.hpp"
#include "collision/tri_tri.hpp"
#include "core/device_copy.hpp"
#include "core/reduce.hpp"
#include "core/sort.hpp"

#include <Kokkos_Core.hpp>
#include <cstdint>
#include <cstring>

namespace weft {
namespace body_cleaning_detail {

inline constexpr uint64_t kNoContact = ~uint64_t(0);

// The body mesh at some positions, as kernels see it.
template <class Mem>
struct BodyGeometry {
  Kokkos::View<const Vec3*, Mem> x;
  Kokkos::View<const int* [3], Mem> tris;
  Kokkos::View<const int*, Mem> vt_offsets, vt_tris;

  KOKKOS_INLINE_FUNCTION bool incident(int v, int t) const {
    return tris(t, 0) == v || tris(t, 1) == v || tris(t, 2) == v;
  }
  KOKKOS_INLINE_FUNCTION Vec3 corner(int t, int k) const { return x(tris(t, k)); }

  // The nearest triangle (by distance, then index) not around v that the ray from x(v) along d meets within
  // t_max; -1 if none.
  KOKKOS_INLINE_FUNCTION int nearest_hit(const LbvhNodes<Mem>& tree, int v, Vec3 d, real t_max, RayHit& best) const {
    const Vec3 o = x(v);
    int best_tri = -1;
    tree.for_each_overlap(ray_box(o, d, t_max), [&](int t) {
      RayHit h;
      if (incident(v, t) || !ray_meets_triangle(o, d, t_max, corner(t, 0), corner(t, 1), corner(t, 2), h)) return;
      if (best_tri < 0 || h.t < best.t || (h.t == best.t && t < best_tri)) {
        best = h;
        best_tri = t;
      }
    });
    return best_tri;
  }
};

// Area-weighted vertex normals, summed over the vertex's triangles in ascending order.
template <class Mem>
struct VertexNormals {
  BodyGeometry<Mem> body;
  Kokkos::View<Vec3*, Mem> n;
  KOKKOS_INLINE_FUNCTION void operator()(long v) const {
    Vec3 s{};
    for (int k = body.vt_offsets(v); k < body.vt_offsets(v + 1); ++k) {
      const int t = body.vt_tris(k);
      const Vec3 a = body.corner(t, 0);
      s += cross(body.corner(t, 1) - a, body.corner(t, 2) - a);
    }
    n(v) = normalized(s);
  }
};

// Step 1: the summed thickness of the cloth layers the normal ray crosses before `reach` or the body.
template <class Mem>
struct ReservedThickness {
  BodyGeometry<Mem> body;
  LbvhNodes<Mem> body_tree, cloth_tree;
  Kokkos::View<const Vec3*, Mem> n, cloth_x;
  Kokkos::View<const int* [3], Mem> cloth_tris;
  Kokkos::View<const uint64_t*, Mem> cloth_bit;
  Kokkos::View<const real*, Mem> bit_thickness;
  real reach;
  Kokkos::View<real*, Mem> reserved;

  KOKKOS_INLINE_FUNCTION void operator()(long v) const {
    const Vec3 d = n(v), o = body.x(v);
    real len = reach;
    RayHit h;
    if (body.nearest_hit(body_tree, int(v), d, reach, h) >= 0) len = h.t;
    uint64_t crossed = 0;
    if (!(d == Vec3{}))
      cloth_tree.for_each_overlap(ray_box(o, d, len), [&](int t) {
        RayHit c;
        if (!(crossed & cloth_bit(t)) &&
            ray_meets_triangle(o, d, len, cloth_x(cloth_tris(t, 0)), cloth_x(cloth_tris(t, 1)), cloth_x(cloth_tris(t, 2)), c))
          crossed |= cloth_bit(t);
      });
    real r = 0;
    for (int k = 0; k < int(bit_thickness.extent(0)); ++k)
      if ((crossed >> k) & 1u) r += bit_thickness(k);
    reserved(v) = r;
  }
};

// Step 2: flag(v) = 1 when v is inside the body: an odd number of crossings of closed colliders' triangles
// (not around v) along at least two of three outward rays, each running to the body's bounding box.
template <class Mem>
struct InsideByParity {
  BodyGeometry<Mem> body;
  LbvhNodes<Mem> tree;
  Kokkos::View<const Vec3*, Mem> n;
  Kokkos::View<const uint8_t*, Mem> closed;
  Kokkos::View<int*, Mem> flag;

  KOKKOS_INLINE_FUNCTION int crossings(int v, Vec3 d) const {
    const Aabb bounds = tree.bounds();  // rounded outward, so it still holds every triangle
    const Vec3 o = body.x(v);
    real t_exit = __builtin_huge_val();
    for (int a = 0; a < 3; ++a) {
      if (d[a] > 0) t_exit = min_(t_exit, (bounds.hi[a] - o[a]) / d[a]);
      if (d[a] < 0) t_exit = min_(t_exit, (bounds.lo[a] - o[a]) / d[a]);
    }
    const real t_max = 2 * t_exit;  // past the box nothing is met; the margin keeps boundary triangles in
    int count = 0;
    tree.for_each_overlap(ray_box(o, d, t_max), [&](int t) {
      RayHit h;
      if (closed(t) && !body.incident(v, t) &&
          ray_meets_triangle(o, d, t_max, body.corner(t, 0), body.corner(t, 1), body.corner(t, 2), h))
        ++count;
    });
    return count;
  }

  KOKKOS_INLINE_FUNCTION void operator()(long v) const {
    const Vec3 d = n(v);
    if (d == Vec3{}) {
      flag(v) = 0;
      return;
    }
    // A tangent frame from the axis least aligned with d; the three rays lean off the normal by unrelated
    // amounts, so a ray through an edge or vertex (counted twice or not at all) is outvoted.
    const real ax = abs_(d.x), ay = abs_(d.y), az = abs_(d.z);
    const Vec3 axis = ax <= ay && ax <= az ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    const Vec3 e1 = normalized(cross(d, axis)), e2 = cross(d, e1);
    int odd = 0;
    odd += crossings(int(v), normalized(d + 0.07 * e1 - 0.11 * e2)) & 1;
    odd += crossings(int(v), normalized(d + 0.31 * e1 + 0.17 * e2)) & 1;
    odd += crossings(int(v), normalized(d - 0.23 * e1 + 0.29 * e2)) & 1;
    flag(v) = odd >= 2 ? 1 : 0;
  }
};

// Step 2: the corners of intersecting triangle pairs move too (an integer flag set to 1, in any order).
template <class Mem>
struct FlagPairCorners {
  Kokkos::View<const IndexPair*, Mem> pairs;
  Kokkos::View<const int* [3], Mem> tris;
  Kokkos::View<int*, Mem> flag;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const {
    for (int k = 0; k < 3; ++k) {
      Kokkos::atomic_exchange(&flag(tris(pairs(i).first, k)), 1);
      Kokkos::atomic_exchange(&flag(tris(pairs(i).second, k)), 1);
    }
  }
};

template <class Mem>
struct StepInward {
  Kokkos::View<Vec3*, Mem> x;
  Kokkos::View<const Vec3*, Mem> n;
  Kokkos::View<const int*, Mem> flag;
  real step;
  KOKKOS_INLINE_FUNCTION void operator()(long v) const {
    if (flag(v)) x(v) = x(v) - step * n(v);
  }
};

// Step 3: vertex v's contact with the nearest body triangle its normal ray meets within the reserved gap G:
// push(v) is the PBD correction (equal weights) that opens the gap to (1 + overshoot) G, the key sorts the
// contacts by triangle.
template <class Mem>
struct GapContacts {
  BodyGeometry<Mem> body;
  LbvhNodes<Mem> tree;
  Kokkos::View<const Vec3*, Mem> n;
  Kokkos::View<const real*, Mem> reserved, vertex_thickness, triangle_thickness;
  real max_thickness, overshoot;
  Kokkos::View<uint64_t*, Mem> key;
  Kokkos::View<uint32_t*, Mem> val;
  Kokkos::View<real*, Mem> push;
  Kokkos::View<Vec3*, Mem> bary;

  KOKKOS_INLINE_FUNCTION void operator()(long v) const {
    key(v) = kNoContact;
    val(v) = uint32_t(v);
    push(v) = 0;
    const real r = reserved(v);
    const Vec3 d = n(v);
    if (!(r > 0) || d == Vec3{}) return;
    const real own = 2 * r + vertex_thickness(v);
    RayHit h;
    const int t = body.nearest_hit(tree, int(v), d, own + max_thickness, h);
    if (t < 0) return;
    const real gap = own + triangle_thickness(t);
    if (!(h.t < gap)) return;
    const Vec3 b{1 - h.u - h.v, h.u, h.v};
    push(v) = ((1 + overshoot) * gap - h.t) / (1 + norm2(b));
    bary(v) = b;
    key(v) = (uint64_t(t) << 32) | uint64_t(v);
  }
};

// Step 3: every point moves by the mean of its corrections, as a contact's vertex (against its normal) and
// as a corner of contacts' faces (along the contact vertex's normal), in sorted-contact order.
template <class Mem>
struct GapDisplace {
  BodyGeometry<Mem> body;
  Kokkos::View<Vec3*, Mem> x;  // the same positions as body.x, written here only at the own point
  Kokkos::View<const Vec3*, Mem> n;
  Kokkos::View<const uint64_t*, Mem> key;
  Kokkos::View<const uint32_t*, Mem> val;
  Kokkos::View<const real*, Mem> push;
  Kokkos::View<const Vec3*, Mem> bary;

  KOKKOS_INLINE_FUNCTION long first_contact(int t) const {  // lower bound of (t, 0) in the sorted keys
    long lo = 0, hi = long(key.extent(0));
    const uint64_t k = uint64_t(t) << 32;
    while (lo < hi) {
      const long mid = lo + (hi - lo) / 2;
      if (key(mid) < k) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  }

  KOKKOS_INLINE_FUNCTION void operator()(long u) const {
    Vec3 sum{};
    int count = 0;
    if (push(u) > 0) {
      sum -= push(u) * n(u);
      ++count;
    }
    for (int k = body.vt_offsets(u); k < body.vt_offsets(u + 1); ++k) {
      const int t = body.vt_tris(k);
      const int c = body.tris(t, 0) == u ? 0 : (body.tris(t, 1) == u ? 1 : 2);
      for (long i = first_contact(t); i < long(key.extent(0)) && (key(i) >> 32) == uint64_t(t); ++i) {
        const uint32_t v = val(i);
        sum += (bary(v)[c] * push(v)) * n(v);
        ++count;
      }
    }
    if (count > 0) x(u) = x(u) + sum / real(count);
  }
};

template <class Mem>
struct CountSet {
  Kokkos::View<const int*, Mem> flag;
  KOKKOS_INLINE_FUNCTION void operator()(long i, long& acc) const { acc += flag(i) != 0 ? 1 : 0; }
};

template <class Mem>
struct CountContacts {
  Kokkos::View<const uint64_t*, Mem> key;
  KOKKOS_INLINE_FUNCTION void operator()(long i, long& acc) const { acc += key(i) != kNoContact ? 1 : 0; }
};

// How far each point moved from the frame's input, and whether it moved at all (bitwise).
template <class Mem>
struct Displacement {
  Kokkos::View<const Vec3*, Mem> x, x_in;
  Kokkos::View<real*, Mem> dist;
  Kokkos::View<int*, Mem> moved;
  KOKKOS_INLINE_FUNCTION void operator()(long v) const {
    const Vec3 a = x(v), b = x_in(v);
    dist(v) = norm(a - b);
    moved(v) = a.x == b.x && a.y == b.y && a.z == b.z ? 0 : 1;
  }
};

}  // namespace body_cleaning_detail

// The check on one execution space. Throws InputError for cloth with more than 64 layers.
template <class Exec>
class BodyCleaner {
 public:
  using Mem = typename Exec::memory_space;
  template <class T>
  using View = Kokkos::View<T, Mem>;

  BodyCleaner(const Scene& s, const CleaningSettings& cs)
      : scene_(s), settings_(cs), mesh_(make_body_mesh(s.colliders)), body_bvh_(exec_) {
    using namespace body_cleaning_detail;
    const long nv = mesh_.vertices();
    tris_ = upload_table<Mem>(mesh_.triangles, "weft::body_tris");
    vt_offsets_ = upload<Mem>(mesh_.vt_offsets, "weft::body_vt_offsets");
    vt_tris_ = upload<Mem>(mesh_.vt_tris, "weft::body_vt_tris");
    closed_ = upload<Mem>(mesh_.closed, "weft::body_closed");
    vertex_th_ = upload<Mem>(mesh_.vertex_thickness, "weft::body_vertex_thickness");
    triangle_th_ = upload<Mem>(mesh_.triangle_thickness, "weft::body_triangle_thickness");
    for (const Collider& c : s.colliders) max_th_ = max_(max_th_, c.thickness);
    x_ = View<Vec3*>("weft::body_x", nv);
    x_in_ = View<Vec3*>("weft::body_x_in", nv);
    n_ = View<Vec3*>("weft::body_n", nv);
    reserved_ = View<real*>("weft::body_reserved", nv);
    flag_ = View<int*>("weft::body_flag", nv);
    key_ = View<uint64_t*>("weft::gap_key", nv);
    val_ = View<uint32_t*>("weft::gap_val", nv);
    push_ = View<real*>("weft::gap_push", nv);
    bary_ = View<Vec3*>("weft::gap_bary", nv);
    dist_ = View<real*>("weft::body_dist", nv);
    boxes_ = View<Aabb*>("weft::body_boxes", mesh_.triangles.size());
  }

  BodyCleaning run() {
    BodyCleaning out;
    out.colliders = scene_.colliders;
    if (mesh_.vertices() == 0 || mesh_.triangles.empty()) return out;
    reserve_thickness(out);
    std::vector<std::vector<Vec3>> cleaned(mesh_.frames);
    for (int f = 0; f < mesh_.frames; ++f) {
      FrameCleaning fc;
      fc.frame = scene_.settings.frame_start + f;
      cleaned[f] = clean_frame(collider_positions(scene_.colliders, mesh_, f), fc);
      out.frames.push_back(fc);
    }
    write_colliders(cleaned, out.colliders);
    return out;
  }

 private:
  body_cleaning_detail::BodyGeometry<Mem> geometry() const {
    return {View<const Vec3*>(x_), View<const int* [3]>(tris_), View<const int*>(vt_offsets_), View<const int*>(vt_tris_)};
  }
  long vertices() const { return mesh_.vertices(); }

  void set_positions(const std::vector<Vec3>& h) {
    copy_to_device(x_, h);
    Kokkos::deep_copy(x_in_, x_);
  }

  // Normals at the current positions, and the tree over the current triangles.
  void prepare() {
    using namespace body_cleaning_detail;
    Kokkos::parallel_for("weft::body_normals", Kokkos::RangePolicy<Exec>(exec_, 0, vertices()), VertexNormals<Mem>{geometry(), n_});
    swept_triangle_boxes(exec_, View<const Vec3*>(x_), View<const Vec3*>(x_), View<const int* [3]>(tris_), real(0), boxes_);
    body_bvh_.build(View<const Aabb*>(boxes_));
  }

  void reserve_thickness(BodyCleaning& out) {
    using namespace body_cleaning_detail;
    set_positions(collider_positions(scene_.colliders, mesh_, 0));
    prepare();
    if (!scene_.triangles.empty()) {
      const ClothLayers layers = make_cloth_layers(scene_);
      const auto cloth_x = upload<Mem>(scene_.points.position, "weft::cloth_x");
      const auto cloth_tris = upload_table<Mem>(scene_.triangles, "weft::cloth_tris");
      View<Aabb*> cloth_boxes("weft::cloth_boxes", scene_.triangles.size());
      swept_triangle_boxes(exec_, View<const Vec3*>(cloth_x), View<const Vec3*>(cloth_x), View<const int* [3]>(cloth_tris),
                           real(0), cloth_boxes);
      Lbvh<Exec> cloth_bvh(exec_);
      cloth_bvh.build(View<const Aabb*>(cloth_boxes));
      Kokkos::parallel_for(
          "weft::body_reserved", Kokkos::RangePolicy<Exec>(exec_, 0, vertices()),
          ReservedThickness<Mem>{geometry(), body_bvh_.nodes(), cloth_bvh.nodes(), n_, cloth_x, cloth_tris,
                                 upload<Mem>(layers.triangle_bit, "weft::cloth_bit"),
                                 upload<Mem>(layers.bit_thickness, "weft::bit_thickness"), settings_.reach,
                                 reserved_});
    }
    for (real r : to_host(reserved_)) {
      out.reserved.push_back(r);
      if (r > 0) ++out.reserved_points;
      out.max_reserved = max_(out.max_reserved, r);
    }
  }

  // Step 2 at the current positions: intersecting pairs and inside points (flag_ = the points to move).
  void find_self_intersections(long& pairs, long& inside) {
    using namespace body_cleaning_detail;
    prepare();
    pairs = count_intersections(body_bvh_, View<const Vec3*>(x_), View<const int* [3]>(tris_), pairs_);
    Kokkos::parallel_for("weft::body_inside", Kokkos::RangePolicy<Exec>(exec_, 0, vertices()),
                         InsideByParity<Mem>{geometry(), body_bvh_.nodes(), n_, closed_, flag_});
    inside = 0;
    Kokkos::parallel_reduce("weft::body_count_inside", Kokkos::RangePolicy<Exec>(exec_, 0, vertices()),
                            CountSet<Mem>{flag_}, inside);
    if (pairs > 0)
      Kokkos::parallel_for("weft::body_pair_corners", Kokkos::RangePolicy<Exec>(exec_, 0, pairs),
                           FlagPairCorners<Mem>{pairs_, tris_, flag_});
  }

  // Step 3 at the current positions: the gap contacts; returns how many.
  long find_gap_contacts() {
    using namespace body_cleaning_detail;
    prepare();
    Kokkos::parallel_for("weft::body_gap_contacts", Kokkos::RangePolicy<Exec>(exec_, 0, vertices()),
                         GapContacts<Mem>{geometry(), body_bvh_.nodes(), n_, reserved_, vertex_th_, triangle_th_, max_th_,
                                          settings_.overshoot, key_, val_, push_, bary_});
    long n = 0;
    Kokkos::parallel_reduce("weft::body_count_gaps", Kokkos::RangePolicy<Exec>(exec_, 0, vertices()),
                            CountContacts<Mem>{key_}, n);
    return n;
  }

  std::vector<Vec3> clean_frame(const std::vector<Vec3>& input, FrameCleaning& fc) {
    using namespace body_cleaning_detail;
    set_positions(input);
    const long nv = vertices();
    // Step 2: step inside points and intersecting triangles' corners inward until nothing is left.
    long pairs = 0, inside = 0;
    for (int s = 0;; ++s) {
      find_self_intersections(pairs, inside);
      if (s == 0) {
        fc.intersections_before = pairs;
        fc.interior_before = inside;
      }
      if ((pairs == 0 && inside == 0) || s == settings_.max_steps) break;
      Kokkos::parallel_for("weft::body_step_inward", Kokkos::RangePolicy<Exec>(exec_, 0, nv),
                           StepInward<Mem>{x_, n_, flag_, settings_.step});
      fc.self_steps = s + 1;
    }
    // Step 3: resolve the gap contacts together until none is left.
    for (int it = 0;; ++it) {
      const long contacts = find_gap_contacts();
      if (it == 0) fc.gap_violations_before = contacts;
      fc.gap_violations_left = contacts;
      if (contacts == 0 || it == settings_.max_iterations) break;
      radix_sort_pairs(exec_, key_, val_);
      Kokkos::parallel_for("weft::body_gap_displace", Kokkos::RangePolicy<Exec>(exec_, 0, nv),
                           GapDisplace<Mem>{geometry(), x_, n_, key_, val_, push_, bary_});
      fc.gap_iterations = it + 1;
    }
    if (fc.gap_iterations > 0) find_self_intersections(pairs, inside);  // moving for the gap may have undone step 2
    fc.intersections_left = pairs;
    fc.interior_left = inside;
    // What changed.
    Kokkos::parallel_for("weft::body_displacement", Kokkos::RangePolicy<Exec>(exec_, 0, nv),
                         Displacement<Mem>{x_, x_in_, dist_, flag_});
    fc.points_moved = 0;
    Kokkos::parallel_reduce("weft::body_count_moved", Kokkos::RangePolicy<Exec>(exec_, 0, nv), CountSet<Mem>{flag_},
                            fc.points_moved);
    fc.max_displacement = fc.points_moved > 0 ? max_fixed(exec_, dist_) : 0;
    return to_host(x_);
  }

  // A collider keeps its own frames, bit for bit, unless the check moved one of its points on some frame;
  // then it gets every body frame.
  void write_colliders(const std::vector<std::vector<Vec3>>& cleaned, std::vector<Collider>& colliders) const {
    for (size_t c = 0; c < colliders.size(); ++c) {
      const int lo = mesh_.first_vertex[c], nv = mesh_.first_vertex[c + 1] - lo;
      const auto& frames = scene_.colliders[c].motion.frames;
      bool changed = false;
      for (int f = 0; f < mesh_.frames && !changed; ++f) {
        const auto& in = frames[std::min<size_t>(f, frames.size() - 1)];
        changed = nv > 0 && std::memcmp(in.data(), cleaned[f].data() + lo, nv * sizeof(Vec3)) != 0;
      }
      if (!changed) continue;
      auto& out = colliders[c].motion.frames;
      out.assign(mesh_.frames, {});
      for (int f = 0; f < mesh_.frames; ++f) out[f].assign(cleaned[f].begin() + lo, cleaned[f].begin() + lo + nv);
    }
  }

  const Scene& scene_;
  CleaningSettings settings_;
  BodyMesh mesh_;
  Exec exec_;
  Lbvh<Exec> body_bvh_;
  View<int* [3]> tris_;
  View<int*> vt_offsets_, vt_tris_, flag_;
  View<uint8_t*> closed_;
  View<real*> vertex_th_, triangle_th_, reserved_, push_, dist_;
  real max_th_ = 0;
  View<Vec3*> x_, x_in_, n_, bary_;
  View<uint64_t*> key_;
  View<uint32_t*> val_;
  View<Aabb*> boxes_;
  View<IndexPair*> pairs_{"weft::body_pairs", 0};
};

template <class Exec>
BodyCleaning clean_body_on(const Scene& s, const CleaningSettings& cs) {
  return BodyCleaner<Exec>(s, cs).run();
}

}  // namespace weft
