// The collision stage's settings (collision/collision_handler.hpp takes them whole), nested in the scene's
// as SolverSettings::collision. Named as the options are that set them: the JSON scene's and --set's
// names, the run options' (--contact-model, --contact-solver, --ccd-span, ...) and their values.
#pragma once
#include "core/real.hpp"

#include <optional>
#include <string>

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

// Self contact among all cloth pieces and layers, contact with colliders. How many collision passes a
// substep runs is the schedule's (SolverSettings::collision_passes).
struct CollisionSettings {
  bool self_collision = true;
  real static_friction = 0.5;            // Vellum "static threshold", times the points' friction scales
  real dynamic_friction = 0.5;           // Vellum "dynamic scale", times the points' dynamicfriction scales
  real layer_shock = 4;                  // a lower layer acts this much heavier than what it carries (contact.hpp)
  real parallel_edge_degrees = 10;       // self edge-edge pairs closer to parallel than this are dropped
  bool impact_zone_smoothing = true;     // paper 2.3: Laplacian smoothing of velocities in unresolved contacts
  real impact_zone_epsilon = 0.1;        // contacts with C < -epsilon * thickness are smoothed
  int impact_zone_sweeps = 4;
  ContactModel contact_model = ContactModel::Proximity;
  real early_pass_fraction = 0.01;       // proximity: a pass runs early when more of the moving points were cut back
  real still_tolerance = 0.1;            // proximity: a refresh keeps the last measured contacts while no point moved
                                         // more than this times the thinnest cloth thickness since (0: off)
  real early_pass_excess = 1;            // proximity: a point cut back counts towards that only where it wanted
                                         // more than (1 + this) times its bound
  int max_early_passes = 1;              // proximity: early passes per substep at most
  int max_collider_early_passes = 4;     // proximity: as many while points a collider pushes are cut back
  bool pair_refresh = true;              // proximity: a pass may keep the last full query's self pairs
  bool merge_contacts = false;           // Jacobi contacts on the same two or three points project as one row
  bool nearest_margins = false;          // proximity: query margins grow no further than the nearest features
  bool predicted_reference = false;      // proximity: bounds beside each point's own wanted move (docs/collisions.md)
  bool collision_failsafe = true;        // ccd model: move back points whose motion would cross cloth (collision/crossing_failsafe.hpp)
  ContactSolver contact_solver = ContactSolver::GaussSeidel;  // ccd model
  CcdSpan ccd_span = CcdSpan::Pass;                           // ccd model
};

}  // namespace weft
