// The XPBD frame loop (see docs/solver.md). A frame = substeps x (predict; iterations of multi-colour
// Gauss-Seidel over every constraint row, with collision passes spread among them; Jacobi smoothing;
// velocity update). Positions, rows and contacts stay on the device; inside a frame only counts and sums
// that size or decide the next launches are read back (docs/solver.md), and the statistics after it.
#pragma once
#include "collision/collision_stage.hpp"
#include "constraints/build_coarse_levels.hpp"
#include "constraints/build_rows.hpp"
#include "constraints/build_stretch_limits.hpp"
#include "constraints/build_tethers.hpp"
#include "constraints/triangle_strain.hpp"
#include "core/colouring.hpp"
#include "core/device_copy.hpp"
#include "core/error.hpp"
#include "core/hash.hpp"
#include "core/kokkos_compat.hpp"
#include "core/reduce.hpp"
#include "core/stage_timer.hpp"
#include "scene/collider_set.hpp"
#include "scene/scene.hpp"
#include "solver/frame_stats.hpp"
#include "solver/solver_kernels.hpp"

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace weft {

template <class Exec>
class Solver {
 public:
  using Mem = typename Exec::memory_space;
  template <class T>
  using View = Kokkos::View<T, Mem>;

  explicit Solver(const Scene& scene) : st_(scene.settings), frame_(scene.settings.frame_start) {
    validate_scene(scene);
    fem_rows_ = !scene.constraints.fem.empty();
    upload_points(scene);
    upload_animation(scene);
    upload_rows(scene);
    state_.exec = exec_;
  }

  const SolverState<Exec>& state() const { return state_; }
  const SolverSettings& settings() const { return st_; }
  int frame() const { return frame_; }
  int colour_count() const { return int(colour_kinds_.size()); }
  long row_count() const { return long(lambda_.extent(0)); }
  long tether_count() const { return long(tethers_.extent(0)); }
  // Bytes of the packed rows on the device (each sweep reads them all).
  long row_storage_bytes() const { return row_storage_bytes_; }
  void set_collision_stage(std::unique_ptr<CollisionStage<Exec>> c) {
    collision_ = std::move(c);
    if (collision_ && chebyshev_on()) cheb_xc_ = View<Vec3*>("weft::chebyshev_xc", state_.x.extent(0));
  }

  // Streamed colliders: every collider vertex, concatenated in the scene's collider order, at the end of the
  // frame the next step_frame() steps; its substeps move the colliders linearly from where they are to
  // there. From the first call on, the scene's collider animation is no longer used: a frame stepped without
  // a new call keeps the colliders where the last one put them.
  void set_collider_frame(const std::vector<Vec3>& x) {
    const size_t n = state_.collider_x.extent(0);
    if (x.size() != n)
      throw InputError("collider frame has " + std::to_string(x.size()) + " vertices, the scene's colliders " +
                       std::to_string(n));
    stream_colliders();
    copy_to_device(collider_frame_end_, x);
  }
  // The same for collider `collider` of the scene alone; the others keep their last streamed positions.
  void set_collider_frame(int collider, const std::vector<Vec3>& x) {
    const int nc = int(collider_first_vertex_.size()) - 1;
    if (collider < 0 || collider >= nc)
      throw InputError("collider " + std::to_string(collider) + " does not exist: the scene has " + std::to_string(nc) +
                       " colliders");
    const long begin = collider_first_vertex_[size_t(collider)], end = collider_first_vertex_[size_t(collider) + 1];
    if (long(x.size()) != end - begin)
      throw InputError("frame of collider " + std::to_string(collider) + " has " + std::to_string(x.size()) +
                       " vertices, the collider " + std::to_string(end - begin));
    stream_colliders();
    copy_to_device(Kokkos::subview(collider_frame_end_, Kokkos::make_pair(begin, end)), x);
  }

  // Advances from frame() to frame() + 1.
  FrameStats step_frame() {
    const auto t0 = std::chrono::steady_clock::now();
    schedule_ = ScheduleStats{};
    if (collision_) collision_->begin_frame();
    if (colliders_streamed_) Kokkos::deep_copy(exec_, collider_frame_start_, state_.collider_x);
    for (int s = 0; s < st_.substeps; ++s) substep(s);
    if (collision_) collision_->end_frame(state_);
    ++frame_;
    exec_.fence();
    const double solve = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    FrameStats fs = measure();
    fs.schedule = schedule_;
    fs.seconds = solve;
    return fs;
  }

  uint64_t hash_positions() const { return hash_view(exec_, state_.x); }

  std::vector<Vec3> positions() const { return to_host(state_.x); }

  void set_state(int frame, const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
    if (x.size() != state_.x.extent(0) || v.size() != state_.v.extent(0))
      throw InputError("saved state has " + std::to_string(x.size()) + " points, the scene " +
                       std::to_string(state_.x.extent(0)));
    copy_to_device(state_.x, x);
    copy_to_device(state_.v, v);
    frame_ = frame;
    // Animated goals and colliders at the new frame, as an uninterrupted run would have them; streamed
    // colliders follow the scene's animation again until the next set_collider_frame.
    const real t = real(frame_ - st_.frame_start);
    kernels::interpolate_animation(exec_, target_frames_, targets_, t);
    kernels::interpolate_animation(exec_, collider_frames_, state_.collider_x, t);
    colliders_streamed_ = false;
  }
  std::vector<Vec3> velocities() const { return to_host(state_.v); }

  // Statistics of the current state, with the collision stage's figures of the last frame.
  FrameStats measure() const {
    FrameStats fs;
    fs.frame = frame_;
    if (collision_) fs.collision = collision_->frame_stats();
    const long n = long(state_.x.extent(0));
    auto x = state_.x, v = state_.v;
    auto w = state_.w;
    auto mass = mass_;
    auto e = scratch_;
    Kokkos::parallel_for("weft::stats_energy", Kokkos::RangePolicy<Exec>(exec_, 0, n),
                         kernels::KineticEnergy<Mem>{v, w, mass, e});
    fs.kinetic_energy = reduce_fixed(exec_, e, SumOp{});
    Kokkos::parallel_for("weft::stats_speed2", Kokkos::RangePolicy<Exec>(exec_, 0, n), kernels::SpeedSquared<Mem>{v, w, e});
    fs.max_speed = sqrt_(reduce_fixed(exec_, e, MaxOp{}));
    const real sum_v2 = reduce_fixed(exec_, e, SumOp{});
    fs.rms_speed = movable_ > 0 ? sqrt_(sum_v2 / real(movable_)) : 0.0;
    const auto edges = edge_strains();
    if (edges.extent(0) > 0) fs.max_edge_strain = max_(real(0), reduce_fixed(exec_, edges, MaxOp{}));  // -1: rest 0
    const std::vector<real> strain = strains();  // copied back once: the max is exact, the percentile needs them all
    for (real e : strain) fs.max_strain = max_(fs.max_strain, e);
    fs.p99_strain = quantile(strain, 0.99);
    const long nk = long(kin_point_.extent(0)), ns = long(still_point_.extent(0));
    if (nk + ns > 0) {
      const auto lag = Kokkos::subview(e, Kokkos::make_pair(0L, nk + ns));
      Kokkos::parallel_for("weft::stats_pin_lag", Kokkos::RangePolicy<Exec>(exec_, 0, nk + ns),
                           kernels::PinLag<Mem>{kin_point_, kin_target_, targets_, still_point_, still_at_, x, lag});
      fs.max_pin_lag = reduce_fixed(exec_, lag, MaxOp{});
    }
    long bad = 0;
    Kokkos::parallel_reduce("weft::stats_finite", Kokkos::RangePolicy<Exec>(exec_, 0, n),
                            kernels::CountNonFinite<Mem>{x}, bad);
    fs.non_finite = bad;
    return fs;
  }

  // The strain of every cloth triangle at the current positions (constraints/triangle_strain.hpp), or of
  // every distance row (|length / rest - 1|) in a scene without triangles; copied back, for percentiles.
  std::vector<real> strains() const {
    if (tri_rest_.extent(0) > 0) return to_host(triangle_strains());
    std::vector<real> all = to_host(edge_strains()), out;
    for (real e : all)
      if (e >= 0) out.push_back(e);
    return out;
  }

  // The q-quantile (0..1) of v, nearest rank; 0 for none.
  static real quantile(std::vector<real> v, double q) {
    if (v.empty()) return 0;
    const size_t k = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
  }

  // One substep.
  void substep(int s) {
    const real h = 1 / (st_.fps * st_.substeps);
    const real t_end = real(frame_ - st_.frame_start) + real(s + 1) / real(st_.substeps);
    if (colliders_streamed_) {
      // The frame's start and end stand as stored frames f and f + 1, so that t_end picks and weighs them as
      // it does a full animation's frames: the same bits where they hold the same positions.
      const long f = frame_ - st_.frame_start;
      const kernels::FramePair p = kernels::frame_pair(t_end, f + 2);
      Kokkos::deep_copy(exec_, state_.collider_x_start, state_.collider_x);
      kernels::interpolate(exec_, p.f0 == f ? collider_frame_start_ : collider_frame_end_,
                           p.f1 == f ? collider_frame_start_ : collider_frame_end_, p.a, state_.collider_x);
    } else if (collider_frames_.extent(0) > 0) {
      Kokkos::deep_copy(exec_, state_.collider_x_start, state_.collider_x);
      kernels::interpolate_animation(exec_, collider_frames_, state_.collider_x, t_end);
    }
    Kokkos::deep_copy(exec_, targets_before_, targets_);
    kernels::interpolate_animation(exec_, target_frames_, targets_, t_end);
    Kokkos::parallel_for("weft::predict", Kokkos::RangePolicy<Exec>(exec_, 0, state_.x.extent(0)),
                         kernels::Predict<Mem>{state_.x, state_.x_start, state_.v, state_.w, st_.gravity + st_.wind,
                                               max_(real(0), 1 - st_.velocity_damping * h), h});
    Kokkos::parallel_for("weft::kinematic", Kokkos::RangePolicy<Exec>(exec_, 0, kin_point_.extent(0)),
                         kernels::FollowTargets<Mem>{kin_point_, kin_target_, targets_, targets_before_, state_.x,
                                                       kPinCatchUp});
    // Before the first collision pass, so that what the coarse levels move counts as the prediction: cut
    // back by the bounds, the rest is handed on to the next queries (a move cut back after a sweep is lost).
    if (coarse_levels() > 0) timed_stage("weft::coarse_levels", st_.profile, schedule_.seconds_constraints, [&] { coarse_cycle(h); });
    Kokkos::deep_copy(exec_, lambda_, 0.0);
    if (collision_) collision_->begin_substep(state_, h, s);
    const int P = collision_ ? st_.collision_passes : 0, I = st_.iterations;
    int next_pass = 0;
    auto timed = [this](const char* region, double& acc, auto&& stage) { timed_stage(region, st_.profile, acc, stage); };
    auto collision_pass = [&] {
      timed("weft::collision_pass", schedule_.seconds_collision_passes, [&] { collision_->pass(state_, h); });
      ++schedule_.collision_passes;
      ++next_pass;
    };
    for (int it = 0; it < I; ++it) {
      while (next_pass < P && (long(next_pass) * I) / P == it) collision_pass();
      timed("weft::constraints", schedule_.seconds_constraints, [&] {
        const real omega = chebyshev_omega(it);
        const bool saving = chebyshev_on() && it + 1 >= st_.chebyshev_delay;
        if (saving) {
          const long np = long(state_.x.extent(0)), nr = long(lambda_.extent(0));
          const kernels::ChebyshevSave<Mem, Vec3> points{state_.x, cheb_xk_, cheb_xkm1_};
          // After a blend, the blend saved the multipliers already.
          if (it > 0 && chebyshev_omega(it - 1) != 1)
            Kokkos::parallel_for("weft::chebyshev_save", Kokkos::RangePolicy<Exec>(exec_, 0, np), points);
          else
            Kokkos::parallel_for("weft::chebyshev_save", Kokkos::RangePolicy<Exec>(exec_, 0, std::max(np, nr)),
                                 kernels::BothElementwise<kernels::ChebyshevSave<Mem, Vec3>, kernels::ChebyshevSave<Mem, real>>{
                                     points, {lambda_, cheb_lk_, cheb_lkm1_}, np, nr});
        }
        gauss_seidel_sweep(h);
        // Tethers are limits, not targets: the blend must not leave a point past its tether.
        const bool tethers = tethers_.extent(0) > 0;
        const bool keep = saving && cheb_xc_.extent(0) > 0;  // the points as this iteration leaves them
        const bool blend_keeps = omega != 1 && !tethers;      // the blend writes them, else a copy does
        if (omega != 1) {
          // The points and the multipliers in one launch.
          const long np = long(state_.x.extent(0)), nr = long(lambda_.extent(0));
          Kokkos::parallel_for("weft::chebyshev_blend", Kokkos::RangePolicy<Exec>(exec_, 0, std::max(np, nr)),
                               kernels::BothElementwise<kernels::ChebyshevBlend<Mem>, kernels::ChebyshevBlendLambda<Mem>>{
                                   {state_.x, cheb_xk_, cheb_xkm1_, cheb_xc_, state_.w, omega, keep && blend_keeps},
                                   {lambda_, cheb_lk_, cheb_lkm1_, omega},
                                   np,
                                   nr});
          if (tethers)
            Kokkos::parallel_for("weft::project_tethers", Kokkos::RangePolicy<Exec>(exec_, 0, tethers_.extent(0)),
                                 kernels::ProjectTethers<Mem>{tethers_, state_.x});
        }
        if (keep && !blend_keeps) Kokkos::deep_copy(exec_, cheb_xc_, state_.x);
      });
      if (!collision_) continue;
      timed("weft::contacts", schedule_.seconds_contacts, [&] { collision_->project(state_, h); });
      // An early pass (proximity contacts, when many points were cut back), unless one is scheduled next.
      const bool scheduled_next = next_pass < P && (long(next_pass) * I) / P == it + 1;
      if (it + 1 < I && !scheduled_next && collision_->wants_pass(state_)) {
        timed("weft::collision_pass", schedule_.seconds_collision_passes, [&] { collision_->pass(state_, h); });
        ++schedule_.collision_passes;
      }
    }
    while (next_pass < P) collision_pass();
    timed("weft::smoothing_sweeps", schedule_.seconds_constraints, [&] {
      for (int it = 0; it < st_.smoothing_iterations; ++it) jacobi_sweep(h);
    });
    if (collision_) timed("weft::finish_positions", schedule_.seconds_failsafe, [&] { collision_->finish_positions(state_, h); });
    Kokkos::parallel_for("weft::velocity", Kokkos::RangePolicy<Exec>(exec_, 0, state_.x.extent(0)),
                         kernels::UpdateVelocity<Mem>{state_.x, state_.x_start, state_.v, h});
    if (collision_) timed("weft::impact_zones", schedule_.seconds_smoothing, [&] { collision_->end_substep(state_, h); });
  }

  // Not with the ccd model: it stays the paper's solver, for comparison; not with FEM membrane rows, whose
  // stable neo-Hookean pair it carries past their balance (docs/solver.md).
  bool chebyshev_on() const {
    return st_.chebyshev_rho > 0 && !fem_rows_ && st_.collision.contact_model == ContactModel::Proximity;
  }

  // The Chebyshev weight of iteration `it` of a substep: 1 before the delay S, then 2 / (2 - rho^2) at S and
  // 4 / (4 - rho^2 omega) after (Wang 2015), computed on the host so that every backend blends by the same bits.
  real chebyshev_omega(int it) const {
    if (!chebyshev_on() || it < st_.chebyshev_delay) return 1;
    const real r2 = st_.chebyshev_rho * st_.chebyshev_rho;
    real omega = 2 / (2 - r2);
    for (int k = st_.chebyshev_delay + 1; k <= it; ++k) omega = 4 / (4 - r2 * omega);
    return omega;
  }

  // One Gauss-Seidel sweep, then the tethers, recorded once as a graph, so that on the device a sweep is one
  // graph launch. Each colour is a kernel per row kind: on the device the kinds of a colour side by side, on
  // the host one after another, since Kokkos 3.4's host graphs walk every path back to the root at each
  // submit, which grows as 2^joins.
  void gauss_seidel_sweep(real h) {
    if (colour_kinds_.empty() && tethers_.extent(0) == 0) return;
    if (!sweep_ || sweep_h_ != h) {
      constexpr bool side_by_side = !Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
      // (void): emplace returns the graph, whose type Kokkos marks [[nodiscard]].
      (void)sweep_.emplace(compat::create_graph(exec_, [&](const compat::GraphNode<Exec>& root) {
        compat::GraphNode<Exec> node = root;
        for (const std::vector<KindRange>& colour : colour_kinds_) {
          if (!side_by_side) {
            for (const KindRange& k : colour) node = project_kind(node, k, h);
            continue;
          }
          std::optional<compat::GraphNode<Exec>> done;
          for (const KindRange& k : colour) {
            const compat::GraphNode<Exec> n = project_kind(node, k, h);
            done = done ? compat::when_all(*done, n) : n;
          }
          if (done) node = *done;
        }
        const long nt = long(tethers_.extent(0));
        if (nt > 0)
          (void)node.then_parallel_for("weft::project_tethers", Kokkos::RangePolicy<Exec>(exec_, 0, nt),
                                       kernels::ProjectTethers<Mem>{tethers_, state_.x});
      }));
      sweep_h_ = h;
    }
    sweep_->submit();
  }

  int coarse_levels() const { return int(coarse_colours_.size()); }

  // The coarse levels, coarsest first (constraints/build_coarse_levels.hpp): each level's rows swept
  // coarse_iterations times, then its followers moved with their parents; recorded once as a graph.
  void coarse_cycle(real h) {
    Kokkos::deep_copy(exec_, coarse_xs_, state_.x);
    Kokkos::deep_copy(exec_, coarse_lambda_, 0.0);
    if (!coarse_ || coarse_h_ != h) {
      (void)coarse_.emplace(compat::create_graph(exec_, [&](const compat::GraphNode<Exec>& root) {
        compat::GraphNode<Exec> node = root;
        for (int l = coarse_levels() - 1; l >= 0; --l) {
          for (int it = 0; it < st_.coarse_iterations; ++it)
            for (const std::pair<long, long>& c : coarse_colours_[size_t(l)])
              node = node.then_parallel_for(
                  "weft::coarse_rows", Kokkos::RangePolicy<Exec>(exec_, c.first, c.second),
                  kernels::ProjectRows<Mem, kRowDistance>{coarse_rows_, 0, materials_, state_.x, state_.x_start,
                                                          state_.w, coarse_lambda_,
                                                          RowContext<Mem>{targets_, state_.collider_x}, h});
          const std::pair<long, long> f = coarse_followers_[size_t(l)];
          if (f.second > f.first) {
            const auto range = Kokkos::make_pair(f.first, f.second);
            node = node.then_parallel_for(
                "weft::coarse_follow", Kokkos::RangePolicy<Exec>(exec_, 0, f.second - f.first),
                kernels::FollowParents<Mem>{Kokkos::subview(coarse_follower_, range), coarse_parent_,
                                            Kokkos::subview(coarse_offset_, range), coarse_weight_, state_.w,
                                            coarse_xs_, state_.x});
          }
        }
      }));
      coarse_h_ = h;
    }
    coarse_->submit();
  }

  // Vellum's smoothing: every row computes its correction from the same positions, and each point moves
  // by the average of the corrections it receives (gathered in the rows' colour order: deterministic). A
  // kernel per row kind, then one over the points; on the device recorded once as a graph, the kinds side by
  // side.
  void jacobi_sweep(real h) {
    const long n = long(state_.x.extent(0));
    const kernels::JacobiPoints<Mem> points{point_slot_offset_, point_slot_, row_delta_, state_.x};
    const auto rows_node = [&](const auto& after, int kind) {
      return with_row_kind(kind, [&](auto k) -> compat::GraphNode<Exec> {
        constexpr int K = decltype(k)::value;
        return after.then_parallel_for(
            "weft::jacobi_rows", Kokkos::RangePolicy<Exec>(exec_, kind_begin_[K], kind_begin_[K + 1]),
            kernels::JacobiRows<Mem, K>{rows_of<K>(), kind_begin_[K], row_count(), materials_, state_.x,
                                        state_.x_start, row_delta_, state_.w, lambda_,
                                        RowContext<Mem>{targets_, state_.collider_x}, h});
      });
    };
    if (!smooth_ || smooth_h_ != h) {
      constexpr bool side_by_side = !Kokkos::SpaceAccessibility<Kokkos::HostSpace, Mem>::accessible;
      (void)smooth_.emplace(compat::create_graph(exec_, [&](const compat::GraphNode<Exec>& root) {
        compat::GraphNode<Exec> node = root;
        std::optional<compat::GraphNode<Exec>> done;
        for (int kind = 0; kind < kRowKinds; ++kind) {
          if (kind_begin_[kind + 1] == kind_begin_[kind]) continue;
          if (!side_by_side) { node = rows_node(node, kind); continue; }
          const compat::GraphNode<Exec> k = rows_node(root, kind);
          done = done ? compat::when_all(*done, k) : k;
        }
        if (done) node = *done;
        (void)node.then_parallel_for("weft::jacobi_points", Kokkos::RangePolicy<Exec>(exec_, 0, n), points);
      }));
      smooth_h_ = h;
    }
    smooth_->submit();
  }

 private:
  // The rows [begin, end) of one colour, all of one kind.
  struct KindRange {
    long begin, end;
    int kind;
  };

  // A node projecting the rows of k after `after`, by the kernel compiled for k's kind.
  compat::GraphNode<Exec> project_kind(const compat::GraphNode<Exec>& after, const KindRange& k, real h) const {
    return with_row_kind(k.kind, [&](auto kind) -> compat::GraphNode<Exec> {
      constexpr int K = decltype(kind)::value;
      return after.then_parallel_for(
          "weft::project_rows", Kokkos::RangePolicy<Exec>(exec_, k.begin, k.end),
          kernels::ProjectRows<Mem, K>{rows_of<K>(), kind_begin_[K], materials_, state_.x, state_.x_start, state_.w,
                                       lambda_, RowContext<Mem>{targets_, state_.collider_x}, h});
    });
  }

  // The packed rows of kind K, the rows [kind_begin_[K], kind_begin_[K + 1]) of all.
  template <int K>
  const View<PackedRow<K>*>& rows_of() const { return std::get<K>(packed_); }

  View<real*> triangle_strains() const {
    const auto out = Kokkos::subview(row_scratch_, Kokkos::make_pair(0L, long(tri_rest_.extent(0))));
    Kokkos::parallel_for("weft::stats_triangle_strain", Kokkos::RangePolicy<Exec>(exec_, 0, tri_rest_.extent(0)),
                         kernels::TriangleStrain<Mem>{tri_rest_, state_.x, out});
    return out;
  }

  // |length / rest - 1| of every distance row at the current positions (-1: rest length 0, or a stretch
  // limit, which is not an edge).
  View<real*> edge_strains() const {
    const long nd = kind_begin_[kRowDistance + 1] - kind_begin_[kRowDistance];
    const auto strain = Kokkos::subview(row_scratch_, Kokkos::make_pair(0L, nd));
    Kokkos::parallel_for("weft::stats_strain", Kokkos::RangePolicy<Exec>(exec_, 0, nd),
                         kernels::EdgeStrain<Mem>{rows_of<kRowDistance>(), materials_, state_.x, strain});
    return strain;
  }

  // Fraction of its lag a pinned point held back (by the ccd model's fail-safe, or by its bound where the
  // cloth jams) closes per substep before the bounds apply.
  static constexpr real kPinCatchUp = 0.25;

  void upload_points(const Scene& sc) {
    const ClothPoints& p = sc.points;
    const size_t n = p.size();
    std::vector<real> w(n);
    std::vector<char> kinematic(n, 0);
    for (int k : sc.kinematic_point) kinematic[k] = 1;
    movable_ = 0;
    std::vector<int> still;
    std::vector<Vec3> still_at;
    for (size_t i = 0; i < n; ++i) {
      w[i] = !p.still(i) && !kinematic[i] ? 1 / p.mass[i] : 0.0;
      movable_ += w[i] > 0;
      if (p.still(i) && !kinematic[i]) {
        still.push_back(int(i));
        still_at.push_back(p.position[i]);
      }
    }
    still_point_ = upload<Mem>(still, "weft::still_point");
    still_at_ = upload<Mem>(still_at, "weft::still_at");
    state_.x = upload<Mem>(p.position, "weft::x");
    state_.v = upload<Mem>(p.velocity, "weft::v");
    state_.x_start = View<Vec3*>("weft::x_start", n);
    state_.w = upload<Mem>(w, "weft::w");
    mass_ = upload<Mem>(p.mass, "weft::mass");
    scratch_ = View<real*>("weft::scratch", n);
    if (chebyshev_on()) {
      cheb_xk_ = View<Vec3*>("weft::chebyshev_xk", n);
      cheb_xkm1_ = View<Vec3*>("weft::chebyshev_xkm1", n);
    }
    w_host_ = w;
  }

  void upload_animation(const Scene& sc) {
    target_frames_ = upload_frames<Mem>(sc.pin_targets.frames, "weft::target_frames");
    targets_ = View<Vec3*>("weft::targets", target_frames_.extent(1));
    targets_before_ = View<Vec3*>("weft::targets_before", target_frames_.extent(1));
    kernels::interpolate_animation(exec_, target_frames_, targets_, 0.0);
    kin_point_ = upload<Mem>(sc.kinematic_point, "weft::kin_point");
    kin_target_ = upload<Mem>(sc.kinematic_target, "weft::kin_target");
    // The collider set's vertices at every stored frame; shorter animations hold their last frame.
    const ColliderSet cs = make_collider_set(sc.colliders);
    std::vector<std::vector<Vec3>> frames(size_t(cs.frames));
    for (int f = 0; f < cs.frames; ++f) frames[size_t(f)] = collider_positions(sc.colliders, cs, f);
    collider_first_vertex_ = cs.first_vertex;
    collider_frames_ = upload_frames<Mem>(frames, "weft::collider_frames");
    state_.collider_x = View<Vec3*>("weft::collider_x", collider_frames_.extent(1));
    state_.collider_x_start = View<Vec3*>("weft::collider_x_start", collider_frames_.extent(1));
    kernels::interpolate_animation(exec_, collider_frames_, state_.collider_x, 0.0);
    Kokkos::deep_copy(state_.collider_x_start, state_.collider_x);
  }

  // Switches the colliders to streamed frames, the end of the next frame where they are now until set.
  void stream_colliders() {
    if (colliders_streamed_) return;
    const size_t n = state_.collider_x.extent(0);
    if (collider_frame_end_.extent(0) != n) {
      collider_frame_start_ = View<Vec3*>("weft::collider_frame_start", n);
      collider_frame_end_ = View<Vec3*>("weft::collider_frame_end", n);
    }
    Kokkos::deep_copy(collider_frame_end_, state_.collider_x);
    colliders_streamed_ = true;
    if (collision_) collision_->colliders_streamed();
  }

  void upload_rows(const Scene& sc) {
    std::vector<Row> rows = build_rows(sc, collider_first_vertex_);
    for (const Row& r : build_stretch_limits(sc, w_host_)) rows.push_back(r);
    const size_t n = sc.points.size(), nr = rows.size();
    std::vector<char> movable(n);
    for (size_t i = 0; i < n; ++i) movable[i] = w_host_[i] > 0;
    const Colouring col = colour_greedy(long(nr), long(n), movable, [&](long r, int(&out)[8]) {
      return row_particles(rows[r], out);
    });
    // Rows by kind, then colour, each (kind, colour) in input order (a stable counting sort): every kind's
    // rows are contiguous, and so are a colour's rows of one kind. The order inside a colour changes no
    // result, since its rows share no moving point.
    const long nc = col.count;
    std::vector<long> key_offset(size_t(kRowKinds * nc) + 1, 0);
    const auto key = [&](size_t r) { return size_t(rows[r].kind * nc + col.colour[r]); };
    for (size_t r = 0; r < nr; ++r) ++key_offset[key(r) + 1];
    for (size_t k = 0; k + 1 < key_offset.size(); ++k) key_offset[k + 1] += key_offset[k];
    std::vector<long> place(nr), fill(key_offset.begin(), key_offset.end() - 1);
    for (size_t r = 0; r < nr; ++r) place[r] = fill[key(r)]++;
    for (int k = 0; k <= kRowKinds; ++k) kind_begin_[k] = key_offset[size_t(k * nc)];
    colour_kinds_.assign(size_t(nc), {});
    for (long c = 0; c < nc; ++c)
      for (int k = 0; k < kRowKinds; ++k)
        if (key_offset[size_t(k * nc + c) + 1] > key_offset[size_t(k * nc + c)])
          colour_kinds_[size_t(c)].push_back({key_offset[size_t(k * nc + c)], key_offset[size_t(k * nc + c) + 1], k});
    // Materials, each stored once; a row keeps its index.
    MaterialTable materials;
    std::vector<int> material(nr);
    for (size_t r = 0; r < nr; ++r) material[r] = materials.index(rows[r].m);
    upload_coarse_levels(sc, materials);
    materials_ = upload<Mem>(materials.all, "weft::materials");
    std::vector<size_t> by_place(nr);
    for (size_t r = 0; r < nr; ++r) by_place[size_t(place[r])] = r;
    upload_packed(rows, material, by_place, std::make_integer_sequence<int, kRowKinds>{});
    tethers_ = upload<Mem>(build_tethers(sc, w_host_), "weft::tethers");
    lambda_ = View<real*>("weft::lambda", nr);
    if (chebyshev_on()) {
      cheb_lk_ = View<real*>("weft::chebyshev_lk", nr);
      cheb_lkm1_ = View<real*>("weft::chebyshev_lkm1", nr);
    }
    tri_rest_ = upload<Mem>(triangle_rest_shapes(sc), "weft::triangle_rest");
    row_scratch_ = View<real*>("weft::row_scratch", std::max(nr, tri_rest_.extent(0)));
    // Jacobi gather lists: for each point, the (row, slot) entries that move it, in colour order (the
    // order of the sum, so it is kept apart from the storage order).
    if (st_.smoothing_iterations > 0) {
      std::vector<size_t> by_colour(nr);
      std::vector<long> colour_fill(size_t(nc) + 1, 0);
      for (size_t r = 0; r < nr; ++r) ++colour_fill[size_t(col.colour[r]) + 1];
      for (long c = 0; c < nc; ++c) colour_fill[size_t(c) + 1] += colour_fill[size_t(c)];
      for (size_t r = 0; r < nr; ++r) by_colour[size_t(colour_fill[size_t(col.colour[r])]++)] = r;
      std::vector<long> off(n + 1, 0), slots;
      for (const Row& r : rows)
        for (int k = 0; k < r.n; ++k) ++off[r.idx[k] + 1];
      for (size_t i = 0; i < n; ++i) off[i + 1] += off[i];
      slots.resize(off[n]);
      std::vector<long> pos(off.begin(), off.end() - 1);
      for (size_t r : by_colour)
        for (int k = 0; k < rows[r].n; ++k) slots[pos[rows[r].idx[k]]++] = long(k) * long(nr) + place[r];
      point_slot_offset_ = upload<Mem>(off, "weft::point_slot_offset");
      point_slot_ = upload<Mem>(slots, "weft::point_slot");
      row_delta_ = View<Vec3*>("weft::row_delta", 5 * nr);
    }
  }

  // The rows' materials, each stored once, told apart by their bits (-0 and 0 stay apart).
  struct MaterialTable {
    std::vector<XpbdMaterial> all;
    std::map<std::array<uint64_t, 3>, int> by_bits;
    int index(const XpbdMaterial& m) {
      static_assert(sizeof(real) == sizeof(uint64_t));
      std::array<uint64_t, 3> bits;
      std::memcpy(bits.data(), &m.compliance, 8);
      std::memcpy(bits.data() + 1, &m.compress_compliance, 8);
      std::memcpy(bits.data() + 2, &m.damping_ratio, 8);
      const auto [it, added] = by_bits.try_emplace(bits, int(all.size()));
      if (added) all.push_back(m);
      return it->second;
    }
  };

  // The coarse levels' rows, by level then colour (their materials added to the table), and their followers.
  void upload_coarse_levels(const Scene& sc, MaterialTable& materials) {
    const std::vector<CoarseLevel> levels = build_coarse_levels(sc, w_host_);
    const size_t n = sc.points.size();
    std::vector<char> movable(n);
    for (size_t i = 0; i < n; ++i) movable[i] = w_host_[i] > 0;
    std::vector<PackedRow<kRowDistance>> rows;
    std::vector<int> follower, parent;
    std::vector<long> offset(1, 0);
    std::vector<real> weight;
    coarse_colours_.assign(levels.size(), {});
    coarse_followers_.clear();
    for (size_t l = 0; l < levels.size(); ++l) {
      const CoarseLevel& lv = levels[l];
      const Colouring col = colour_greedy(long(lv.rows.size()), long(n), movable, [&](long r, int(&out)[8]) {
        return row_particles(lv.rows[size_t(r)], out);
      });
      for (int c = 0; c < col.count; ++c) {
        const long begin = long(rows.size());
        for (size_t r = 0; r < lv.rows.size(); ++r) {
          if (col.colour[r] == c) rows.push_back(pack_row<kRowDistance>(lv.rows[r], materials.index(lv.rows[r].m)));
        }
        coarse_colours_[l].push_back({begin, long(rows.size())});
      }
      const long first = long(follower.size());
      for (size_t k = 0; k < lv.follower.size(); ++k) {
        follower.push_back(lv.follower[k]);
        for (long j = lv.offset[k]; j < lv.offset[k + 1]; ++j) {
          parent.push_back(lv.parent[size_t(j)]);
          weight.push_back(lv.weight[size_t(j)]);
        }
        offset.push_back(long(parent.size()));
      }
      coarse_followers_.push_back({first, long(follower.size())});
    }
    if (levels.empty()) return;
    coarse_rows_ = upload<Mem>(rows, "weft::coarse_rows");
    coarse_lambda_ = View<real*>("weft::coarse_lambda", rows.size());
    coarse_follower_ = upload<Mem>(follower, "weft::coarse_follower");
    coarse_offset_ = upload<Mem>(offset, "weft::coarse_offset");
    coarse_parent_ = upload<Mem>(parent, "weft::coarse_parent");
    coarse_weight_ = upload<Mem>(weight, "weft::coarse_weight");
    coarse_xs_ = View<Vec3*>("weft::coarse_xs", n);
  }

  // Every kind's packed rows, from the rows in storage order (by_place) and their material indices.
  template <int... K>
  void upload_packed(const std::vector<Row>& rows, const std::vector<int>& material, const std::vector<size_t>& by_place,
                     std::integer_sequence<int, K...>) {
    const auto one = [&](auto kind) {
      constexpr int Kind = decltype(kind)::value;
      std::vector<PackedRow<Kind>> packed;
      packed.reserve(size_t(kind_begin_[Kind + 1] - kind_begin_[Kind]));
      for (long p = kind_begin_[Kind]; p < kind_begin_[Kind + 1]; ++p) {
        const size_t r = by_place[size_t(p)];
        packed.push_back(pack_row<Kind>(rows[r], material[r]));
      }
      std::get<Kind>(packed_) = upload<Mem>(packed, "weft::rows");
      row_storage_bytes_ += long(packed.size() * sizeof(PackedRow<Kind>));
    };
    (one(std::integral_constant<int, K>{}), ...);
  }

  template <int... K>
  static auto packed_views(std::integer_sequence<int, K...>) -> std::tuple<View<PackedRow<K>*>...>;
  using PackedViews = decltype(packed_views(std::make_integer_sequence<int, kRowKinds>{}));

  Exec exec_;
  SolverSettings st_;
  int frame_;
  long movable_ = 0;
  SolverState<Exec> state_;
  View<real*> mass_, scratch_, row_scratch_, lambda_;
  std::vector<real> w_host_;
  PackedViews packed_;                   // the rows of each kind
  long kind_begin_[kRowKinds + 1] = {};  // kind K's rows are [kind_begin_[K], kind_begin_[K + 1]) of all
  View<XpbdMaterial*> materials_;
  long row_storage_bytes_ = 0;
  View<Tether*> tethers_;
  View<TriangleRest*> tri_rest_;  // for the strain statistics
  std::vector<std::vector<KindRange>> colour_kinds_;  // per colour, its rows by kind
  View<Vec3**> target_frames_, collider_frames_;
  View<Vec3*> targets_, targets_before_;  // targets at the end and at the start of the substep
  View<int*> kin_point_, kin_target_;
  View<int*> still_point_;  // points that never move (stopped, or no mass), for the pin lag
  View<Vec3*> still_at_;    // where they stand
  std::vector<int> collider_first_vertex_;  // each collider's first vertex in collider_x, then their count
  bool colliders_streamed_ = false;   // set_collider_frame was called: colliders follow the streamed frames
  View<Vec3*> collider_frame_start_, collider_frame_end_;  // streamed: the colliders at the frame's start and end
  View<Vec3*> row_delta_;
  View<Vec3*> cheb_xk_, cheb_xkm1_;  // Chebyshev: the iterates at the start of this and of the last iteration
  View<real*> cheb_lk_, cheb_lkm1_;  // and the rows' multipliers then
  View<Vec3*> cheb_xc_;  // with a collision stage: the points as the last sweep left them, before the contacts
  View<long*> point_slot_offset_, point_slot_;
  std::unique_ptr<CollisionStage<Exec>> collision_;
  ScheduleStats schedule_;  // the frame in progress
  bool fem_rows_ = false;   // the scene has FEM membrane rows
  std::optional<compat::Graph<Exec>> sweep_;  // gauss_seidel_sweep's kernels, for step h sweep_h_
  real sweep_h_ = 0;
  std::optional<compat::Graph<Exec>> smooth_;  // jacobi_sweep's kernels on the device, for step smooth_h_
  real smooth_h_ = 0;
  // Coarse levels: their rows (by level, then colour) and multipliers; per level its colours' row ranges and
  // its followers' range; the followers' parents and weights; the points where the cycle began.
  View<PackedRow<kRowDistance>*> coarse_rows_;
  View<real*> coarse_lambda_;
  std::vector<std::vector<std::pair<long, long>>> coarse_colours_;
  std::vector<std::pair<long, long>> coarse_followers_;
  View<int*> coarse_follower_, coarse_parent_;
  View<long*> coarse_offset_;
  View<real*> coarse_weight_;
  View<Vec3*> coarse_xs_;
  std::optional<compat::Graph<Exec>> coarse_;  // coarse_cycle's kernels, for step coarse_h_
  real coarse_h_ = 0;
};

}  // namespace weft
