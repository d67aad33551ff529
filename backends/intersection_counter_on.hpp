// IntersectionCounter on one execution space; included only by backends/on_backend_impl.hpp.
#pragma once
#include "backends/intersection_counter.hpp"
#include "collision/mesh_intersections.hpp"
#include "scene/mesh_checks.hpp"

namespace weft {

template <class Exec>
class IntersectionCounterOn final : public IntersectionCounter {
 public:
  IntersectionCounterOn(const std::string& name, const std::vector<std::array<int, 3>>& tris)
      : name_(name), tris_(tris), mesh_(tris) {}
  long count(const std::vector<Vec3>& x) override {
    validate_mesh(name_, x, tris_);
    return mesh_.count(x);
  }
  std::vector<std::array<int, 2>> pairs(const std::vector<Vec3>& x) override {
    validate_mesh(name_, x, tris_);
    return mesh_.pairs(x);
  }

 private:
  std::string name_;
  std::vector<std::array<int, 3>> tris_;
  MeshIntersections<Exec> mesh_;
};

}  // namespace weft
