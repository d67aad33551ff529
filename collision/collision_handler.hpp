// The collision stage of the frame loop, in one of two contact models (docs/collisions.md):
// - proximity (the default): each pass queries the pairs near the cloth where it stands (X0), makes contacts
//   of those within reach and gives every point a displacement bound (collision/displacement_bounds.hpp);
//   contacts are projected Jacobi-style in fixed point and every update is cut back to the bounds, so no
//   pair can cross and nothing is moved back;
// - ccd (paper sec. 2-3): LBVH broad phase over swept, thickness-inflated triangle boxes, narrow phase on
//   representative features with CCD and proximity, contacts coloured and projected in the same
//   Gauss-Seidel iterations as the cloth, and the crossing fail-safe.
// Both: friction, and impact-zone smoothing of velocities at the end of the substep.
#pragma once
#include "collision/aabb.hpp"
#include "collision/collision_stage.hpp"
#include "collision/contact_colouring.hpp"
#include "collision/contact_jacobi.hpp"
#include "collision/crossing_failsafe.hpp"
#include "collision/displacement_bounds.hpp"
#include "collision/impact_zone.hpp"
#include "collision/lbvh.hpp"
#include "collision/narrow_pipeline.hpp"
#include "collision/pin_groups.hpp"
#include "collision/representative.hpp"
#include "core/device_copy.hpp"
#include "core/stage_timer.hpp"
#include "core/topology.hpp"
#include "scene/collider_set.hpp"
#include "scene/scene.hpp"

#include <optional>

namespace weft {

// The handler's kernels, as named functors (docs/solver.md, "Kernels are functors").
template <class Mem>
struct ProjectContacts {
  Kokkos::View<Contact*, Mem> c;
  Kokkos::View<Vec3*, Mem> x, xs;
  Kokkos::View<real*, Mem> w;
  Kokkos::View<Vec3*, Mem> cx, cxs;
  KOKKOS_INLINE_FUNCTION void operator()(long i) const { project_contact(c(i), x, xs, w, cx, cxs); }
};

template <class Exec>
class CollisionHandler final : public CollisionStage<Exec> {
 public:
  using Mem = typename Exec::memory_space;
  template <class T>
  using View = Kokkos::View<T, Mem>;

