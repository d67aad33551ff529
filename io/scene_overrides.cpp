#include "io/scene_overrides.hpp"

#include "core/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>

namespace weft::io {
namespace {

struct BadValue {
  std::string what;
};

enum class Range { Any, NonNegative, Positive };

real to_real(const std::string& v, Range r = Range::NonNegative) {
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || end == v.c_str() || *end != 0 || errno == ERANGE || !std::isfinite(x))
    throw BadValue{"expected a number, got '" + v + "'"};
  if (r == Range::NonNegative && x < 0) throw BadValue{"expected a number >= 0, got " + v};
  if (r == Range::Positive && !(x > 0)) throw BadValue{"expected a number > 0, got " + v};
  return x;
}

int to_int(const std::string& v, int lo) {
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || end == v.c_str() || *end != 0 || errno == ERANGE || x > (1L << 30))
    throw BadValue{"expected an integer, got '" + v + "'"};
  if (x < lo) throw BadValue{"expected an integer >= " + std::to_string(lo) + ", got " + v};
  return int(x);
}

bool to_bool(const std::string& v) {
  if (v == "true" || v == "on" || v == "1") return true;
  if (v == "false" || v == "off" || v == "0") return false;
  throw BadValue{"expected on or off (true or false), got '" + v + "'"};
}

Vec3 to_vec3(const std::string& v) {
  Vec3 r;
  size_t start = 0;
  for (int c = 0; c < 3; ++c) {
    const size_t comma = v.find(',', start);
    if ((c < 2) == (comma == std::string::npos)) throw BadValue{"expected x,y,z, got '" + v + "'"};
    r[c] = to_real(v.substr(start, comma == std::string::npos ? std::string::npos : comma - start), Range::Any);
    start = comma + 1;
  }
  return r;
}

std::string one_of(const std::string& v, std::initializer_list<const char*> allowed) {
  std::string list;
  for (const char* a : allowed) {
    if (v == a) return v;
    list += (list.empty() ? "" : ", ") + std::string(a);
  }
  throw BadValue{"expected one of " + list + ", got '" + v + "'"};
}

// Stiffness times s is compliance divided by s.
void scale_compliance(XpbdMaterial& m, real s) {
  m.compliance /= s;
  m.compress_compliance /= s;
}

