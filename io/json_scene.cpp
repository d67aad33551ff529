#include "io/json_scene.hpp"

#include "collision/ccd_proximity.hpp"
#include "constraints/vellum_cloth.hpp"
#include "core/error.hpp"
#include "core/topology.hpp"
#include "io/builtin_scenes.hpp"
#include "io/obj.hpp"
#include "io/procedural.hpp"
#include "io/vellum_import.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <system_error>

namespace weft::io {
namespace {

using json = nlohmann::json;

enum class Range { Any, NonNegative, Positive };

// A JSON value and where it is, so that every error names the file and the JSON path.
class Node {
 public:
  Node(const std::string& file, const json& j, std::string path) : file_(file), j_(j), path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_ + ": " + (path_.empty() ? "top level" : path_) + ": " + what);
  }
  const std::string& file() const { return file_; }

  // An object whose keys are all in `known` (a misspelt key is an error, not a silent default).
  const Node& object(std::initializer_list<const char*> known) const {
    if (!j_.is_object()) fail("expected an object {...}");
    for (const auto& item : j_.items()) {
      bool ok = false;
      for (const char* k : known) ok = ok || item.key() == k;
      if (!ok) {
        std::string list;
        for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        child_path_fail(item.key(), "unknown key (known here: " + list + ")");
      }
    }
    return *this;
  }
  bool has(const char* key) const { return j_.contains(key); }
  Node operator[](const char* key) const {
    if (!has(key)) fail(std::string("missing key '") + key + "'");
    return Node(file_, j_.at(key), path_.empty() ? key : path_ + "." + key);
  }
  size_t size() const {
    if (!j_.is_array()) fail("expected an array [...]");
    return j_.size();
  }
  Node item(size_t i) const { return Node(file_, j_.at(i), path_ + "[" + std::to_string(i) + "]"); }
  std::vector<std::string> keys() const {
    if (!j_.is_object()) fail("expected an object {...}");
    std::vector<std::string> k;
    for (const auto& item : j_.items()) k.push_back(item.key());
    return k;
  }
  Node at_key(const std::string& key) const { return Node(file_, j_.at(key), path_ + "." + key); }

  real number(Range r = Range::Any) const {
    if (!j_.is_number()) fail("expected a number");
    const real x = j_.get<real>();
    if (!std::isfinite(x)) fail("expected a finite number");
    if (r == Range::NonNegative && x < 0) fail("expected a number >= 0, got " + j_.dump());
    if (r == Range::Positive && !(x > 0)) fail("expected a positive number, got " + j_.dump());
    return x;
  }
  int integer(int lo, int hi = 1 << 30) const {
    if (!j_.is_number() || j_.get<double>() != std::floor(j_.get<double>())) fail("expected an integer");
    const double x = j_.get<double>();
    if (x < lo || x > hi)
      fail("expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + j_.dump());
    return int(x);
  }
  std::string string() const {
    if (!j_.is_string()) fail("expected a string");
    return j_.get<std::string>();
  }
  bool boolean() const {
    if (!j_.is_boolean()) fail("expected true or false");
    return j_.get<bool>();
  }
  Vec3 vec3() const {
    if (!j_.is_array() || j_.size() != 3) fail("expected [x, y, z]");
    Vec3 v;
    for (size_t c = 0; c < 3; ++c) v[int(c)] = item(c).number();
    return v;
  }

  // Optional keys.
  real number(const char* key, real fallback, Range r = Range::Any) const {
    return has(key) ? (*this)[key].number(r) : fallback;
  }
  int integer(const char* key, int fallback, int lo, int hi = 1 << 30) const {
    return has(key) ? (*this)[key].integer(lo, hi) : fallback;
  }
  Vec3 vec3(const char* key, Vec3 fallback) const { return has(key) ? (*this)[key].vec3() : fallback; }

 private:
  [[noreturn]] void child_path_fail(const std::string& key, const std::string& what) const {
    Node(file_, j_, path_.empty() ? key : path_ + "." + key).fail(what);
  }

  const std::string& file_;
  const json& j_;
  std::string path_;
};

json parse_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    const std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line L, column C: ..."
    const size_t tag = what.find("] ");
    throw InputError(path + ": " + (tag == std::string::npos ? what : what.substr(tag + 2)));
  }
}

// Runs a file reader for a JSON node: errors about the referenced file are reported at that node.
template <class F>
auto reading_for(const Node& n, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const std::system_error& e) {
    n.fail(e.what());
  } catch (const InputError& e) {
    n.fail(e.what());
  }
}