  explicit CollisionHandler(const Scene& s)
      : settings_(s.settings.collision), cloth_bvh_(Exec()), collider_bvh_(Exec()),
        jacobi_run_(s.settings.collision.merge_contacts) {
    ns_.static_friction = settings_.static_friction;
    ns_.dynamic_friction = settings_.dynamic_friction;
    ns_.layer_shock = settings_.layer_shock;
    const real rad = settings_.parallel_edge_degrees * pi / 180;
    ns_.min_sin_angle = sin_small(rad);
    jacobi_ = settings_.contact_solver == ContactSolver::Jacobi;
    per_pass_ = settings_.ccd_span == CcdSpan::Pass && s.settings.collision_passes > 1;
    passes_ = s.settings.collision_passes;
    profile_ = s.settings.profile;
    proximity_ = settings_.contact_model == ContactModel::Proximity;
    // Cloth side.
    cloth_tris_ = upload_table<Mem>(s.triangles, "weft::cloth_tris");
    cloth_rmask_ = upload<Mem>(representative_features(s.triangles, int(s.points.size())), "weft::cloth_rmask");
    cloth_th_ = upload<Mem>(s.points.thickness, "weft::thickness");
    cloth_fr_ = upload<Mem>(s.points.friction, "weft::friction");
    cloth_dfr_ = upload<Mem>(s.points.dynamic_friction, "weft::dfriction");
    cloth_layer_ = upload<Mem>(s.points.layer, "weft::layer");
    std::vector<real> margin(s.triangles.size()), failsafe_margin(s.triangles.size());
    for (size_t t = 0; t < s.triangles.size(); ++t) {
      real m = 0;
      for (int k = 0; k < 3; ++k) m = std::max(m, s.points.thickness[s.triangles[t][k]]);
      margin[t] = ns_.detect_scale * m;
      failsafe_margin[t] = failsafe_box_margin(m);
    }
    cloth_margin_ = upload<Mem>(margin, "weft::cloth_margin");
    cloth_failsafe_margin_ = upload<Mem>(failsafe_margin, "weft::cloth_failsafe_margin");
    if (proximity_) {
      bound_settings_.nearest_margins = settings_.nearest_margins;
      bound_settings_.predicted_reference = settings_.predicted_reference;
      bound_settings_.early_excess = settings_.early_pass_excess;
      real thinnest = 0;
      for (real th : s.points.thickness)
        if (th > 0 && (thinnest == 0 || th < thinnest)) thinnest = th;
      bound_settings_.still_distance = settings_.still_tolerance * thinnest;
      // Far below any contact's reach, far above the rounding of positions and of the fixed-point distances.
      bound_settings_.separation = 1e-4 * thinnest;
      // A triangle's smallest query margin: an unfound pair keeps more than (1 - gamma)(m_A + m_B), at
      // least the contact reach of its points.
      std::vector<real> floor(s.triangles.size()), ceiling(s.triangles.size());
      for (size_t t = 0; t < s.triangles.size(); ++t) {
        floor[t] = margin[t] / (1 - bound_settings_.gamma);
        real edge = 0;
        for (int k = 0; k < 3; ++k)
          edge = std::max(edge, norm(s.points.position[s.triangles[t][(k + 1) % 3]] - s.points.position[s.triangles[t][k]]));
        ceiling[t] = std::max(floor[t], std::min(edge, 2 * floor[t]));
      }
      bounds_.emplace(long(s.points.size()), upload<Mem>(floor, "weft::bounds_floor"), upload<Mem>(ceiling, "weft::bounds_ceiling"),
                      bound_settings_);
      // Pins that follow an animation hold back in groups. Still pins need none: the common translation
      // is theirs, 0 (DisplacementBounds::prepare). But cloth on still pins in a scene whose colliders move
      // moves with its free points' mean (free_frame_): a sheet held in its pins' frame cannot keep ahead
      // of a collider pushing it (the 10 m/s box ran through the fast-collider sheet), so there the pins
      // are dragged along where the cloth's free points move faster than their bounds allow.
      const bool animated_pins = !s.kinematic_point.empty() && s.pin_targets.frames.size() > 1;
      bool any_pinned = !s.kinematic_point.empty();
      for (size_t i = 0; i < s.points.size(); ++i) any_pinned = any_pinned || s.points.still(i);
      still_pins_ = any_pinned && !animated_pins;
      bool colliders_move = false;
      for (const Collider& c : s.colliders)
        for (const std::vector<Vec3>& f : c.motion.frames) colliders_move = colliders_move || f != c.motion.frames[0];
      free_frame_ = still_pins_ && colliders_move;
      if (animated_pins && bound_settings_.bound_pins) {
        std::vector<char> pinned(s.points.size(), 0);
        for (int k : s.kinematic_point) pinned[size_t(k)] = 1;
        const PinGroups groups = pin_groups(s.triangles, pinned);
        if (groups.count > 0) bounds_->set_pin_groups(upload<Mem>(groups.group, "weft::pin_group"), groups.count);
      }
    }
    cloth_boxes_ = View<Aabb*>("weft::cloth_boxes", s.triangles.size());
    // Collider side: the collider set, each vertex with its collider's thickness and friction; a collider
    // triangle's boxes grow by its contact reach.
    const ColliderSet cs = make_collider_set(s.colliders);
    std::vector<real> tmargin;
    for (int c : cs.triangle_collider) tmargin.push_back(ns_.detect_scale * s.colliders[size_t(c)].thickness);
    collider_th_ = upload<Mem>(cs.vertex_thickness, "weft::collider_thickness");
    collider_fr_ = upload<Mem>(cs.vertex_friction, "weft::collider_friction");
    collider_margin_ = upload<Mem>(tmargin, "weft::collider_margin");
    collider_tris_ = upload_table<Mem>(cs.triangles, "weft::collider_tris");
    collider_rmask_ = upload<Mem>(representative_features(cs.triangles, cs.vertices()), "weft::collider_rmask");
    collider_nb_ = upload_table<Mem>(triangle_neighbours(cs.triangles), "weft::collider_neighbours");
    collider_boxes_ = View<Aabb*>("weft::collider_boxes", cs.triangles.size());
  }

