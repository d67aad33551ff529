// The collision benchmarks' scene: two resting cloth layers, as in layer-stack and the demo. Sheets with
// 1 cm edges, the upper one 4 mm above the lower and offset by half a cell (its points lie over faces),
// thickness 1.8 mm (0.18 x the edge, the demo's rule, so no sheet starts in contact with itself); during
// the substep every point moves by up to 1 mm on each axis. The candidate pairs are then mostly in-layer
// neighbours, and vertex-face contacts between the layers cover the whole sheet.
#pragma once
#include "bench/micro/bench_common.hpp"
#include "bench/micro/cloth_grid.hpp"
#include "collision/collision_handler.hpp"

namespace weft::bench {

template <class Exec>
struct ClothLayers {
  using Mem = typename Exec::memory_space;
  static constexpr real kEdge = 0.01, kGap = 0.004, kThickness = 0.0018, kMotion = 0.001;

  Exec exec;
  long triangles = 0, points = 0;
  Kokkos::View<Vec3*, Mem> xs, x;  // start and end of the substep
  Kokkos::View<int* [3], Mem> tris;
  Kokkos::View<uint8_t*, Mem> rmask;
  Kokkos::View<real*, Mem> thickness, friction, w;
  Kokkos::View<int*, Mem> layer;
  Kokkos::View<Aabb*, Mem> boxes;
  Lbvh<Exec> bvh;
  Kokkos::View<IndexPair*, Mem> pairs{"bench::pairs", 0};
  long npairs = 0;
  NarrowSettings ns;  // the collision handler's defaults, self collision

  // About `n` triangles in all.
  explicit ClothLayers(long n) : bvh(exec) {
    const int res = grid_res(n / 2);
    Sheet cloth = sheet(res, kEdge, 0, 0, 0);
    const Sheet upper = sheet(res, kEdge, kGap, kEdge / 2, kEdge / 2);
    const int first = int(cloth.x.size());
    cloth.x.insert(cloth.x.end(), upper.x.begin(), upper.x.end());
    for (const auto& t : upper.tris) cloth.tris.push_back({first + t[0], first + t[1], first + t[2]});
    triangles = long(cloth.tris.size());
    points = long(cloth.x.size());
    std::vector<Vec3> moved(cloth.x);
    for (long i = 0; i < points; ++i)
      for (int k = 0; k < 3; ++k) moved[i][k] += (2 * unit_random(1, 3 * i + k) - 1) * kMotion;
    std::vector<int> layers(points, 0);
    std::fill(layers.begin() + first, layers.end(), 1);
    xs = upload<Mem>(cloth.x, "bench::x_start");
    x = upload<Mem>(moved, "bench::x");
    tris = upload_triangles<Mem>(cloth.tris);
    rmask = upload<Mem>(representative_features(cloth.tris, int(points)), "bench::rmask");
    thickness = upload<Mem>(std::vector<real>(points, kThickness), "bench::thickness");
    friction = upload<Mem>(std::vector<real>(points, 1.0), "bench::friction");
    w = upload<Mem>(std::vector<real>(points, 1.0), "bench::w");
    layer = upload<Mem>(layers, "bench::layer");
    boxes = Kokkos::View<Aabb*, Mem>("bench::boxes", triangles);
    swept_triangle_boxes(exec, Kokkos::View<const Vec3*, Mem>(xs), Kokkos::View<const Vec3*, Mem>(x),
                         Kokkos::View<const int* [3], Mem>(tris), ns.detect_scale * kThickness, boxes);
    bvh.build(boxes);
    npairs = bvh.query_self(KeepAllPairs{}, pairs);
    exec.fence();
  }

  // The cloth as the narrow phase sees it (CollisionHandler::cloth_side).
  SideMesh<Mem> side() const {
    SideMesh<Mem> m;
    m.x = x; m.xs = xs; m.xo = xs; m.tris = tris; m.rmask = rmask; m.thickness = thickness;
    m.friction = friction; m.dfriction = friction; m.layer = layer;
    return m;
  }
};

}  // namespace weft::bench