std::string resolve(const std::string& json_path, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? file : (std::filesystem::path(json_path).parent_path() / p).string();
}

void read_settings(const Node& n, Scene& s) {
  n.object({"fps", "frames", "substeps", "iterations", "collision_passes", "smoothing", "gravity", "wind", "damping",
            "impact_zone_smoothing", "collision_failsafe", "contact_solver", "ccd_span", "tethers", "collisions",
            "contact_model", "early_pass_fraction", "early_pass_excess", "max_early_passes", "max_collider_early_passes", "pair_refresh", "merge_contacts", "nearest_margins",
            "predicted_reference", "layer_shock", "still_tolerance", "chebyshev_rho",
            "chebyshev_delay", "stretch_limits", "coarse_levels", "coarse_iterations"});
  SolverSettings& st = s.settings;
  st.fps = n.number("fps", st.fps, Range::Positive);
  if (n.has("frames")) {
    const Node f = n["frames"];
    if (f.size() != 2) f.fail("expected [first, last]");
    st.frame_start = f.item(0).integer(-(1 << 30));
    st.frame_end = f.item(1).integer(st.frame_start);
  }
  st.substeps = n.integer("substeps", st.substeps, 1);
  st.iterations = n.integer("iterations", st.iterations, 0);
  st.collision_passes = n.integer("collision_passes", st.collision_passes, 0);
  st.smoothing_iterations = n.integer("smoothing", st.smoothing_iterations, 0);
  st.chebyshev_rho = n.number("chebyshev_rho", st.chebyshev_rho, Range::NonNegative);
  if (!(st.chebyshev_rho < 1)) n["chebyshev_rho"].fail("expected a rate in [0, 1) (0: no Chebyshev acceleration)");
  st.chebyshev_delay = n.integer("chebyshev_delay", st.chebyshev_delay, 1);
  st.gravity = n.vec3("gravity", st.gravity);
  st.wind = n.vec3("wind", st.wind);
  st.velocity_damping = n.number("damping", st.velocity_damping, Range::NonNegative);
  if (n.has("impact_zone_smoothing")) st.collision.impact_zone_smoothing = n["impact_zone_smoothing"].boolean();
  if (n.has("collision_failsafe")) st.collision.collision_failsafe = n["collision_failsafe"].boolean();
  if (n.has("contact_solver")) {
    const auto v = parse_contact_solver(n["contact_solver"].string());
    if (!v) n["contact_solver"].fail("expected \"gauss-seidel\" or \"jacobi\"");
    st.collision.contact_solver = *v;
  }
  if (n.has("contact_model")) {
    const std::string v = n["contact_model"].string();
    const auto m = parse_contact_model(v);
    if (!m) n["contact_model"].fail("expected \"proximity\" or \"ccd\"");
    st.collision.contact_model = *m;
  }
  st.collision.early_pass_fraction =
      n.number("early_pass_fraction", st.collision.early_pass_fraction, Range::NonNegative);
  st.collision.early_pass_excess =
      n.number("early_pass_excess", st.collision.early_pass_excess, Range::NonNegative);
  st.collision.max_early_passes = n.integer("max_early_passes", st.collision.max_early_passes, 0);
  st.collision.max_collider_early_passes =
      n.integer("max_collider_early_passes", st.collision.max_collider_early_passes, 0);
  if (n.has("pair_refresh")) st.collision.pair_refresh = n["pair_refresh"].boolean();
  if (n.has("merge_contacts")) st.collision.merge_contacts = n["merge_contacts"].boolean();
  if (n.has("nearest_margins")) st.collision.nearest_margins = n["nearest_margins"].boolean();
  if (n.has("predicted_reference")) st.collision.predicted_reference = n["predicted_reference"].boolean();
  st.collision.still_tolerance = n.number("still_tolerance", st.collision.still_tolerance, Range::NonNegative);
  st.collision.layer_shock = n.number("layer_shock", st.collision.layer_shock, Range::Positive);
  if (st.collision.layer_shock < 1) n["layer_shock"].fail("expected a number >= 1 (1: off)");
  if (n.has("ccd_span")) {
    const auto v = parse_ccd_span(n["ccd_span"].string());
    if (!v) n["ccd_span"].fail("expected \"substep\" or \"pass\"");
    st.collision.ccd_span = *v;
  }
  st.stretch_limits = n.integer("stretch_limits", st.stretch_limits, 0, 3);
  st.coarse_levels = n.integer("coarse_levels", st.coarse_levels, 0, 16);
  st.coarse_iterations = n.integer("coarse_iterations", st.coarse_iterations, 1, 1000);
  if (n.has("tethers")) {
    st.tether_stretch = n.number("tethers", st.tether_stretch, Range::NonNegative);
    if (st.tether_stretch != 0 && st.tether_stretch < 1)
      n["tethers"].fail("expected 0 (no tethers) or a stretch of at least 1");
  }
  if (n.has("collisions")) s.needs_collisions = n["collisions"].boolean();
}

