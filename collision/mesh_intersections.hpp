// A mesh's intersecting triangle pairs (count_intersections, collision/tri_tri.hpp) at positions that change
// from call to call, such as a simulation's frames or a cache's: the triangles go to the device once, and the
// tree and its buffers are kept.
#pragma once
#include "collision/tri_tri.hpp"
#include "core/device_copy.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace weft {

template <class Exec>
class MeshIntersections {
 public:
  using Mem = typename Exec::memory_space;

  explicit MeshIntersections(const std::vector<std::array<int, 3>>& tris)
      : tris_(upload_table<Mem>(tris, "weft::mesh_tris")) {}

  // Positions on the device.
  long count(Kokkos::View<const Vec3*, Mem> x) { return count_intersections(bvh_, x, Kokkos::View<const int* [3], Mem>(tris_)); }

  // Positions on the host, copied into a device buffer kept from call to call.
  long count(const std::vector<Vec3>& x) { return count(upload(x)); }

  // The intersecting pairs (i < j) at positions on the host, sorted.
  std::vector<std::array<int, 2>> pairs(const std::vector<Vec3>& x) {
    const long n = count_intersections(bvh_, upload(x), Kokkos::View<const int* [3], Mem>(tris_), pairs_);
    const std::vector<IndexPair> found = to_host(Kokkos::subview(pairs_, std::make_pair(0L, n)));
    std::vector<std::array<int, 2>> out;
    for (const IndexPair& p : found) out.push_back({p.first, p.second});
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  Lbvh<Exec> bvh_;
  Kokkos::View<int* [3], Mem> tris_;
  Kokkos::View<const Vec3*, Mem> upload(const std::vector<Vec3>& x) {
    if (x_.extent(0) != x.size()) x_ = Kokkos::View<Vec3*, Mem>("weft::mesh_x", x.size());
    copy_to_device(x_, x);
    return x_;
  }

  Kokkos::View<Vec3*, Mem> x_;
  Kokkos::View<IndexPair*, Mem> pairs_;
};

}  // namespace weft
