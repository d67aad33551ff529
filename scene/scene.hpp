// The host-side description of a simulation: cloth points and triangles, constraints with Vellum
// semantics, animated targets and colliders, solver settings. Built by scene generators and readers,
// validated by validate_scene(), then uploaded once to the device by the solver.
#pragma once
#include "core/vec.hpp"
#include "scene/material.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace weft {

// How contacts are found and kept (docs/collisions.md): proximity queries with per-point displacement
// bounds (no crossing by construction), or the paper's CCD every pass with the crossing fail-safe.
enum class ContactModel { Proximity = 0, Ccd = 1 };
inline const char* contact_model_name(ContactModel m) { return m == ContactModel::Ccd ? "ccd" : "proximity"; }
inline std::optional<ContactModel> parse_contact_model(const std::string& s) {
  if (s == "proximity") return ContactModel::Proximity;
  if (s == "ccd") return ContactModel::Ccd;
  return std::nullopt;
}

// How the ccd model projects contacts (--contact-solver): Gauss-Seidel by colours, or Jacobi-style (each point
// moves by the average of its contacts' corrections; the proximity model always averages).
enum class ContactSolver { GaussSeidel = 0, Jacobi = 1 };
inline const char* contact_solver_name(ContactSolver s) { return s == ContactSolver::Jacobi ? "jacobi" : "gauss-seidel"; }
inline std::optional<ContactSolver> parse_contact_solver(const std::string& s) {
  if (s == "gauss-seidel") return ContactSolver::GaussSeidel;
  if (s == "jacobi") return ContactSolver::Jacobi;
  return std::nullopt;
}

// The motion a collision pass of the ccd model tests (--ccd-span): the whole substep's, or, for a pass after
// the first of its substep, only the motion since the previous pass.
enum class CcdSpan { Substep = 0, Pass = 1 };
inline const char* ccd_span_name(CcdSpan s) { return s == CcdSpan::Pass ? "pass" : "substep"; }
inline std::optional<CcdSpan> parse_ccd_span(const std::string& s) {
  if (s == "substep") return CcdSpan::Substep;
  if (s == "pass") return CcdSpan::Pass;
  return std::nullopt;
}

struct SolverSettings {
  real fps = 24;
  int frame_start = 1, frame_end = 48;  // inclusive; positions at frame_start are the scene's initial state
  int substeps = 10;                     // per frame
  int iterations = 20;                   // Gauss-Seidel constraint iterations per substep
  int collision_passes = 2;              // per substep, spread evenly over the iterations
  int smoothing_iterations = 0;          // Jacobi passes after Gauss-Seidel (Vellum "smoothing iterations")
  real tether_stretch = 0;               // 0: no tethers; else a point stays within this times its path length
                                         // at rest from the nearest hard-pinned point (constraints/tether.hpp)
  Vec3 gravity{0, -9.81, 0};             // m/s^2
  Vec3 wind{0, 0, 0};                    // constant acceleration, m/s^2
  real velocity_damping = 0;             // 1/s: v <- max(0, 1 - damping h) v + h a each substep
  // Collisions (collision/): self contact among all cloth pieces and layers, contact with colliders.
  bool self_collision = true;
  real static_friction = 0.5;            // Vellum "static threshold", times the points' friction scales
  real dynamic_friction = 0.5;           // Vellum "dynamic scale", times the points' dynamicfriction scales
  real layer_shock = 4;                  // lower layers act this much heavier in contacts with higher ones
  real parallel_edge_degrees = 10;       // self edge-edge pairs closer to parallel than this are dropped
  bool impact_zone_smoothing = true;     // paper 2.3: Laplacian smoothing of velocities in unresolved contacts
  real impact_zone_epsilon = 0.1;        // contacts with C < -epsilon * thickness are smoothed
  int impact_zone_sweeps = 4;
  ContactModel contact_model = ContactModel::Proximity;
  real early_pass_fraction = 0.01;       // proximity: a pass runs early when more of the moving points were cut back
  int max_early_passes = 4;              // proximity: early passes per substep at most
  bool pair_refresh = true;              // proximity: a pass may keep the last full query's self pairs
  bool collision_failsafe = true;        // ccd model: move back points whose motion would cross cloth (collision/crossing_failsafe.hpp)
  ContactSolver contact_solver = ContactSolver::GaussSeidel;  // ccd model
  CcdSpan ccd_span = CcdSpan::Pass;                           // ccd model
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