  // The sums start anew; the last pass's contacts and the last substep's impact zones carry over until
  // replaced.
  void begin_frame() override {
    CollisionStats next;
    next.contacts = stats_.contacts;
    next.impact_zone_points = stats_.impact_zone_points;
    stats_ = next;
  }
  void end_frame(const SolverState<Exec>& s) override {
    if (proximity_) stats_.points_cut_back = bounds_->take_cut_tally(s.exec);
  }
  CollisionStats frame_stats() const override { return stats_; }
  void colliders_streamed() override { free_frame_ = still_pins_; }

  // The trees are built once per frame; every pass refits them first.
  void begin_substep(const SolverState<Exec>& s, real, int substep) override {
    pass_in_substep_ = 0;
    early_in_substep_ = 0;
    if (substep != 0) return;
    if (proximity_) {  // the first query builds the trees from its own boxes
      build_ = true;
      if (bounds_) bounds_->retry_references();
      return;
    }
    timed("weft::lbvh_build", stats_.seconds_lbvh_build, [&] {
      update_boxes(s.exec, cloth_side(s), collider_side(s), cloth_margin_);
      cloth_bvh_.build(cloth_boxes_);
      if (collider_boxes_.extent(0) > 0) collider_bvh_.build(collider_boxes_);
    });
  }

  // With CcdSpan::Pass, a pass after the first of its substep tests the motion since the previous pass
  // (x_pass_ to x; colliders do not move within a substep): a later pass then sweeps its boxes and runs its
  // CCD over the constraint iterations' corrections only, not over the whole substep again. Contacts keep
  // the side their points had at the start of the substep (SideMesh::xo).
  void pass(const SolverState<Exec>& s, real) override {
    if (proximity_) return proximity_pass(s);
    SideMesh<Mem> cloth = cloth_side(s), collider = collider_side(s);
    if (per_pass_ && pass_in_substep_ > 0) {
      cloth.xs = x_pass_;
      collider.xs = collider.x;
    }
    timed("weft::broad_phase", stats_.seconds_broad_phase, [&] {
      update_boxes(s.exec, cloth, collider, cloth_margin_);
      cloth_bvh_.refit(cloth_boxes_);
      if (collider_boxes_.extent(0) > 0) collider_bvh_.refit(collider_boxes_);
    });
    long n = 0;
    if (settings_.self_collision) n += narrow(cloth, cloth, /*self*/ true, n);
    if (collider_boxes_.extent(0) > 0) n += narrow(cloth, collider, false, n);
    ncontacts_ = n;
    jacobi_run_.contacts_changed();
    if (per_pass_ && ++pass_in_substep_ < passes_) {
      if (x_pass_.extent(0) != s.x.extent(0))
        x_pass_ = View<Vec3*>(Kokkos::view_alloc(Kokkos::WithoutInitializing, "weft::x_pass"), s.x.extent(0));
      Kokkos::deep_copy(s.exec, x_pass_, s.x);
    }
    if (jacobi_) offsets_ = {0};  // Jacobi needs no colours
    else timed("weft::contact_colouring", stats_.seconds_contact_colouring, [&] { offsets_ = colouring_.colour(s.exec, contacts_, n, s.w); });
    stats_.contacts = n;
  }

  void project(const SolverState<Exec>& s, real) override {
    auto c = contacts_;
    auto x = s.x, xs = s.x_start;
    auto w = s.w;
    auto cx = s.collider_x, cxs = s.collider_x_start;
    if (proximity_) return jacobi_run_.project(s.exec, c, ncontacts_, x, xs, w, cx, cxs, bounds_->truncate_step(x, w));
    if (jacobi_) return jacobi_run_.project(s.exec, c, ncontacts_, x, xs, w, cx, cxs);
    for (size_t k = 0; k + 1 < offsets_.size(); ++k)
      Kokkos::parallel_for("weft::project_contacts", Kokkos::RangePolicy<Exec>(s.exec, offsets_[k], offsets_[k + 1]),
                           ProjectContacts<Mem>{c, x, xs, w, cx, cxs});
  }

