// Axis-aligned boxes for the broad phase, and the kernel that makes swept, inflated triangle boxes.
// Boxes are closed: touching boxes overlap. min/max are exact, so every box is the same on every backend.
#pragma once
#include "core/vec.hpp"

#include <Kokkos_Core.hpp>
#include <type_traits>

namespace weft {

struct Aabb {
  Vec3 lo, hi;
};

// The box of nothing: merging it changes nothing and it overlaps nothing.
KOKKOS_INLINE_FUNCTION Aabb empty_aabb() {
  const real inf = __builtin_huge_val();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}
KOKKOS_INLINE_FUNCTION Aabb merge(const Aabb& a, const Aabb& b) { return {vmin(a.lo, b.lo), vmax(a.hi, b.hi)}; }
KOKKOS_INLINE_FUNCTION Aabb expand(const Aabb& a, Vec3 p) { return {vmin(a.lo, p), vmax(a.hi, p)}; }
KOKKOS_INLINE_FUNCTION Aabb inflated(const Aabb& a, real m) { return {a.lo - Vec3{m, m, m}, a.hi + Vec3{m, m, m}}; }
KOKKOS_INLINE_FUNCTION Vec3 centre(const Aabb& a) { return 0.5 * (a.lo + a.hi); }
// Closed intervals on every axis; false when either box holds a NaN.
KOKKOS_INLINE_FUNCTION bool overlaps(const Aabb& a, const Aabb& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

// The box of triangle (a, b, c) over a step where its vertices move linearly from x0 to x1, grown by m on
// every side. It holds the triangle at every time of the step.
KOKKOS_INLINE_FUNCTION Aabb swept_triangle_box(Vec3 a0, Vec3 b0, Vec3 c0, Vec3 a1, Vec3 b1, Vec3 c1, real m) {
  Aabb box{a0, a0};
  box = expand(expand(expand(expand(expand(box, b0), c0), a1), b1), c1);
  return inflated(box, m);
}

// Swept, inflated triangle boxes; Margin is a View of per-triangle margins or one real for all.
template <class Mem, class Margin>
struct SweptTriangleBoxes {
  Kokkos::View<const Vec3*, Mem> x0, x1;
  Kokkos::View<const int* [3], Mem> tris;
  Margin margin;
  Kokkos::View<Aabb*, Mem> boxes;
  KOKKOS_INLINE_FUNCTION real margin_of(long t) const {
    if constexpr (std::is_arithmetic_v<Margin>) return margin; else return margin(t);
  }
  KOKKOS_INLINE_FUNCTION void operator()(long t) const {
    const int a = tris(t, 0), b = tris(t, 1), c = tris(t, 2);
    boxes(t) = swept_triangle_box(x0(a), x0(b), x0(c), x1(a), x1(b), x1(c), margin_of(t));
  }
};

// boxes(t) = swept box of triangle t from positions x0 to x1, inflated by margin(t) (e.g. its thickness, so
// two boxes overlap whenever the triangles come within the sum of their margins). x1 = x0 gives static boxes.
// margin is a View of per-triangle margins or one real for every triangle.
template <class Exec, class Margin>
void swept_triangle_boxes(const Exec& exec, Kokkos::View<const Vec3*, typename Exec::memory_space> x0,
                          Kokkos::View<const Vec3*, typename Exec::memory_space> x1,
                          Kokkos::View<const int* [3], typename Exec::memory_space> tris, const Margin& margin,
                          Kokkos::View<Aabb*, typename Exec::memory_space> boxes) {
  using Mem = typename Exec::memory_space;
  using M = std::conditional_t<std::is_arithmetic_v<Margin>, real, Kokkos::View<const real*, Mem>>;
  Kokkos::parallel_for("weft::swept_triangle_boxes", Kokkos::RangePolicy<Exec>(exec, 0, tris.extent(0)),
                       SweptTriangleBoxes<Mem, M>{x0, x1, tris, M(margin), boxes});
}

}  // namespace weft
