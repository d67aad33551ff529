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
    if (!scene.colliders.empty() || scene.settings.collision.self_collision) {
      auto handler = std::make_unique<CollisionHandler<Exec>>(scene);
      collisions_ = handler.get();
      solver_.set_collision_stage(std::move(handler));
    }
  }
  FrameStats step_frame() override {
    if (!collisions_) return solver_.step_frame();
    const auto before = collisions_->stats();  // the handler's totals: this frame's are the differences
    FrameStats fs = with_collision_stats(solver_.step_frame());
    const auto& after = collisions_->stats();
    fs.failsafe_points = after.failsafe_points - before.failsafe_points;
    fs.failsafe_rounds = after.failsafe_rounds - before.failsafe_rounds;
    fs.failsafe_pinned = after.failsafe_pinned - before.failsafe_pinned;
    fs.collision_queries = after.queries - before.queries;
    fs.early_passes = after.early_passes - before.early_passes;
    fs.points_cut_back = after.points_cut_back - before.points_cut_back;
    fs.seconds_lbvh_build = after.seconds_lbvh_build - before.seconds_lbvh_build;
    fs.seconds_broad_phase = after.seconds_broad_phase - before.seconds_broad_phase;
    fs.seconds_narrow_phase = after.seconds_narrow_phase - before.seconds_narrow_phase;
    fs.seconds_contact_colouring = after.seconds_contact_colouring - before.seconds_contact_colouring;
    return fs;
  }
  FrameStats measure() const override { return with_collision_stats(solver_.measure()); }
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
  FrameStats with_collision_stats(FrameStats fs) const {
    if (collisions_) {
      fs.contacts = collisions_->stats().contacts;
      fs.impact_zone_points = collisions_->stats().zones.points;
    }
    return fs;
  }
  Solver<Exec> solver_;
  CollisionHandler<Exec>* collisions_ = nullptr;  // owned by solver_
  mutable MeshIntersections<Exec> intersections_;  // a diagnostic: its tree is kept between calls
};

}  // namespace weft