  // The crossing fail-safe over fresh candidate pairs (boxes from x_start to the final x).
  void finish_positions(const SolverState<Exec>& s, real) override {
    if (proximity_) return bounds_->truncate(s.exec, s.x, s.w);  // after the smoothing sweeps
    if (!settings_.collision_failsafe) return;
    update_boxes(s.exec, cloth_side(s), collider_side(s), cloth_failsafe_margin_);
    cloth_bvh_.refit(cloth_boxes_);
    long nself = 0, ncollider = 0;
    if (settings_.self_collision) nself = cloth_bvh_.query_self(KeepAllPairs{}, pairs_);
    if (collider_boxes_.extent(0) > 0) {
      collider_bvh_.refit(collider_boxes_);
      ncollider = collider_bvh_.query(View<const Aabb*>(cloth_boxes_), KeepAllPairs{}, collider_pairs_);
    }
    if (nself + ncollider == 0) return;
    const FailsafeStats fs = failsafe_run_.run(s.exec, cloth_side(s), collider_side(s), pairs_, nself, collider_pairs_,
                                               ncollider, s.x, s.x_start, s.w,
                                               narrow_.pair_cull());
    stats_.failsafe_points += fs.points;
    stats_.failsafe_rounds += fs.rounds;
    stats_.failsafe_pinned += fs.pinned;
  }

  // Proximity: a query again before the next sweep when more than early_pass_fraction of the points that
  // move were cut back by the last truncation (reads one sum back), at most max_early_passes a substep; or
  // while that many of them have a collider within their contact reach that moves farther than that reach
  // over the substep (pushing them), up to max_collider_early_passes.
  // A query lets a pair that cannot part close by another 2 gamma of its distance: where cloth jams, more
  // queries hold it tighter, where a point pushed by a fast collider needs them to keep ahead of it.
  // Where no early pass can follow (the substep's budget spent, and no collider pair at the last query to
  // push a point), nothing is read back: the same decisions with the device left to run ahead.
  bool wants_pass(const SolverState<Exec>& s) override {
    if (!proximity_) return false;
    const bool cut_open = early_in_substep_ < settings_.max_early_passes;
    const bool push_open = this->push_open();
    if (!cut_open && !push_open) {
      held_ = {0, 0};
      return false;
    }
    const auto counts = bounds_->cut_counts(s.exec);
    const real many = settings_.early_pass_fraction * real(bounds_->movable());
    const bool cut = cut_open && real(counts.all + held_.all) > many;
    const bool pushed = push_open && real(counts.pushed + held_.pushed) > many;
    held_ = {0, 0};
    if (!cut && !pushed) return false;
    ++early_in_substep_;
    ++stats_.early_passes;
    early_next_ = true;
    return true;
  }

  void end_substep(const SolverState<Exec>& s, real) override {
    if (!settings_.impact_zone_smoothing) return;
    stats_.impact_zone_points = zones_.smooth(s.exec, contacts_, ncontacts_, s.x, s.collider_x, s.v,
                                              settings_.impact_zone_epsilon, settings_.impact_zone_sweeps).points;
  }