ClothMaterial read_material(const Node& n) {
  n.object({"density", "thickness", "stretch", "stretch_stiffness", "compress_stiffness", "stretch_damping",
            "bend_stiffness", "bend_damping", "young", "poisson", "fabric_thickness", "friction", "dynamic_friction",
            "layer"});
  ClothMaterial m;
  m.density = n.number("density", m.density, Range::Positive);
  m.thickness = n.number("thickness", m.thickness, Range::NonNegative);
  if (n.has("stretch")) {
    const std::string model = n["stretch"].string();
    if (model == "distance")
      m.stretch = StretchModel::Distance;
    else if (model == "triarap")
      m.stretch = StretchModel::Triarap;
    else if (model == "triarapnorm")
      m.stretch = StretchModel::TriarapNorm;
    else if (model == "fem")
      m.stretch = StretchModel::Fem;
    else
      n["stretch"].fail("unknown stretch model '" + model + "' (distance, triarap, triarapnorm, fem)");
  }
  m.stretch_stiffness = n.number("stretch_stiffness", m.stretch_stiffness, Range::Positive);
  if (n.has("compress_stiffness")) {
    m.compress_stiffness = n["compress_stiffness"].number();
    if (!(m.compress_stiffness > 0 || m.compress_stiffness == -1))
      n["compress_stiffness"].fail("expected -1 (same as stretch) or a positive number");
  }
  m.stretch_damping = n.number("stretch_damping", m.stretch_damping, Range::NonNegative);
  m.bend_stiffness = n.number("bend_stiffness", m.bend_stiffness, Range::NonNegative);
  m.bend_damping = n.number("bend_damping", m.bend_damping, Range::NonNegative);
  m.young = n.number("young", m.young, Range::Positive);
  if (n.has("poisson")) {
    m.poisson = n["poisson"].number();
    if (!(m.poisson > -1 && m.poisson < 1)) n["poisson"].fail("expected a number in (-1, 1)");
  }
  m.fabric_thickness = n.number("fabric_thickness", m.fabric_thickness, Range::Positive);
  m.friction = n.number("friction", m.friction, Range::NonNegative);
  m.dynamic_friction = n.number("dynamic_friction", m.dynamic_friction, Range::NonNegative);
  m.layer = n.integer("layer", m.layer, -(1 << 30));
  return m;
}

Mesh read_cloth_obj(const Node& n, const std::string& json_path) {
  const std::string file = n.string();
  if (file.find("$F") != std::string::npos) n.fail("a cloth piece is one mesh, not a frame sequence");
  const std::string path = resolve(json_path, file);
  const TriMesh t = reading_for(n, [&] { return read_obj(path); });
  if (t.triangles.empty()) n.fail(path + ": no triangles");
  std::vector<char> used(t.positions.size(), 0);
  for (size_t k = 0; k < t.triangles.size(); ++k) {
    const auto& tri = t.triangles[k];
    for (int q : tri) used[size_t(q)] = 1;
    if (!(triangle_area(t.positions[size_t(tri[0])], t.positions[size_t(tri[1])], t.positions[size_t(tri[2])]) > 0))
      n.fail(path + ": triangle " + std::to_string(k) + " (vertices " + std::to_string(tri[0] + 1) + ", " +
             std::to_string(tri[1] + 1) + ", " + std::to_string(tri[2] + 1) + ") has zero area");
  }
  for (size_t p = 0; p < t.positions.size(); ++p) {
    if (!isfinite_(t.positions[p])) n.fail(path + ": vertex " + std::to_string(p + 1) + " is not finite");
    // A point on no triangle would get no mass, which means a permanent pin.
    if (!used[p]) n.fail(path + ": vertex " + std::to_string(p + 1) + " is on no face");
  }
  return {t.positions, t.triangles};
}

