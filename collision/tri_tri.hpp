// Discrete triangle-triangle intersection, and counting the intersecting triangle pairs of meshes.
//
// Two closed triangles meet iff an edge of one meets the other (the ends of their intersection lie on edges),
// so the test is six segment-triangle tests decided by signs of orientation determinants. Each sign is either
// certain (the floating-point value exceeds Shewchuk's bound on its rounding error, so it is the exact sign
// for the given coordinates) or 0, "too close to call". A segment whose side of the plane is unclear at both
// ends, or whose crossing point is unclear, is settled in the triangle's plane, where a nearly flat
// configuration is well conditioned: so flat cloth in any orientation has no false crossings. Touching
// counts as meeting, and within rounding of touching either answer may come. Triangles need non-zero area.
#pragma once
#include "collision/aabb.hpp"
#include "collision/lbvh.hpp"

namespace weft {

namespace tri_tri_detail {

inline constexpr real kEpsilon = 1.1102230246251565e-16;  // 2^-53, half an ulp of 1
// Shewchuk's bounds ("Adaptive precision floating-point arithmetic and fast robust geometric predicates",
// 1997) on the rounding error of the plain evaluations below, relative to their permanents.
inline constexpr real kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;
inline constexpr real kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;

KOKKOS_INLINE_FUNCTION int certain_sign(real det, real bound) { return det > bound ? 1 : (det < -bound ? -1 : 0); }

// +1 or -1 as d lies on one side or the other of the plane through a, b, c; 0 on it or too close to call.
KOKKOS_INLINE_FUNCTION int orient3d(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const real adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const real ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const real adz = a.z - d.z, bdz = b.z - d.z, cdz = c.z - d.z;
  const real bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const real cdxady = cdx * ady, adxcdy = adx * cdy;
  const real adxbdy = adx * bdy, bdxady = bdx * ady;
  const real det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const real permanent = (abs_(bdxcdy) + abs_(cdxbdy)) * abs_(adz) + (abs_(cdxady) + abs_(adxcdy)) * abs_(bdz) +
                         (abs_(adxbdy) + abs_(bdxady)) * abs_(cdz);
  return certain_sign(det, kOrient3dBound * permanent);
}

struct Pt2 {
  real u, v;
};

KOKKOS_INLINE_FUNCTION int orient2d(Pt2 a, Pt2 b, Pt2 c) {
  const real left = (a.u - c.u) * (b.v - c.v), right = (a.v - c.v) * (b.u - c.u);
  return certain_sign(left - right, kOrient2dBound * (abs_(left) + abs_(right)));
}

// Closed segments pq and ab in the plane.
KOKKOS_INLINE_FUNCTION bool segments_meet_2d(Pt2 p, Pt2 q, Pt2 a, Pt2 b) {
  const int d1 = orient2d(a, b, p), d2 = orient2d(a, b, q), d3 = orient2d(p, q, a), d4 = orient2d(p, q, b);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  // A collinear end point meets the other segment iff it lies within that segment's box.
  const auto within = [](Pt2 s, Pt2 t, Pt2 x) {
    return min_(s.u, t.u) <= x.u && x.u <= max_(s.u, t.u) && min_(s.v, t.v) <= x.v && x.v <= max_(s.v, t.v);
  };
  return (d1 == 0 && within(a, b, p)) || (d2 == 0 && within(a, b, q)) || (d3 == 0 && within(p, q, a)) ||
         (d4 == 0 && within(p, q, b));
}

// Closed triangle abc (non-degenerate) contains x.
KOKKOS_INLINE_FUNCTION bool contains_2d(Pt2 a, Pt2 b, Pt2 c, Pt2 x) {
  const int s1 = orient2d(a, b, x), s2 = orient2d(b, c, x), s3 = orient2d(c, a, x);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Segment pq projected into the coordinate plane where triangle abc's projection is largest (dropping the
// axis of its normal's largest component) meets the projected triangle: the exact answer when pq lies in
// abc's plane, and the answer for a segment crossing the plane within rounding of the triangle's boundary.
KOKKOS_INLINE_FUNCTION bool coplanar_segment_meets_triangle(Vec3 p, Vec3 q, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 n = cross(b - a, c - a);
  const real nx = abs_(n.x), ny = abs_(n.y), nz = abs_(n.z);
  const int drop = nx >= ny && nx >= nz ? 0 : (ny >= nz ? 1 : 2);
  const auto project = [drop](Vec3 v) { return drop == 0 ? Pt2{v.y, v.z} : (drop == 1 ? Pt2{v.z, v.x} : Pt2{v.x, v.y}); };
  const Pt2 p2 = project(p), q2 = project(q), a2 = project(a), b2 = project(b), c2 = project(c);
  return contains_2d(a2, b2, c2, p2) || contains_2d(a2, b2, c2, q2) || segments_meet_2d(p2, q2, a2, b2) ||
         segments_meet_2d(p2, q2, b2, c2) || segments_meet_2d(p2, q2, c2, a2);
}

}  // namespace tri_tri_detail

// Closed segment pq meets closed triangle abc.
KOKKOS_INLINE_FUNCTION bool segment_meets_triangle(Vec3 p, Vec3 q, Vec3 a, Vec3 b, Vec3 c) {
  using namespace tri_tri_detail;
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp * sq > 0) return false;  // both ends certainly on one side
  if (sp == 0 && sq == 0) return coplanar_segment_meets_triangle(p, q, a, b, c);
  // pq reaches the plane; the point where it does is inside iff line pq passes every edge on the same side.
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  if ((s1 > 0 || s2 > 0 || s3 > 0) && (s1 < 0 || s2 < 0 || s3 < 0)) return false;
  if (s1 != 0 && s2 != 0 && s3 != 0) return true;
  return coplanar_segment_meets_triangle(p, q, a, b, c);  // on an edge, or everything nearly flat
}

namespace tri_tri_detail {

// Points p, q, r all certainly strictly on one side of the plane through a, b, c.
KOKKOS_INLINE_FUNCTION bool all_on_one_side(Vec3 a, Vec3 b, Vec3 c, Vec3 p, Vec3 q, Vec3 r) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q), sr = orient3d(a, b, c, r);
  return sp != 0 && sp == sq && sp == sr;
}

}  // namespace tri_tri_detail