  // A proximity query (collision/displacement_bounds.hpp): X0 is where the substep started (its first
  // query: the prediction is then cut back) or where the cloth stands. Self pairs are met in the frame that
  // translates with the cloth's common move t: boxes at X0 (pinned points swept to their targets less t),
  // contacts at X0. Collider pairs are met where the cloth goes (X0 + t): boxes swept from X0, and the
  // colliders' swept over the whole substep in every query, whose narrow phase then also catches, by CCD,
  // a collider face that has swept over a point this substep, or a point carried through a face: such a
  // contact is found again at each query until the point is out. Bounds from every candidate pair.
  //
  // With pair_refresh, a scheduled pass after the frame's first keeps the self pairs of the last full query
  // while few points have spent half of what that query allows them (DisplacementBounds::spent): it measures
  // their distances and contacts again at X0, with no tree refit or traversal, and the bounds spend what
  // the points moved since. Collider pairs are queried at every pass (the colliders move within it).
  void proximity_pass(const SolverState<Exec>& s) {
    const bool first = pass_in_substep_++ == 0;
    DisplacementBounds<Exec>& b = *bounds_;
    SideMesh<Mem> cloth = cloth_side(s), collider = collider_side(s);
    const bool colliders = collider_boxes_.extent(0) > 0;
    collider_near_ = false;
    const View<Vec3*> from = first ? s.x_start : s.x;
    bool refresh = false;
    timed("weft::broad_phase", stats_.seconds_broad_phase, [&] {
      // An early pass runs because points were cut back: it queries afresh, which resets what they spent
      // and widens the margins where they want to move. Letting it keep the pairs, as a scheduled pass
      // may, saved nothing on the skirt: by then most points had spent half of what the pairs allow.
      // A substep's first query with reference moves sweeps the boxes for the prediction: it never keeps pairs.
      refresh = settings_.pair_refresh && settings_.self_collision && !build_ && !early_next_ &&
                !(b.references() && first) &&
                !(real(b.spent(s.exec, from, s.w)) > settings_.early_pass_fraction * real(b.movable()));
      early_next_ = false;
      b.prepare(s.exec, from, s.x, s.w, cloth_tris_, first, refresh, free_frame_);
      cloth.x = cloth.xs = cloth.xo = b.x0();
      const View<const real*> margins = b.margins();
      if (!refresh)
        swept_triangle_boxes(s.exec, View<const Vec3*>(b.x0()), View<const Vec3*>(b.relative_end()),
                             View<const int* [3]>(cloth_tris_), margins, cloth_boxes_);
      if (colliders)
        swept_triangle_boxes(s.exec, collider.xs, collider.x, View<const int* [3]>(collider_tris_),
                             View<const real*>(collider_margin_), collider_boxes_);
      if (build_) {
        cloth_bvh_.build(cloth_boxes_);
        if (colliders) collider_bvh_.build(collider_boxes_);
        build_ = false;
      } else {
        if (!refresh) cloth_bvh_.refit(cloth_boxes_);
        if (colliders) collider_bvh_.refit(collider_boxes_);
      }
    });
    long n = 0;
    if (settings_.self_collision) {
      NarrowSettings ns = ns_;
      ns.self = true;
      if (!refresh) timed("weft::broad_phase", stats_.seconds_broad_phase, [&] { nself_pairs_ = cloth_bvh_.query_self(KeepAllPairs{}, pairs_); });
      timed("weft::self_bounds_contacts", stats_.seconds_narrow_phase, [&] {
        if (b.still()) {
          // The last measured pass's self contacts stand (contacts_[0, n) is kept), their closest points and
          // normals measured again where the cloth stands: frozen ones left the resting layer-stack jittering
          // five times as fast (rms 2.1e-3 against 3.9e-4 m/s at --res 6).
          n += nself_contacts_;
          if (n > 0)
            Kokkos::parallel_for("weft::still_contacts", Kokkos::RangePolicy<Exec>(s.exec, 0, n),
                                 RemeasureSelfContacts<Mem>{contacts_, cloth, ns});
          ++stats_.still_passes;
          return;
        }
        // The cloth stands still at X0: the bounds' distances decide its contacts too.
        const long np = nself_pairs_;
        lbvh_detail::reserve(self_hits_, np, "weft::self_hits");
        View<const IndexPair*> measured = pairs_;
        long nm = np;
        if (b.sweeps()) b.add_self_pairs_with_references(s.exec, cloth, pairs_, np, s.w, self_hits_, ns, narrow_.pair_cull(), measured, nm);
        else b.add_self_pairs(s.exec, cloth, pairs_, np, b.relative_end(), s.w, self_hits_, ns, narrow_.pair_cull(), measured, nm);
        if (nm > 0) n += narrow_.fill(s.exec, cloth, cloth, ns, measured, nm, self_hits_, contacts_, n);
        nself_contacts_ = n;
        b.measured_self(s.exec);
      });
    }
    if (colliders) {
      NarrowSettings ns = ns_;
      ns.self = false;
      SideMesh<Mem> moving = cloth;  // from X0 to where the cloth goes
      moving.x = b.end();
      long npairs = 0;
      timed("weft::broad_phase", stats_.seconds_broad_phase, [&] {
        // Swept to where the cloth goes, which reference moves settle only with the self pairs.
        if (swept_boxes_.extent(0) != cloth_boxes_.extent(0))
          swept_boxes_ = View<Aabb*>("weft::cloth_swept_boxes", cloth_boxes_.extent(0));
        swept_triangle_boxes(s.exec, View<const Vec3*>(b.x0()), View<const Vec3*>(b.end()),
                             View<const int* [3]>(cloth_tris_), b.margins(), swept_boxes_);
        npairs = collider_bvh_.query(View<const Aabb*>(swept_boxes_), KeepAllPairs{}, collider_pairs_);
        collider_near_ = npairs > 0;
      });
      timed("weft::collider_narrow_phase", stats_.seconds_narrow_phase, [&] {
        SideMesh<Mem> there = cloth;
        there.x = there.xs = b.end();
        b.add_pairs(s.exec, there, collider, collider_pairs_, npairs, b.end(), s.w);
        if (npairs > 0) n += narrow_.run(Exec(), moving, collider, ns, collider_pairs_, npairs, contacts_, n);
      });
    }
    timed("weft::bounds_finish", stats_.seconds_narrow_phase, [&] {
      b.finish(s.exec, s.w);
      // The prediction (or what the last query left of it) cut back to the new bounds; the points still
      // held short ask for an early pass at the next check (their count read back only while one can run).
      b.truncate_prediction(s.exec, s.x, s.w);
      held_ = early_open() ? b.cut_counts(s.exec) : typename DisplacementBounds<Exec>::CutCounts{0, 0};
    });
    ncontacts_ = n;
    jacobi_run_.contacts_changed();
    offsets_ = {0};
    stats_.contacts = n;
    if (!refresh) ++stats_.queries;
  }