Mesh read_grid(const Node& n) {
  int nu = 16, nv = 16;
  if (n.has("res")) {
    const Node r = n["res"];
    if (r.size() != 2) r.fail("expected [nu, nv]");
    nu = r.item(0).integer(1, 4096);
    nv = r.item(1).integer(1, 4096);
  }
  const Vec3 du = n.vec3("u", {1, 0, 0}), dv = n.vec3("v", {0, 0, 1});
  if (!(norm(cross(du, dv)) > 0)) n.fail("u and v must span a rectangle (non-zero, not parallel)");
  return grid(nu, nv, n.vec3("origin", {-0.5, 1, -0.5}), du, dv);
}

// Points of a piece (its own numbering) that a pin selects.
std::vector<int> pin_selection(const Node& pin, const Node& cloth, const Mesh& m) {
  const int n = int(m.x.size());
  const auto indices = [n](const Node& list) {
    std::vector<int> r;
    for (size_t k = 0; k < list.size(); ++k) r.push_back(list.item(k).integer(0, n - 1));
    return r;
  };
  const int kinds = int(pin.has("points")) + int(pin.has("group")) + int(pin.has("box"));
  if (kinds != 1) pin.fail("give exactly one of 'points', 'group', 'box'");
  if (pin.has("points")) return indices(pin["points"]);
  if (pin.has("group")) {
    const std::string name = pin["group"].string();
    const std::vector<std::string> groups = cloth.has("groups") ? cloth["groups"].keys() : std::vector<std::string>{};
    if (std::find(groups.begin(), groups.end(), name) == groups.end())
      pin["group"].fail("no group '" + name + "' in this cloth piece's 'groups'");
    return indices(cloth["groups"].at_key(name));
  }
  const Node box = pin["box"];
  box.object({"min", "max"});
  const Vec3 lo = box["min"].vec3(), hi = box["max"].vec3();
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) box.fail("min must not exceed max");
  std::vector<int> r;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = m.x[size_t(i)];
    if (p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z) r.push_back(i);
  }
  if (r.empty()) box.fail("no point of this cloth piece is inside the box");
  return r;
}

// A pin to a collider's surface, resolved once the colliders are read.
struct PendingAttach {
  std::string collider;
  std::string where;  // the JSON path, for errors
  std::vector<int> points;
  XpbdMaterial m;
};

void read_pins(const Node& cloth, const Mesh& m, int first, const std::string& json_path, Scene& s,
               std::vector<PendingAttach>& attaches) {
  const Node pins = cloth["pins"];
  for (size_t j = 0; j < pins.size(); ++j) {
    const Node pin = pins.item(j);
    pin.object({"points", "group", "box", "stiffness", "damping", "target", "attach"});
    const std::vector<int> sel = pin_selection(pin, cloth, m);
    const bool hard = !pin.has("stiffness");
    if (hard && pin.has("damping")) pin["damping"].fail("only a soft pin (with 'stiffness') has damping");
    if (pin.has("target") && pin.has("attach")) pin.fail("give at most one of 'target' and 'attach'");
    // Hard: compliance 0; soft: 1/k.
    const XpbdMaterial mat = hard ? XpbdMaterial{0, 0, 0}
                                  : xpbd_material(pin["stiffness"].number(Range::Positive), -1,
                                                  pin.number("damping", 0, Range::NonNegative));
    std::vector<int> points;
    for (int i : sel) points.push_back(first + i);
    if (pin.has("attach")) {
      attaches.push_back({pin["attach"].string(), pin["attach"].file() + ": " + "pins[" + std::to_string(j) + "].attach",
                          points, mat});
      continue;
    }
    if (pin.has("target")) {
      // An animated copy of this piece (an OBJ or Houdini geometry, a $F sequence over the scene's frames):
      // each selected point follows the point of the same number.
      const Node t = pin["target"];
      const std::string pattern = resolve(json_path, t.string());
      const Collider track = reading_for(t, [&] {
        return read_collider("pin target", pattern, s.settings.frame_start, s.settings.frame_end);
      });
      if (track.motion.frames[0].size() != m.x.size())
        t.fail(pattern + " has " + std::to_string(track.motion.frames[0].size()) + " points, this cloth piece " +
               std::to_string(m.x.size()) + " (targets are matched by point number)");
      Animation goals;
      for (const auto& frame : track.motion.frames) {
        goals.frames.emplace_back();
        for (int i : sel) goals.frames.back().push_back(frame[size_t(i)]);
      }
      const int k0 = add_pin_targets(s, goals);
      std::vector<int> targets;
      for (size_t k = 0; k < sel.size(); ++k) targets.push_back(k0 + int(k));
      pin_to_targets(s, points, targets, hard, mat);
      continue;
    }
    if (hard) {
      for (int p : points) s.points.stopped[size_t(p)] = 1;
    } else {
      for (int p : points) s.constraints.pin.push_back({p, s.points.position[size_t(p)], -1, 0, mat});
    }
  }
}