struct Entry {
  const char* name;
  const char* help;
  std::function<void(Scene&, const std::string&)> apply;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = {
      {"fps", "number > 0: frames per second",
       [](Scene& s, const std::string& v) { s.settings.fps = to_real(v, Range::Positive); }},
      {"substeps", "integer >= 1: substeps per frame",
       [](Scene& s, const std::string& v) { s.settings.substeps = to_int(v, 1); }},
      {"iterations", "integer >= 0: constraint iterations per substep",
       [](Scene& s, const std::string& v) { s.settings.iterations = to_int(v, 0); }},
      {"collision_passes", "integer >= 0: collision passes per substep",
       [](Scene& s, const std::string& v) { s.settings.collision_passes = to_int(v, 0); }},
      {"smoothing", "integer >= 0: Jacobi smoothing iterations per substep",
       [](Scene& s, const std::string& v) { s.settings.smoothing_iterations = to_int(v, 0); }},
      {"chebyshev_rho", "number in [0, 1): Chebyshev acceleration of the iterations at this rate (0: off; 0.95 by default)",
       [](Scene& s, const std::string& v) { s.settings.chebyshev_rho = to_real(v); }},
      {"chebyshev_delay", "integer >= 1: iterations of a substep before Chebyshev acceleration starts",
       [](Scene& s, const std::string& v) { s.settings.chebyshev_delay = to_int(v, 1); }},
      {"damping", "number >= 0, 1/s: velocity damping",
       [](Scene& s, const std::string& v) { s.settings.velocity_damping = to_real(v); }},
      {"gravity", "x,y,z in m/s^2", [](Scene& s, const std::string& v) { s.settings.gravity = to_vec3(v); }},
      {"wind", "x,y,z in m/s^2: a constant acceleration",
       [](Scene& s, const std::string& v) { s.settings.wind = to_vec3(v); }},
      {"tethers", "0 (off) or a stretch >= 1: tethers to the hard-pinned points",
       [](Scene& s, const std::string& v) {
         const real x = to_real(v);
         if (x != 0 && x < 1) throw BadValue{"expected 0 (off) or a stretch of at least 1, got " + v};
         s.settings.tether_stretch = x;
       }},
      {"stretch_limits", "integer 0 to 3: levels of long-range stretch limits, 4, 16 and 64 hops long (0: none)",
       [](Scene& s, const std::string& v) { s.settings.stretch_limits = to_int(v, 0); }},
      {"coarse_levels", "integer 0 to 16: coarse levels of the stretch rows solved before each substep's iterations (0: none)",
       [](Scene& s, const std::string& v) { s.settings.coarse_levels = to_int(v, 0); }},
      {"coarse_iterations", "integer >= 1: sweeps of each coarse level per substep",
       [](Scene& s, const std::string& v) { s.settings.coarse_iterations = to_int(v, 1); }},
      {"self_collision", "on | off: cloth against itself",
       [](Scene& s, const std::string& v) { s.settings.collision.self_collision = to_bool(v); }},
      {"static_friction", "number >= 0: the solver's static threshold (times each point's friction)",
       [](Scene& s, const std::string& v) { s.settings.collision.static_friction = to_real(v); }},
      {"dynamic_friction", "number >= 0: the solver's dynamic scale (times each point's dynamic friction)",
       [](Scene& s, const std::string& v) { s.settings.collision.dynamic_friction = to_real(v); }},
      {"layer_shock", "number >= 1: in a contact between layers, the lower layer acts this many times heavier than what it carries (1: off)",
       [](Scene& s, const std::string& v) {
         const real k = to_real(v, Range::Positive);
         if (k < 1) throw BadValue{"expected a number >= 1 (1: off), got " + v};
         s.settings.collision.layer_shock = k;
       }},
      {"contact_model", "proximity | ccd",
       [](Scene& s, const std::string& v) { s.settings.collision.contact_model = *parse_contact_model(one_of(v, {"proximity", "ccd"})); }},
      {"pair_refresh", "on | off: proximity passes may keep the last full query's self pairs",
       [](Scene& s, const std::string& v) { s.settings.collision.pair_refresh = to_bool(v); }},
      {"merge_contacts", "on | off: Jacobi contacts on the same two or three points project as one row counted as many",
       [](Scene& s, const std::string& v) { s.settings.collision.merge_contacts = to_bool(v); }},
      {"nearest_margins", "on | off: proximity query margins grow no further than the nearest features at the last query",
       [](Scene& s, const std::string& v) { s.settings.collision.nearest_margins = to_bool(v); }},
      {"predicted_reference", "on | off: proximity bounds beside each point's own wanted move, not only the common translation",
       [](Scene& s, const std::string& v) { s.settings.collision.predicted_reference = to_bool(v); }},
      {"still_tolerance", "number >= 0: a proximity pass keeps the last measured contacts while no point moved more than this times the thinnest cloth thickness (0: off)",
       [](Scene& s, const std::string& v) { s.settings.collision.still_tolerance = to_real(v, Range::NonNegative); }},
      {"early_pass_excess", "number >= 0: a point cut back counts towards an early pass when it wanted more than (1 + this) times its bound",
       [](Scene& s, const std::string& v) { s.settings.collision.early_pass_excess = to_real(v, Range::NonNegative); }},
      {"early_pass_fraction", "number >= 0: share of moving points cut back that runs a pass early",
       [](Scene& s, const std::string& v) { s.settings.collision.early_pass_fraction = to_real(v); }},
      {"max_early_passes", "integer >= 0: early passes per substep at most",
       [](Scene& s, const std::string& v) { s.settings.collision.max_early_passes = to_int(v, 0); }},
      {"max_collider_early_passes", "integer >= 0: early passes per substep at most while points a collider pushes are cut back",
       [](Scene& s, const std::string& v) { s.settings.collision.max_collider_early_passes = to_int(v, 0); }},
      {"impact_zone_smoothing", "on | off: smoothing of velocities in unresolved contacts (both models)",
       [](Scene& s, const std::string& v) { s.settings.collision.impact_zone_smoothing = to_bool(v); }},
      {"collision_failsafe", "on | off (ccd model)",
       [](Scene& s, const std::string& v) { s.settings.collision.collision_failsafe = to_bool(v); }},
      {"contact_solver", "gauss-seidel | jacobi (ccd model)",
       [](Scene& s, const std::string& v) { s.settings.collision.contact_solver = *parse_contact_solver(one_of(v, {"gauss-seidel", "jacobi"})); }},
      {"ccd_span", "substep | pass (ccd model)",
       [](Scene& s, const std::string& v) { s.settings.collision.ccd_span = *parse_ccd_span(one_of(v, {"substep", "pass"})); }},
      {"thickness", "number >= 0, m: every cloth point's collision thickness",
       [](Scene& s, const std::string& v) {
         const real t = to_real(v);
         for (real& x : s.points.thickness) x = t;
       }},
      {"thickness_scale", "number > 0: every cloth point's collision thickness times this",
       [](Scene& s, const std::string& v) {
         const real k = to_real(v, Range::Positive);
         for (real& x : s.points.thickness) x *= k;
       }},
      {"stretch_stiffness_scale",
       "number > 0: the stiffness of every stretch row (distance and stitch, triangle stretch, FEM membrane) times this",
       [](Scene& s, const std::string& v) {
         const real k = to_real(v, Range::Positive);
         for (auto& c : s.constraints.distance) scale_compliance(c.m, k);
         for (auto& c : s.constraints.triarap) scale_compliance(c.m, k);
         for (auto& c : s.constraints.fem) {
           c.dev_compliance /= k;
           c.hyd_compliance /= k;
         }
       }},
      {"bend_stiffness_scale", "number > 0: the stiffness of every bend row times this",
       [](Scene& s, const std::string& v) {
         const real k = to_real(v, Range::Positive);
         for (auto& c : s.constraints.bend) scale_compliance(c.m, k);
       }},
  };
  return table;
}

