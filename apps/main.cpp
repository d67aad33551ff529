#include "apps/cli.hpp"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>

namespace weft::cli {

static std::map<std::string, AddCommand>& registry() {
  static std::map<std::string, AddCommand> r;  // sorted by name, so --help lists them in order
  return r;
}

Register::Register(const char* name, AddCommand add) { registry()[name] = add; }

Backend resolve_backend(const GlobalOptions& g) {
  if (g.backend.empty()) return default_backend();
  const auto b = parse_backend(g.backend);
  if (!b) throw Error("unknown backend '" + g.backend + "' (serial, openmp or cuda)", 2);
  if (!backend_compiled(*b)) {
    std::string have;
    for (Backend c : compiled_backends()) have += std::string(have.empty() ? "" : ", ") + backend_name(c);
    throw Error(std::string("this build of weft has no ") + backend_name(*b) + " backend (it has: " + have + ")", 2);
  }
  return *b;
}

void add_self_collision_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--self-collision", value, "on | off: cloth against itself (default: the scene's)")
      ->check(CLI::IsMember({"on", "off"}));
}

void apply_self_collision(const std::string& value, bool& self_collision) {
  if (!value.empty()) self_collision = value == "on";
}

void add_contact_model_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--contact-model", value,
                  "proximity (contacts and per-point displacement bounds: nothing crosses, nothing is moved back) | "
                  "ccd (the paper's: CCD every pass, crossing fail-safe, impact zones) (default: the scene's)")
      ->check(CLI::IsMember({"proximity", "ccd"}));
}

void apply_contact_model(const std::string& value, ContactModel& model) {
  if (!value.empty()) model = *parse_contact_model(value);
}

void add_pair_refresh_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--pair-refresh", value,
                  "on | off: proximity passes keep the last full query's self pairs while the points have moved "
                  "little, measuring them again without a tree traversal (default: the scene's)")
      ->check(CLI::IsMember({"on", "off"}));
}

void apply_pair_refresh(const std::string& value, bool& pair_refresh) {
  if (!value.empty()) pair_refresh = value == "on";
}

void add_contact_solver_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--contact-solver", value,
                  "gauss-seidel (by colours) | jacobi (averaged, two launches an iteration): how the ccd model "
                  "projects contacts (the proximity model always averages) (default: the scene's)")
      ->check(CLI::IsMember({"gauss-seidel", "jacobi"}));
}

void apply_contact_solver(const std::string& value, ContactSolver& solver) {
  if (!value.empty()) solver = *parse_contact_solver(value);
}

void add_ccd_span_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--ccd-span", value,
                  "substep (every collision pass tests the motion since the substep's start) | pass (a later "
                  "pass only the motion since the previous pass) (default: the scene's)")
      ->check(CLI::IsMember({"substep", "pass"}));
}

void apply_ccd_span(const std::string& value, CcdSpan& span) {
  if (!value.empty()) span = *parse_ccd_span(value);
}

void add_tethers_option(CLI::App* cmd, std::string& value) {
  cmd->add_option("--tethers", value,
                  "STRETCH: hold every point within STRETCH (>= 1) times its path along the cloth from the nearest "
                  "hard-pinned point; 0 = no tethers (default: the scene's; docs/solver.md)")
      ->check([](const std::string& v) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != 0 || !(x == 0 || (x >= 1 && x < 1e6)))
          return "wants 0 (off) or a stretch of at least 1, got '" + v + "'";
        return "";
      });
}

void apply_tethers(const std::string& value, real& tether_stretch) {
  if (!value.empty()) tether_stretch = std::strtod(value.c_str(), nullptr);
}

void warn_about_thickness(const Scene& s) {
  for (const std::string& w : thickness_warnings(s)) std::fprintf(stderr, "weft: warning: %s: %s\n", s.name.c_str(), w.c_str());
}

}  // namespace weft::cli

int main(int argc, char** argv) {
  using namespace weft::cli;
  CLI::App app{"weft: a GPU cloth solver for character effects (XPBD, Vellum-compatible)"};
  app.require_subcommand(1);
  // Subcommands inherit this: a global option is taken after the subcommand too (`weft run X --backend cuda`).
  app.fallthrough();
  GlobalOptions g;
  app.add_option("--backend", g.backend, "serial | openmp | cuda (default: the fastest compiled)");
  app.add_option("--threads", g.threads, "host threads for the openmp backend")->check(CLI::NonNegativeNumber);
  Action run;
  for (auto& [name, add] : registry()) add(app, g, run);
  try {
    app.parse(argc, argv);
    return run ? run() : 0;
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const Error& e) {
    std::cerr << "weft: " << e.what() << "\n";
    return e.code;
  } catch (const std::exception& e) {
    std::cerr << "weft: " << e.what() << "\n";
    return 1;
  }
}
