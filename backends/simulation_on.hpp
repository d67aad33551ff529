// Simulation on one execution space; included only by backends/on_backend_impl.hpp (and tests).
#pragma once
#include "backends/simulation.hpp"
#include "collision/collision_handler.hpp"
#include "collision/mesh_intersections.hpp"
#include "solver/solver.hpp"

#include <algorithm>

namespace weft {

template <class Exec>
class SimulationOn final : public Simulation {
 public:
  explicit SimulationOn(const Scene& scene) : solver_(scene), intersections_(scene.triangles) {
    // A scene pays only for the stages it uses: no collision stage without colliders or self collision.
    if (!scene.colliders.empty() || scene.settings.collision.self_collision)
      solver_.set_collision_stage(std::make_unique<CollisionHandler<Exec>>(scene));
  }
  FrameStats step_frame() override { return solver_.step_frame(); }
  FrameStats measure() const override { return solver_.measure(); }
  int frame() const override { return solver_.frame(); }
  uint64_t hash_positions() const override { return solver_.hash_positions(); }
  std::vector<Vec3> positions() const override { return solver_.positions(); }
  std::vector<Vec3> velocities() const override { return solver_.velocities(); }
  void set_state(int frame, const std::vector<Vec3>& x, const std::vector<Vec3>& v) override {
    solver_.set_state(frame, x, v);
  }
  void set_collider_frame(const std::vector<Vec3>& x) override { solver_.set_collider_frame(x); }
  void set_collider_frame(int collider, const std::vector<Vec3>& x) override { solver_.set_collider_frame(collider, x); }
  int colour_count() const override { return solver_.colour_count(); }
  long row_count() const override { return solver_.row_count(); }
  long tether_count() const override { return solver_.tether_count(); }
  real strain_quantile(double q) const override {
    return Solver<Exec>::quantile(solver_.strains(), q);
  }
  long intersections() const override {
    return intersections_.count(Kokkos::View<const Vec3*, typename Exec::memory_space>(solver_.state().x));
  }

 private:
  Solver<Exec> solver_;
  mutable MeshIntersections<Exec> intersections_;  // a diagnostic: its tree is kept between calls
};

}  // namespace weft