const Entry& find(const std::string& name) {
  for (const Entry& e : entries())
    if (name == e.name) return e;
  std::string list;
  for (const Entry& e : entries()) list += (list.empty() ? "" : ", ") + std::string(e.name);
  throw InputError("unknown setting '" + name + "' (known: " + list + ")");
}

void apply_one(Scene& s, const SceneOverride& o) {
  const Entry& e = find(o.name);
  try {
    e.apply(s, o.value);
  } catch (const BadValue& b) {
    throw InputError(o.name + ": " + b.what);
  }
}

}  // namespace

SceneOverride parse_override(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError("a setting is given as name=value, got '" + text + "'");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void check_override(const SceneOverride& o) {
  Scene scratch;  // empty: only the value's kind and range are checked
  apply_one(scratch, o);
}

void apply_overrides(Scene& s, const std::vector<SceneOverride>& overrides) {
  for (const SceneOverride& o : overrides) apply_one(s, o);
  validate_scene(s);
}

std::string overrides_text(const std::vector<SceneOverride>& overrides) {
  std::string t;
  for (const SceneOverride& o : overrides) t += (t.empty() ? "" : ";") + o.name + "=" + o.value;
  return t;
}

std::vector<std::string> override_help() {
  std::vector<std::string> lines;
  for (const Entry& e : entries()) {
    std::string n = e.name;
    n.resize(std::max<size_t>(n.size() + 2, 25), ' ');
    lines.push_back(n + e.help);
  }
  return lines;
}

}  // namespace weft::io