// Each attached point holds its place on the collider: the nearest point of the collider's first frame, at
// the distance it starts from.
void resolve_attach(const PendingAttach& a, Scene& s) {
  int col = -1;
  std::string names;
  for (size_t k = 0; k < s.colliders.size(); ++k) {
    if (s.colliders[k].name == a.collider) col = int(k);
    names += (names.empty() ? "" : ", ") + s.colliders[k].name;
  }
  if (col < 0) throw InputError(a.where + ": no collider named '" + a.collider + "' (colliders: " + (names.empty() ? "none" : names) + ")");
  const Collider& c = s.colliders[size_t(col)];
  const std::vector<Vec3>& x = c.motion.frames[0];
  for (int p : a.points) {
    const Vec3 q = s.points.position[size_t(p)];
    real best = -1;
    AttachConstraint t{p, col, -1, 0, 0, 0, a.m};
    for (size_t k = 0; k < c.triangles.size(); ++k) {
      const auto& tri = c.triangles[k];
      real w0, w1, w2;
      const real d2 = point_triangle_distance2(q, x[size_t(tri[0])], x[size_t(tri[1])], x[size_t(tri[2])], w0, w1, w2);
      if (best < 0 || d2 < best) {
        best = d2;
        t.tri = int(k);
        t.u = w1;
        t.v = w2;
      }
    }
    t.rest = std::sqrt(best);
    s.constraints.attach.push_back(t);
  }
}

// Stitches between points of any pieces: {"a": [piece, point], "b": [piece, point]}, sewn to `rest` (0).
void read_stitches(const Node& n, const std::vector<int>& piece_first, const std::vector<int>& piece_size, Scene& s) {
  for (size_t k = 0; k < n.size(); ++k) {
    const Node st = n.item(k);
    st.object({"a", "b", "stiffness", "damping", "rest"});
    int ends[2];
    for (int e = 0; e < 2; ++e) {
      const Node end = st[e == 0 ? "a" : "b"];
      if (end.size() != 2) end.fail("expected [piece, point]");
      const int piece = end.item(0).integer(0, int(piece_first.size()) - 1);
      ends[e] = piece_first[size_t(piece)] + end.item(1).integer(0, piece_size[size_t(piece)] - 1);
    }
    if (ends[0] == ends[1]) st.fail("a stitch joins two different points");
    const real k_st = st.number("stiffness", 1e10, Range::Positive);
    const XpbdMaterial mat = xpbd_material(k_st, -1, st.number("damping", 0, Range::NonNegative));
    s.constraints.distance.push_back({ends[0], ends[1], st.number("rest", 0, Range::NonNegative), mat});
  }
}

void read_cloth(const Node& n, const std::string& json_path, Scene& s, std::vector<PendingAttach>& attaches,
                std::vector<int>& piece_first, std::vector<int>& piece_size) {
  const bool obj = n.has("obj");
  if (obj == n.has("generator")) n.fail("give exactly one of 'obj' and 'generator'");
  Mesh m;
  if (obj) {
    n.object({"obj", "material", "pins", "groups"});
    m = read_cloth_obj(n["obj"], json_path);
  } else {
    n.object({"generator", "res", "origin", "u", "v", "material", "pins", "groups"});
    const std::string g = n["generator"].string();
    if (g != "grid") n["generator"].fail("unknown cloth generator '" + g + "' (grid)");
    m = read_grid(n);
  }
  const ClothMaterial mat = n.has("material") ? read_material(n["material"]) : ClothMaterial{};
  if (n.has("groups")) {
    const Node groups = n["groups"];
    for (const std::string& name : groups.keys()) {
      const Node list = groups.at_key(name);
      for (size_t k = 0; k < list.size(); ++k) list.item(k).integer(0, int(m.x.size()) - 1);
    }
  }
  const int first = add_cloth_piece(s, m.x, m.tris, mat);
  piece_first.push_back(first);
  piece_size.push_back(int(m.x.size()));
  if (n.has("pins")) read_pins(n, m, first, json_path, s, attaches);
}