  // Narrow phase of the pairs between sides A and B, contacts appended at `first`; returns how many.
  long narrow(const SideMesh<Mem>& A, const SideMesh<Mem>& B, bool self, long first) {
    NarrowSettings ns = ns_;
    ns.self = self;
    long npairs = 0;
    timed("weft::broad_phase", stats_.seconds_broad_phase, [&] {
      if (self) npairs = cloth_bvh_.query_self(KeepAllPairs{}, pairs_);
      else npairs = collider_bvh_.query(View<const Aabb*>(cloth_boxes_), KeepAllPairs{}, pairs_);
    });
    if (npairs == 0) return 0;
    long total = 0;
    timed("weft::narrow_phase", stats_.seconds_narrow_phase, [&] { total = narrow_pairs(A, B, ns, npairs, first); });
    return total;
  }

  // The narrow phase proper (collision/narrow_pipeline.hpp), contacts written at `first` on.
  long narrow_pairs(const SideMesh<Mem>& A, const SideMesh<Mem>& B, const NarrowSettings& ns, long npairs, long first) {
    return narrow_.run(Exec(), A, B, ns, pairs_, npairs, contacts_, first);
  }

 private:
  // Whether an early pass can still run in this substep: for any cut-back points, or for points a collider
  // pushes (the last pass had collider pairs).
  bool push_open() const { return early_in_substep_ < settings_.max_collider_early_passes && collider_near_; }
  bool early_open() const { return early_in_substep_ < settings_.max_early_passes || push_open(); }

  template <class F>
  void timed(const char* region, double& acc, F&& stage) { timed_stage(region, profile_, acc, stage); }
  // sin(x) for the small angle of the parallel-edge rule, from its Taylor series (no library call).
  static real sin_small(real x) {
    real term = x, s = x;
    for (int k = 1; k < 12; ++k) { term = -term * x * x / real((2 * k) * (2 * k + 1)); s += term; }
    return s;
  }
  // The triangle across each edge (corner k to k+1) of a collider mesh, -1 on a boundary.

