// The weft command line: global options, and subcommands that register themselves (apps/cmd_*.cpp).
#pragma once
#include "backends/backend.hpp"
#include "scene/scene.hpp"

#include <CLI/CLI.hpp>
#include <array>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace weft::cli {

struct GlobalOptions {
  std::string backend;  // empty: default_backend()
  int threads = 0;      // 0: Kokkos' default
};

// A user-facing error: printed as "weft: <message>", exit code `code`.
struct Error : std::runtime_error {
  int code;
  explicit Error(const std::string& m, int c = 1) : std::runtime_error(m), code(c) {}
};

// Resolves --backend against this build; throws Error when it lacks the backend.
Backend resolve_backend(const GlobalOptions& g);

// --self-collision on|off (run, bench): overrides the scene's self_collision when `value` is not empty.
void add_self_collision_option(CLI::App* cmd, std::string& value);
void apply_self_collision(const std::string& value, bool& self_collision);
// --contact-model proximity|ccd (run, bench): overrides the scene's contact_model when not empty.
void add_contact_model_option(CLI::App* cmd, std::string& value);
void apply_contact_model(const std::string& value, ContactModel& model);
// --pair-refresh on|off (run, bench): overrides the scene's pair_refresh when not empty.
void add_pair_refresh_option(CLI::App* cmd, std::string& value);
void apply_pair_refresh(const std::string& value, bool& pair_refresh);
// --contact-solver gauss-seidel|jacobi (run, bench): overrides the scene's contact_solver when not empty.
void add_contact_solver_option(CLI::App* cmd, std::string& value);
void apply_contact_solver(const std::string& value, ContactSolver& solver);
// --ccd-span substep|pass (run, bench): overrides the scene's ccd_span when not empty.
void add_ccd_span_option(CLI::App* cmd, std::string& value);
void apply_ccd_span(const std::string& value, CcdSpan& span);
// --tethers STRETCH (run, bench): overrides the scene's tether_stretch when not empty (0 switches them off).
void add_tethers_option(CLI::App* cmd, std::string& value);
void apply_tethers(const std::string& value, real& tether_stretch);

// Prints `weft: warning: SCENE: ...` on stderr for each cloth piece too thick for its triangles
// (thickness_warnings, scene/scene.hpp); the run goes on.
void warn_about_thickness(const Scene& s);

// The cloth's triangle pairs (i < j, sorted) that intersect at its starting positions (apps/starting_state.cpp).
std::vector<std::array<int, 2>> starting_intersections(Backend b, const Scene& s);
// "triangles I (points a b c) and J (points d e f)", for messages.
std::string describe_triangle_pair(const Scene& s, const std::array<int, 2>& p);
// Prints `weft: warning: SCENE: the cloth starts with N intersecting triangle pairs ...` on stderr when the
// scene's cloth, with self collision on, starts crossed; the run goes on.
void warn_about_starting_state(Backend b, const Scene& s);

// The work a subcommand does once parsing is done; returns the exit code.
using Action = std::function<int()>;
// A subcommand adds itself to `app` and, from its parse callback, sets `run`.
using AddCommand = void (*)(CLI::App& app, const GlobalOptions& g, Action& run);

// In a cmd_*.cpp:  static const weft::cli::Register reg("name", add_name);
struct Register {
  Register(const char* name, AddCommand add);
};

}  // namespace weft::cli