// Closed triangles (a0, a1, a2) and (b0, b1, b2) meet. Triangles that share a vertex always meet there: use
// triangles_intersect_sharing_vertex for those, and skip pairs that share an edge (they meet along it and
// can only overlap further when folded exactly flat onto each other).
KOKKOS_INLINE_FUNCTION bool triangles_intersect(Vec3 a0, Vec3 a1, Vec3 a2, Vec3 b0, Vec3 b1, Vec3 b2) {
  using tri_tri_detail::all_on_one_side;
  // Certain separation by either plane settles it (and keeps the edge tests' plane fallbacks consistent).
  if (all_on_one_side(a0, a1, a2, b0, b1, b2) || all_on_one_side(b0, b1, b2, a0, a1, a2)) return false;
  return segment_meets_triangle(a0, a1, b0, b1, b2) || segment_meets_triangle(a1, a2, b0, b1, b2) ||
         segment_meets_triangle(a2, a0, b0, b1, b2) || segment_meets_triangle(b0, b1, a0, a1, a2) ||
         segment_meets_triangle(b1, b2, a0, a1, a2) || segment_meets_triangle(b2, b0, a0, a1, a2);
}

// Triangles (s, a1, a2) and (s, b1, b2) sharing exactly the vertex s meet somewhere other than s. Their
// intersection is convex and contains s; a ray from s through any other common point leaves it on the
// edge opposite s of one triangle, inside the other. So it is the two opposite edges against the other
// triangle; neither edge holds s, so meeting at s alone never counts.
KOKKOS_INLINE_FUNCTION bool triangles_intersect_sharing_vertex(Vec3 s, Vec3 a1, Vec3 a2, Vec3 b1, Vec3 b2) {
  using tri_tri_detail::orient3d;
  // b1 and b2 certainly on one side of A's plane (or a1, a2 of B's): the triangles meet at s only.
  const int sb1 = orient3d(s, a1, a2, b1), sa1 = orient3d(s, b1, b2, a1);
  if ((sb1 != 0 && sb1 == orient3d(s, a1, a2, b2)) || (sa1 != 0 && sa1 == orient3d(s, b1, b2, a2))) return false;
  return segment_meets_triangle(a1, a2, s, b1, b2) || segment_meets_triangle(b1, b2, s, a1, a2);
}

// Predicate for a mesh's self query: triangles i and j (i != j) meet, by the rule for how many vertex
// indices they share: none -> triangles_intersect, one -> triangles_intersect_sharing_vertex, two or three
// -> never (adjacent). Vertices are shared by index, not by position.
template <class Mem>
struct MeshTrianglesMeet {
  Kokkos::View<const Vec3*, Mem> x;
  Kokkos::View<const int* [3], Mem> tris;