 public:
  // Swept boxes from each side's xs to x: cloth boxes inflated by `cloth_margin` (per triangle), collider
  // boxes by the contact margin.
  void update_boxes(const Exec& exec, const SideMesh<Mem>& cloth, const SideMesh<Mem>& collider, const View<real*>& cloth_margin) {
    swept_triangle_boxes(exec, cloth.xs, cloth.x, View<const int* [3]>(cloth_tris_), View<const real*>(cloth_margin),
                         cloth_boxes_);
    if (collider_boxes_.extent(0) > 0)
      swept_triangle_boxes(exec, collider.xs, collider.x, View<const int* [3]>(collider_tris_),
                           View<const real*>(collider_margin_), collider_boxes_);
  }
  SideMesh<Mem> cloth_side(const SolverState<Exec>& s) const {
    SideMesh<Mem> m;
    m.x = s.x; m.xs = s.x_start; m.xo = s.x_start; m.tris = cloth_tris_; m.rmask = cloth_rmask_; m.thickness = cloth_th_;
    m.friction = cloth_fr_; m.dfriction = cloth_dfr_; m.layer = cloth_layer_;
    return m;
  }
  SideMesh<Mem> collider_side(const SolverState<Exec>& s) const {
    SideMesh<Mem> m;
    m.x = s.collider_x; m.xs = s.collider_x_start; m.xo = s.collider_x_start; m.tris = collider_tris_; m.rmask = collider_rmask_;
    m.neighbour = collider_nb_; m.thickness = collider_th_; m.friction = collider_fr_; m.dfriction = collider_fr_;
    m.collider = true;
    return m;
  }

 private:
  const CollisionSettings settings_;
  NarrowSettings ns_;
  bool profile_ = false, jacobi_ = false, per_pass_ = false;
  bool proximity_ = false, build_ = true;
  int passes_ = 1, pass_in_substep_ = 0, early_in_substep_ = 0;
  // Points the last query's truncation held short of their prediction (and of them, pushed by a collider).
  typename DisplacementBounds<Exec>::CutCounts held_{0, 0};
  long nself_pairs_ = 0;  // proximity: self pairs of the last full query (in pairs_)
  long nself_contacts_ = 0;  // proximity: self contacts of the last pass that measured them (contacts_[0, n))
  bool early_next_ = false;  // proximity: wants_pass asked for the next pass
  bool collider_near_ = false;  // proximity: the last pass had collider pairs (a collider may push points)
  bool still_pins_ = false;     // proximity: the cloth has pins, none of them animated
  bool free_frame_ = false;     // proximity: queries in the free points' frame (still pins, moving colliders)
  BoundSettings bound_settings_;
  std::optional<DisplacementBounds<Exec>> bounds_;
  View<Vec3*> x_pass_;  // cloth positions at the previous pass of the substep (CcdSpan::Pass)
  long ncontacts_ = 0;
  View<int* [3]> cloth_tris_, collider_tris_, collider_nb_;
  View<uint8_t*> cloth_rmask_, collider_rmask_;
  View<real*> cloth_th_, cloth_fr_, cloth_dfr_, cloth_margin_, cloth_failsafe_margin_;
  View<int*> cloth_layer_;
  View<real*> collider_th_, collider_fr_, collider_margin_;  // per collider vertex, per collider triangle
  View<Aabb*> cloth_boxes_, collider_boxes_, swept_boxes_;  // swept_boxes_: proximity queries against colliders
  Lbvh<Exec> cloth_bvh_, collider_bvh_;
  View<IndexPair*> pairs_{"weft::pairs", 0}, collider_pairs_{"weft::collider_pairs", 0};
  View<uint32_t*> self_hits_;  // proximity: per self pair, its contact bits
  View<Contact*> contacts_{"weft::contacts", 0};
  std::vector<long> offsets_{0};
  NarrowPipeline<Exec> narrow_;
  ContactColouring<Exec> colouring_;
  JacobiContacts<Exec> jacobi_run_;
  ImpactZones<Exec> zones_;
  CrossingFailsafe<Exec> failsafe_run_;
  CollisionStats stats_;  // this frame's, since begin_frame()
};

}  // namespace weft
