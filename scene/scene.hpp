// The host-side description of a simulation: cloth points and triangles, constraints with Vellum
// semantics, animated targets and colliders, solver settings. Built by scene generators and readers,
// validated by validate_scene(), then uploaded once to the device by the solver.
#pragma once
#include "core/vec.hpp"
#include "scene/collision_settings.hpp"
#include "scene/material.hpp"

#include <array>
#include <string>
#include <vector>

namespace weft {

struct SolverSettings {
  real fps = 24;
  int frame_start = 1, frame_end = 48;  // inclusive; positions at frame_start are the scene's initial state
  int substeps = 10;                     // per frame
  int iterations = 20;                   // Gauss-Seidel constraint iterations per substep
  int collision_passes = 2;              // per substep, spread evenly over the iterations
  int smoothing_iterations = 0;          // Jacobi passes after Gauss-Seidel (Vellum "smoothing iterations")
  real chebyshev_rho = 0.95;             // Chebyshev acceleration of a substep's iterations with this estimate of
                                         // their convergence rate (Wang 2015; docs/solver.md); 0: off
  int chebyshev_delay = 4;               // iterations of a substep before the acceleration starts (>= 1)
  int stretch_limits = 0;                // levels of long-range stretch limits, 4, 16, 64 hops (0: none;
                                         // constraints/build_stretch_limits.hpp)
  int coarse_levels = 0;                 // coarse levels of the stretch rows solved before each substep's
                                         // iterations (0: none; constraints/build_coarse_levels.hpp)
  int coarse_iterations = 4;             // Gauss-Seidel sweeps of each coarse level per substep
  real tether_stretch = 0;               // 0: no tethers; else a point stays within this times its path length
                                         // at rest from the nearest hard-pinned point (constraints/tether.hpp)
  Vec3 gravity{0, -9.81, 0};             // m/s^2
  Vec3 wind{0, 0, 0};                    // constant acceleration, m/s^2
  real velocity_damping = 0;             // 1/s: v <- max(0, 1 - damping h) v + h a each substep
  CollisionSettings collision;           // the collision stage's (collision/collision_handler.hpp)
  bool profile = false;                  // time each stage (fences between stages)
};

// Per-point data of all cloth pieces, welded into one point set.
struct ClothPoints {
  std::vector<Vec3> position, velocity;
  std::vector<real> mass;       // kg; 0 = infinite (a permanent pin)
  std::vector<real> thickness;  // m, collision radius (Vellum pscale)
  std::vector<real> friction, dynamic_friction;
  std::vector<int> layer;       // garment layer, higher is outer
  std::vector<int> stopped;     // bit 0: the point does not move
  std::vector<int> piece;       // which cloth piece
  size_t size() const { return position.size(); }
  // Whether point i is held where it stands (no mass, or stopped); kinematic points are pinned too.
  bool still(size_t i) const { return !(mass[i] > 0) || (stopped[i] & 1); }
};

// An animated position source: `frames[f][k]` is target k at frame frame_start + f; positions between
// frames are interpolated linearly, and the last frame is held.
struct Animation {
  std::vector<std::vector<Vec3>> frames;
  bool empty() const { return frames.empty(); }
};

struct Collider {
  std::string name;
  std::vector<std::array<int, 3>> triangles;
  Animation motion;  // vertex positions per frame (one frame = static)
  real thickness = 0.0;
  real friction = 0.5;
};

// Constraints, one table per kind, with Vellum's rest data.
struct DistanceConstraint { int a, b; real rest; XpbdMaterial m; };
struct BendConstraint { int o0, o1, e0, e1; real rest_rad; XpbdMaterial m; };
struct TriarapConstraint { int p0, p1, p2; real dm_inv[4]; real area; bool normalized; XpbdMaterial m; };
// Pin p to a goal: a fixed point, or target `target` of Scene::pin_targets when >= 0.
struct PinConstraint { int p; Vec3 goal; int target; real rest; XpbdMaterial m; };
// Attach p to collider triangle `tri` at barycentric (u, v): goal = (1-u-v) t0 + u t1 + v t2.
struct AttachConstraint { int p, collider, tri; real u, v, rest; XpbdMaterial m; };
// Point-to-primitive stitch: |sum w_i t_i - p| - rest over nt = 2..4 target points.
struct PtPrimConstraint { int p; int t[4]; real w[4]; int nt; real rest; XpbdMaterial m; };
// FEM membrane from Young's modulus, Poisson's ratio and fabric thickness (compliances per triangle).
struct FemConstraint { int p0, p1, p2; real dm_inv[4]; real area; real dev_compliance, hyd_compliance, gamma;
                       real damping_ratio; };

struct Constraints {
  std::vector<DistanceConstraint> distance;  // distance along edges, and point-to-point stitches
  std::vector<BendConstraint> bend;
  std::vector<TriarapConstraint> triarap;
  std::vector<PinConstraint> pin;
  std::vector<AttachConstraint> attach;
  std::vector<PtPrimConstraint> ptprim;
  std::vector<FemConstraint> fem;
  size_t size() const {
    return distance.size() + bend.size() + triarap.size() + pin.size() + attach.size() + ptprim.size() + fem.size();
  }
};

struct Scene {
  std::string name;                               // for messages: file name or builtin:NAME
  ClothPoints points;
  std::vector<std::array<int, 3>> triangles;      // cloth triangles (all pieces)
  Constraints constraints;
  Animation pin_targets;                          // goals of animated pins
  std::vector<int> kinematic_point, kinematic_target;  // hard pins that follow pin_targets each substep
  std::vector<Collider> colliders;
  SolverSettings settings;
  bool needs_collisions = false;                  // the scene makes no sense without collision handling
};

// Throws InputError naming the scene and the element: out-of-range indices, NaN/Inf, zero-area triangles,
// negative mass or thickness, inconsistent animation frames, bad settings.
void validate_scene(const Scene& s);

// Self contacts reach 2.5 x a point's thickness (1.25 x the two sides'); past 0.4 of a triangle's smallest
// height they reach the point's own neighbouring faces and lock the cloth. One warning per cloth piece with
// such triangles (none with self collision off): what to change, and where.
constexpr real kMaxThicknessPerHeight = 0.4;
std::vector<std::string> thickness_warnings(const Scene& s);

}  // namespace weft