  KOKKOS_INLINE_FUNCTION bool operator()(int i, int j) const {
    int shared = 0, si = 0, sj = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (tris(i, a) == tris(j, b)) {
          ++shared;
          si = a;
          sj = b;
        }
    if (shared >= 2) return false;
    if (shared == 1)
      return triangles_intersect_sharing_vertex(x(tris(i, si)), x(tris(i, (si + 1) % 3)), x(tris(i, (si + 2) % 3)),
                                                x(tris(j, (sj + 1) % 3)), x(tris(j, (sj + 2) % 3)));
    return triangles_intersect(x(tris(i, 0)), x(tris(i, 1)), x(tris(i, 2)), x(tris(j, 0)), x(tris(j, 1)),
                               x(tris(j, 2)));
  }
};

// Predicate for a query of mesh A's triangles against a tree over mesh B's: triangles a and b meet.
template <class Mem>
struct TwoMeshTrianglesMeet {
  Kokkos::View<const Vec3*, Mem> xa, xb;
  Kokkos::View<const int* [3], Mem> ta, tb;

  KOKKOS_INLINE_FUNCTION bool operator()(int a, int b) const {
    return triangles_intersect(xa(ta(a, 0)), xa(ta(a, 1)), xa(ta(a, 2)), xb(tb(b, 0)), xb(tb(b, 1)), xb(tb(b, 2)));
  }
};

namespace tri_tri_detail {

template <class Exec>
Kokkos::View<Aabb*, typename Exec::memory_space> triangle_boxes(
    const Exec& exec, Kokkos::View<const Vec3*, typename Exec::memory_space> x,
    Kokkos::View<const int* [3], typename Exec::memory_space> tris) {
  Kokkos::View<Aabb*, typename Exec::memory_space> boxes(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::triangle_boxes"), tris.extent(0));
  swept_triangle_boxes(exec, x, x, tris, real(0), boxes);
  return boxes;
}

}  // namespace tri_tri_detail

// Intersecting triangle pairs of one mesh (MeshTrianglesMeet). Rebuilds `bvh` over the mesh; the boxes are
// allocated per call (a diagnostic, not a per-substep kernel). Returns the count; with `pairs`, also the
// pairs (i < j) in query_self's order.
template <class Exec>
long count_intersections(Lbvh<Exec>& bvh, Kokkos::View<const Vec3*, typename Exec::memory_space> x,
                         Kokkos::View<const int* [3], typename Exec::memory_space> tris) {
  bvh.build(tri_tri_detail::triangle_boxes(bvh.execution_space(), x, tris));
  return bvh.count_self(MeshTrianglesMeet<typename Exec::memory_space>{x, tris});
}

template <class Exec>
long count_intersections(Lbvh<Exec>& bvh, Kokkos::View<const Vec3*, typename Exec::memory_space> x,
                         Kokkos::View<const int* [3], typename Exec::memory_space> tris,
                         Kokkos::View<IndexPair*, typename Exec::memory_space>& pairs) {
  bvh.build(tri_tri_detail::triangle_boxes(bvh.execution_space(), x, tris));
  return bvh.query_self(MeshTrianglesMeet<typename Exec::memory_space>{x, tris}, pairs);
}

// Intersecting pairs (a, b) of a triangle of mesh A and one of mesh B (no shared vertices). Rebuilds `bvh`
// over mesh B; with `pairs`, also the pairs in query's order (by a, then b in tree order).
template <class Exec>
long count_intersections(Lbvh<Exec>& bvh, Kokkos::View<const Vec3*, typename Exec::memory_space> xa,
                         Kokkos::View<const int* [3], typename Exec::memory_space> ta,
                         Kokkos::View<const Vec3*, typename Exec::memory_space> xb,
                         Kokkos::View<const int* [3], typename Exec::memory_space> tb) {
  bvh.build(tri_tri_detail::triangle_boxes(bvh.execution_space(), xb, tb));
  return bvh.count(tri_tri_detail::triangle_boxes(bvh.execution_space(), xa, ta),
                   TwoMeshTrianglesMeet<typename Exec::memory_space>{xa, xb, ta, tb});
}

template <class Exec>
long count_intersections(Lbvh<Exec>& bvh, Kokkos::View<const Vec3*, typename Exec::memory_space> xa,
                         Kokkos::View<const int* [3], typename Exec::memory_space> ta,
                         Kokkos::View<const Vec3*, typename Exec::memory_space> xb,
                         Kokkos::View<const int* [3], typename Exec::memory_space> tb,
                         Kokkos::View<IndexPair*, typename Exec::memory_space>& pairs) {
  bvh.build(tri_tri_detail::triangle_boxes(bvh.execution_space(), xb, tb));
  return bvh.query(tri_tri_detail::triangle_boxes(bvh.execution_space(), xa, ta),
                   TwoMeshTrianglesMeet<typename Exec::memory_space>{xa, xb, ta, tb}, pairs);
}

}  // namespace weft