Mesh read_collider_generator(const Node& n, const std::string& g) {
  const auto resolution = [&](const char* key, int fallback, int lo) { return n.integer(key, fallback, lo, 4096); };
  if (g == "sphere") {
    n.object({"generator", "name", "center", "radius", "rings", "segments", "thickness", "friction"});
    return uv_sphere(n.vec3("center", {}), n["radius"].number(Range::Positive), resolution("rings", 16, 2),
                     resolution("segments", 32, 3));
  }
  if (g == "box") {
    n.object({"generator", "name", "min", "max", "thickness", "friction"});
    const Vec3 lo = n["min"].vec3(), hi = n["max"].vec3();
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) n.fail("min must be below max in x, y and z");
    return box(lo, hi);
  }
  if (g == "capsule") {
    n.object({"generator", "name", "a", "b", "radius", "rings", "segments", "thickness", "friction"});
    const Vec3 a = n["a"].vec3(), b = n["b"].vec3();
    if (!(norm(b - a) > 0)) n.fail("a and b must differ");
    return capsule(a, b, n["radius"].number(Range::Positive), resolution("rings", 16, 2),
                   resolution("segments", 32, 3));
  }
  if (g == "plane") {
    n.object({"generator", "name", "center", "normal", "size", "thickness", "friction"});
    const Vec3 nrm = n.vec3("normal", {0, 1, 0});
    if (!(norm(nrm) > 0)) n["normal"].fail("expected a non-zero vector");
    const real size = n.number("size", 10, Range::Positive);
    // Tangents t1 x t2 = normal, so the square's triangles face along the normal.
    const Vec3 nh = normalized(nrm);
    const Vec3 t1 = normalized(cross(std::fabs(nh.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}, nh)), t2 = cross(nh, t1);
    return grid(1, 1, n.vec3("center", {}) - (size / 2) * (t1 + t2), size * t1, size * t2);
  }
  n["generator"].fail("unknown collider generator '" + g + "' (sphere, box, capsule, plane)");
}

Collider read_collider_entry(const Node& n, size_t index, const std::string& json_path, const SolverSettings& st) {
  Collider c;
  if (n.has("obj") == n.has("generator")) n.fail("give exactly one of 'obj' and 'generator'");
  if (n.has("obj")) {
    n.object({"obj", "name", "thickness", "friction"});
    const std::string pattern = n["obj"].string();
    const std::string name = n.has("name") ? n["name"].string() : collider_name_from_pattern(pattern);
    c = reading_for(n["obj"],
                    [&] { return read_collider(name, resolve(json_path, pattern), st.frame_start, st.frame_end); });
  } else {
    const std::string g = n["generator"].string();
    const Mesh m = read_collider_generator(n, g);
    c.name = n.has("name") ? n["name"].string() : g + std::to_string(index);
    c.triangles = m.tris;
    c.motion.frames.push_back(m.x);
  }
  c.thickness = n.number("thickness", c.thickness, Range::NonNegative);
  c.friction = n.number("friction", c.friction, Range::NonNegative);
  return c;
}

}  // namespace

Scene read_json_scene(const std::string& path) {
  const json j = parse_file(path);
  const Node root(path, j, "");
  root.object({"builtin", "res", "settings", "cloth", "colliders", "stitches"});
  Scene s;
  if (root.has("builtin")) {
    const Node b = root["builtin"];
    const BuiltinOptions opt{root.integer("res", 0, 1, 4096)};
    s = reading_for(b, [&] { return make_builtin_scene(b.string(), opt); });
  } else if (root.has("res")) {
    root["res"].fail("'res' sets the resolution of a 'builtin' base scene, and there is none");
  }
  s.name = path;
  if (root.has("settings")) read_settings(root["settings"], s);
  std::vector<PendingAttach> attaches;
  std::vector<int> piece_first, piece_size;
  if (root.has("cloth")) {
    const Node cloth = root["cloth"];
    for (size_t i = 0; i < cloth.size(); ++i) read_cloth(cloth.item(i), path, s, attaches, piece_first, piece_size);
  }
  if (root.has("stitches")) read_stitches(root["stitches"], piece_first, piece_size, s);
  if (root.has("colliders")) {
    const Node colliders = root["colliders"];
    for (size_t k = 0; k < colliders.size(); ++k)
      s.colliders.push_back(read_collider_entry(colliders.item(k), k, path, s.settings));
    const bool told = root.has("settings") && root["settings"].has("collisions");
    if (!told && colliders.size() > 0) s.needs_collisions = true;
  }
  for (const PendingAttach& a : attaches) resolve_attach(a, s);
  validate_scene(s);
  return s;
}

}  // namespace weft::io
