#include "io/vellum_import.hpp"

#include "constraints/bend.hpp"
#include "constraints/triarap.hpp"
#include "constraints/vellum_cloth.hpp"
#include "core/error.hpp"
#include "core/topology.hpp"
#include "io/houdini_geo.hpp"
#include "io/obj.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numeric>
#include <sstream>
#include <system_error>

namespace weft::io {
namespace {

std::string str(size_t n) { return std::to_string(n); }

std::string num(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

std::string vec_str(Vec3 v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }

bool has_suffix(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

// The readers report an unreadable file as std::system_error; to the user it is bad input like any other.
template <class F>
auto reading(F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const std::system_error& e) {
    throw InputError(e.what());
  }
}

// A collider frame, and for attach constraints how Houdini numbers its primitives.
struct ColliderMesh {
  TriMesh mesh;
  std::vector<int> prim_triangle;  // .geo/.bgeo: the triangle of each triangle primitive, -1 for other primitives
  bool from_geo = false;
};

ColliderMesh read_collider_mesh(const std::string& path) {
  ColliderMesh c;
  if (has_suffix(path, ".obj")) {
    c.mesh = reading([&] { return read_obj(path); });
    return c;
  }
  const Geometry g = reading([&] { return read_geo(path); });
  Triangulation t = triangulate(g);
  c.mesh = std::move(t.mesh);
  c.prim_triangle.assign(g.primitives.size(), -1);
  for (size_t k = 0; k < t.primitive.size(); ++k)
    if (g.primitives[size_t(t.primitive[k])].points.size() == 3) c.prim_triangle[size_t(t.primitive[k])] = int(k);
  c.from_geo = true;
  return c;
}

struct LoadedCollider {
  Collider collider;
  ColliderMesh first_frame;
};

LoadedCollider load_collider(const std::string& name, const std::string& pattern, int first, int last) {
  const std::vector<std::string> files = pattern.find("$F") == std::string::npos
                                             ? std::vector<std::string>{pattern}
                                             : expand_frame_pattern(pattern, first, last);
  LoadedCollider out;
  Collider& c = out.collider;
  c.name = name;
  for (size_t f = 0; f < files.size(); ++f) {
    ColliderMesh m = read_collider_mesh(files[f]);
    for (size_t k = 0; k < m.mesh.positions.size(); ++k)
      if (!isfinite_(m.mesh.positions[k]))
        throw InputError(files[f] + ": point " + str(k) + " has a non-finite position " + vec_str(m.mesh.positions[k]));
    if (f == 0) {
      if (m.mesh.triangles.empty()) throw InputError(files[f] + ": the collider has no triangles");
      c.triangles = m.mesh.triangles;
    } else if (m.mesh.positions.size() != c.motion.frames[0].size() || m.mesh.triangles != c.triangles) {
      const bool same_counts =
          m.mesh.positions.size() == c.motion.frames[0].size() && m.mesh.triangles.size() == c.triangles.size();
      throw InputError(files[f] + ": the collider's topology changes at frame " + std::to_string(first + int(f)) +
                       " (" +
                       (same_counts ? "other triangles than " + files[0]
                                    : str(m.mesh.positions.size()) + " points, " + str(m.mesh.triangles.size()) +
                                          " triangles; " + files[0] + " has " + str(c.motion.frames[0].size()) +
                                          " points, " + str(c.triangles.size()) + " triangles") +
                       ")");
    }
    c.motion.frames.push_back(m.mesh.positions);
    if (f == 0) out.first_frame = std::move(m);
  }
  return out;
}

// ---- attributes ----------------------------------------------------------------------------------------

const Attribute* numeric(const AttributeMap& m, const std::string& file, const char* cls, const std::string& name,
                         int min_size = 1) {
  const auto it = m.find(name);
  if (it == m.end()) return nullptr;
  if (it->second.storage == Storage::String)
    throw InputError(file + ": " + cls + " attribute '" + name + "' holds strings, expected numbers");
  if (it->second.size < min_size)
    throw InputError(file + ": " + cls + " attribute '" + name + "' has " + std::to_string(it->second.size) +
                     " components, expected " + std::to_string(min_size));
  return &it->second;
}

const Attribute* text(const AttributeMap& m, const std::string& file, const char* cls, const std::string& name) {
  const auto it = m.find(name);
  if (it == m.end()) return nullptr;
  if (it->second.storage != Storage::String)
    throw InputError(file + ": " + cls + " attribute '" + name + "' holds numbers, expected strings");
  return &it->second;
}

Vec3 vec3(const Attribute& a, size_t e) { return {a.number(e, 0), a.number(e, 1), a.number(e, 2)}; }

// ---- constraint types --------------------------------------------------------------------------------------

enum class Kind { Distance, Bend, Triarap, TriarapNorm, Pin, Attach, PtPrim, Unsupported };

Kind kind_of(const std::string& type) {
  if (type == "distance" || type == "stitch" || type == "branchstitch" || type == "glue") return Kind::Distance;
  if (type == "bend") return Kind::Bend;
  if (type == "triarap" || type == "triarapnl") return Kind::Triarap;
  if (type == "triarapnorm") return Kind::TriarapNorm;
  if (type == "pin") return Kind::Pin;
  if (type == "attach") return Kind::Attach;
  if (type == "ptprim") return Kind::PtPrim;
  return Kind::Unsupported;
}

// Vertices per kind: the smallest and largest count.
std::array<size_t, 2> vertex_range(Kind k) {
  switch (k) {
    case Kind::Distance: return {2, 2};
    case Kind::Bend: return {4, 4};
    case Kind::Triarap:
    case Kind::TriarapNorm: return {3, 3};
    case Kind::Pin:
    case Kind::Attach: return {1, 1};
    case Kind::PtPrim: return {3, 5};
    case Kind::Unsupported: break;
  }
  return {0, 0};
}

class Importer {
 public:
  Importer(const std::string& sim_path, const std::string& cons_path, const VellumImportOptions& opt,
           VellumImportReport& rep)
      : sim_path_(sim_path), cons_path_(cons_path), opt_(opt), rep_(rep) {}

  Scene run() {
    sim_ = reading([&] { return read_geo(sim_path_); });
    cons_ = reading([&] { return read_geo(cons_path_); });
    refuse_packed(sim_, sim_path_);
    refuse_packed(cons_, cons_path_);
    for (const std::string& w : sim_.warnings) rep_.notes.push_back(sim_path_ + ": " + w);
    for (const std::string& w : cons_.warnings) rep_.notes.push_back(cons_path_ + ": " + w);
    if (sim_.points.size() != cons_.points.size())
      throw InputError("the simulation geometry " + sim_path_ + " has " + str(sim_.points.size()) +
                       " points and the constraint geometry " + cons_path_ + " has " + str(cons_.points.size()) +
                       "; a Vellum asset's two geometries have the same points");
    s_.name = sim_path_;
    match_points();
    read_points();
    read_triangles();
    read_settings(cons_, cons_path_);  // the simulation geometry's values win where both have one
    read_settings(sim_, sim_path_);
    if (opt_.frames) {
      s_.settings.frame_start = (*opt_.frames)[0];
      s_.settings.frame_end = (*opt_.frames)[1];
    }
    if (s_.settings.frame_end < s_.settings.frame_start)
      throw InputError(sim_path_ + ": frame range " + std::to_string(s_.settings.frame_start) + "-" +
                       std::to_string(s_.settings.frame_end) + " ends before it starts");
    read_colliders();
    read_constraints();
    if (!opt_.pin_target.empty()) follow_pin_target();
    refuse_unsupported();
    s_.needs_collisions = !s_.colliders.empty();
    validate_scene(s_);
    return std::move(s_);
  }

 private:
  static void refuse_packed(const Geometry& g, const std::string& path) {
    const bool tagged = g.primitive_attributes.count("vellum_type") > 0;
    const bool packed = std::any_of(g.primitives.begin(), g.primitives.end(), [](const Primitive& p) {
      return p.kind == PrimKind::Other && p.type_name.rfind("Packed", 0) == 0;
    });
    if (tagged || packed)
      throw InputError(path + ": packed Vellum geometry (" +
                       std::string(tagged ? "primitive attribute 'vellum_type'" : "packed primitives") +
                       "); unpack it (Vellum Unpack) and write the simulation geometry and the constraint geometry "
                       "to two files");
  }

  // cons_to_sim_[i]: the simulation point of constraint-geometry point i; by `id` when both geometries have it.
  void match_points() {
    const size_t n = sim_.points.size();
    const Attribute* sim_id = numeric(sim_.point_attributes, sim_path_, "point", "id");
    const Attribute* cons_id = numeric(cons_.point_attributes, cons_path_, "point", "id");
    cons_to_sim_.resize(n);
    if (!sim_id || !cons_id) {
      std::iota(cons_to_sim_.begin(), cons_to_sim_.end(), 0);
      if (sim_id || cons_id)
        rep_.notes.push_back("only " + (sim_id ? sim_path_ : cons_path_) + " has point ids: points matched by number");
      return;
    }
    std::map<int64_t, int> by_id;
    for (size_t p = 0; p < n; ++p) {
      const auto id = int64_t(sim_id->number(p));
      if (!by_id.emplace(id, int(p)).second)
        throw InputError(sim_path_ + ": point " + str(p) + " has id " + std::to_string(id) + ", as point " +
                         str(size_t(by_id[id])) + " does; ids must be unique");
    }
    std::vector<int> taken(n, -1);
    for (size_t p = 0; p < n; ++p) {
      const auto id = int64_t(cons_id->number(p));
      const auto it = by_id.find(id);
      if (it == by_id.end())
        throw InputError(cons_path_ + ": point " + str(p) + " has id " + std::to_string(id) + ", which no point of " +
                         sim_path_ + " has");
      if (taken[size_t(it->second)] >= 0)
        throw InputError(cons_path_ + ": point " + str(p) + " has id " + std::to_string(id) + ", as point " +
                         str(size_t(taken[size_t(it->second)])) + " does; ids must be unique");
      taken[size_t(it->second)] = int(p);
      cons_to_sim_[p] = it->second;
    }
  }

  [[noreturn]] void bad_point(size_t p, const std::string& what) const {
    throw InputError(sim_path_ + ": point " + str(p) + " " + what);
  }

  // A per-point float, checked finite (and non-negative where asked); `fallback` where the attribute is absent.
  real point_value(const Attribute* a, size_t p, const char* name, real fallback, bool non_negative) const {
    if (!a) return fallback;
    const real x = a->number(p);
    if (!isfinite_(x) || (non_negative && x < 0)) bad_point(p, std::string("has an invalid ") + name + " " + num(x));
    return x;
  }

  // --pin-target: the cloth's animated target (Vellum's animated rest input), matched by point number.
  // pintoanimation points follow it exactly; pin constraints are pulled to it (Vellum's Match Animation).
  void follow_pin_target() {
    const Collider track = load_collider("pin target", opt_.pin_target, s_.settings.frame_start,
                                         s_.settings.frame_end).collider;
    const size_t n = s_.points.size();
    if (track.motion.frames[0].size() != n)
      throw InputError(opt_.pin_target + ": the pin target has " + str(track.motion.frames[0].size()) +
                       " points, the simulation geometry " + sim_path_ + " " + str(n) +
                       " (targets are matched by point number)");
    // Goals: the kinematic points' first, in their order (kinematic_target[k] == k), then one per pin.
    Animation goals;
    for (const auto& frame : track.motion.frames) {
      goals.frames.emplace_back();
      for (int k : s_.kinematic_point) goals.frames.back().push_back(frame[size_t(k)]);
      for (size_t k : pin_rows_) goals.frames.back().push_back(frame[size_t(s_.constraints.pin[k].p)]);
    }
    s_.pin_targets = Animation{};
    add_pin_targets(s_, goals);
    int next = int(s_.kinematic_point.size());
    for (size_t k : pin_rows_) s_.constraints.pin[k].target = next++;
    rep_.notes.push_back("pins following " + opt_.pin_target + " (" + str(track.motion.frames.size()) +
                         " frames): " + str(s_.kinematic_point.size()) + " pintoanimation points exactly, " +
                         str(pin_rows_.size()) + " pin constraints");
  }

  void read_points() {
    const auto& at = sim_.point_attributes;
    const auto attr = [&](const char* name, int size = 1) { return numeric(at, sim_path_, "point", name, size); };
    const Attribute *v = attr("v", 3), *mass = attr("mass"), *pscale = attr("pscale"), *stopped = attr("stopped"),
                    *anim = attr("pintoanimation"), *friction = attr("friction"), *dfriction = attr("dynamicfriction"),
                    *layer = attr("layer");
    const ClothMaterial defaults;
    const size_t n = sim_.points.size();
    ClothPoints& p = s_.points;
    p.position = sim_.points;
    for (size_t i = 0; i < n; ++i) {
      if (!isfinite_(p.position[i])) bad_point(i, "has a non-finite position " + vec_str(p.position[i]));
      const Vec3 vel = v ? vec3(*v, i) : Vec3{};
      if (!isfinite_(vel)) bad_point(i, "has a non-finite velocity " + vec_str(vel));
      p.velocity.push_back(vel);
      p.thickness.push_back(point_value(pscale, i, "pscale", defaults.thickness, true));
      p.friction.push_back(point_value(friction, i, "friction", defaults.friction, true));
      p.dynamic_friction.push_back(point_value(dfriction, i, "dynamicfriction", defaults.dynamic_friction, true));
      p.layer.push_back(int(point_value(layer, i, "layer", defaults.layer, false)));
      p.stopped.push_back(stopped ? int(stopped->number(i)) & 1 : 0);
      if (mass) p.mass.push_back(point_value(mass, i, "mass", 0, true));
      if (anim && anim->number(i) != 0) {
        // No animated target comes with the asset: the point holds its imported position.
        s_.kinematic_point.push_back(int(i));
        s_.kinematic_target.push_back(int(s_.kinematic_target.size()));
      }
    }
    if (!s_.kinematic_point.empty()) {
      s_.pin_targets.frames.emplace_back();
      for (int k : s_.kinematic_point) s_.pin_targets.frames[0].push_back(p.position[size_t(k)]);
      if (opt_.pin_target.empty())
        rep_.notes.push_back("points with pintoanimation: " + str(s_.kinematic_point.size()) +
                             "; they hold their imported positions (no --pin-target animation given)");
    }
    count_unsupported_points("weld", [](double w) { return w >= 0; });
    count_unsupported_points("disableself", [](double d) { return d != 0; });
    count_unsupported_points("disableexternal", [](double d) { return d != 0; });
  }

  template <class Used>
  void count_unsupported_points(const char* name, Used used) {
    const Attribute* a = numeric(sim_.point_attributes, sim_path_, "point", name);
    if (!a) return;
    size_t k = 0;
    for (size_t i = 0; i < sim_.points.size(); ++i) k += used(a->number(i)) ? 1 : 0;
    if (k) rep_.unsupported[std::string("point attribute ") + name] += k;
  }

  void read_triangles() {
    const Triangulation t = triangulate(sim_);
    const std::vector<Vec3>& x = s_.points.position;
    for (size_t k = 0; k < t.mesh.triangles.size(); ++k) {
      const auto& tri = t.mesh.triangles[k];
      if (!(triangle_area(x[size_t(tri[0])], x[size_t(tri[1])], x[size_t(tri[2])]) > 0)) {
        const Primitive& prim = sim_.primitives[size_t(t.primitive[k])];
        std::string pts;
        for (int q : prim.points) pts += (pts.empty() ? "" : ", ") + std::to_string(q);
        throw InputError(sim_path_ + ": primitive " + str(size_t(t.primitive[k])) + " (points " + pts +
                         ") has zero area");
      }
    }
    s_.triangles = t.mesh.triangles;
    for (const Primitive& prim : sim_.primitives) {
      if (prim.kind == PrimKind::Polygon) continue;
      const std::string kind = prim.kind == PrimKind::Polyline ? "Polyline"
                               : prim.kind == PrimKind::Sphere ? "Sphere"
                                                               : prim.type_name;
      ++rep_.unsupported["simulation primitive " + kind];
    }
    if (s_.points.mass.empty()) {
      // No mass attribute: masses from the default area density, as the Vellum Constraints node would.
      s_.points.mass = lumped_masses(x, s_.triangles, ClothMaterial{}.density);
      const size_t loose = size_t(std::count(s_.points.mass.begin(), s_.points.mass.end(), real(0)));
      rep_.notes.push_back(sim_path_ + ": no point attribute 'mass': masses from an area density of " +
                           num(ClothMaterial{}.density) + " kg/m^2" +
                           (loose ? "; " + str(loose) + " points on no triangle get infinite mass" : ""));
    }
    assign_pieces();
  }

  // Pieces are the connected components of the triangle mesh, numbered by their lowest point.
  void assign_pieces() {
    const size_t n = s_.points.size();
    std::vector<int> root(n);
    std::iota(root.begin(), root.end(), 0);
    const auto find = [&](int a) {
      while (root[size_t(a)] != a) a = root[size_t(a)] = root[size_t(root[size_t(a)])];
      return a;
    };
    for (const auto& t : s_.triangles)
      for (int k = 1; k < 3; ++k) {
        const int a = find(t[0]), b = find(t[size_t(k)]);
        root[size_t(std::max(a, b))] = std::min(a, b);
      }
    std::map<int, int> piece;
    for (size_t i = 0; i < n; ++i) {
      const int r = find(int(i));
      s_.points.piece.push_back(piece.emplace(r, int(piece.size())).first->second);
    }
  }

  void read_settings(const Geometry& g, const std::string& path) {
    SolverSettings& st = s_.settings;
    const auto value = [&](const char* name, int size = 1) -> const Attribute* {
      const Attribute* a = numeric(g.detail_attributes, path, "detail", name, size);
      if (!a) return nullptr;
      for (int c = 0; c < size; ++c)
        if (!isfinite_(a->number(0, c))) throw InputError(path + ": detail attribute '" + name + "' is not finite");
      return a;
    };
    const auto integer = [&](const char* name, int& to) {
      if (const Attribute* a = value(name)) {
        const double x = a->number(0);
        if (x != std::floor(x))
          throw InputError(path + ": detail attribute '" + name + "' = " + num(x) + ": expected an integer");
        to = int(x);
      }
    };
    if (const Attribute* a = value("fps")) st.fps = a->number(0);
    integer("framestart", st.frame_start);
    integer("frameend", st.frame_end);
    integer("substeps", st.substeps);
    integer("constraintiterations", st.iterations);
    integer("collisionpasses", st.collision_passes);
    integer("smoothingiterations", st.smoothing_iterations);
    if (const Attribute* a = value("gravity", 3)) st.gravity = vec3(*a, 0);
    if (const Attribute* a = value("wind", 3)) st.wind = vec3(*a, 0);
    if (const Attribute* a = value("velocitydamping")) st.velocity_damping = a->number(0);
  }

  void read_colliders() {
    for (const VellumCollider& vc : opt_.colliders) {
      const std::string name = vc.name.empty() ? collider_name_from_pattern(vc.pattern) : vc.name;
      for (const Collider& c : s_.colliders)
        if (c.name == name) throw InputError(vc.pattern + ": a second collider named '" + name + "'");
      LoadedCollider lc = load_collider(name, vc.pattern, s_.settings.frame_start, s_.settings.frame_end);
      lc.collider.thickness = vc.thickness;
      lc.collider.friction = vc.friction;
      s_.colliders.push_back(std::move(lc.collider));
      collider_meshes_.push_back(std::move(lc.first_frame));
    }
  }

  // The collider an attach constraint's target_path names: the only one, else by name, a path component
  // ("/obj/body/OUT" names "body") or a number; -1 when no collider was given.
  int collider_for(const std::string& target, const std::string& where) const {
    const size_t n = s_.colliders.size();
    if (n <= 1) return n == 1 ? 0 : -1;
    for (size_t i = 0; i < n; ++i)
      if (target == s_.colliders[i].name) return int(i);
    std::vector<std::string> parts;
    std::istringstream in(target);
    for (std::string part; std::getline(in, part, '/');) parts.push_back(part);
    for (size_t i = 0; i < n; ++i)
      if (std::find(parts.begin(), parts.end(), s_.colliders[i].name) != parts.end()) return int(i);
    if (!target.empty() &&
        std::all_of(target.begin(), target.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }) &&
        std::stoul(target) < n)
      return int(std::stoul(target));
    std::string names;
    for (const Collider& c : s_.colliders) names += (names.empty() ? "" : ", ") + c.name;
    throw InputError(where + ": target_path '" + target + "' names none of the colliders (" + names + ")");
  }

  struct PrimAttributes {
    const Attribute *type, *stiffness, *compress, *damping, *restlength, *restvector, *target_path, *target_prim,
        *target_pt, *target_uv;
  };

  void read_constraints() {
    const auto& at = cons_.primitive_attributes;
    const auto number = [&](const char* name, int size = 1) {
      return numeric(at, cons_path_, "primitive", name, size);
    };
    PrimAttributes a{text(at, cons_path_, "primitive", "type"),
                     number("stiffness"),
                     number("compressstiffness"),
                     number("dampingratio"),
                     number("restlength"),
                     number("restvector", 2),
                     text(at, cons_path_, "primitive", "target_path"),
                     number("target_prim"),
                     number("target_pt"),
                     number("target_uv", 2)};
    if (cons_.primitives.empty()) return;
    if (!a.type)
      throw InputError(cons_path_ + ": no primitive attribute 'type': this is not a Vellum constraint geometry");
    if (!a.stiffness) throw InputError(cons_path_ + ": no primitive attribute 'stiffness'");
    for (size_t i = 0; i < cons_.primitives.size(); ++i) read_constraint(i, a);
    for (const auto& [target, count] : fixed_attach_)
      rep_.notes.push_back("attach constraints to '" + target + "': " + str(count) +
                           "; no collider was given, so they hold their points where they are");
  }

  void read_constraint(size_t i, const PrimAttributes& a) {
    const std::string type = a.type->strings[i].empty() ? "(no type)" : a.type->strings[i];
    const Kind kind = kind_of(type);
    if (kind == Kind::Unsupported) {
      ++rep_.unsupported[type];
      return;
    }
    const std::string where = cons_path_ + ": primitive " + str(i) + " (" + type + ")";
    const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
    const auto value = [&](const Attribute* attr, const char* name, real fallback) {
      if (!attr) return fallback;
      const real x = attr->number(i);
      if (!isfinite_(x)) fail(std::string(name) + " is not finite");
      return x;
    };
    const real k = value(a.stiffness, "stiffness", 0);
    if (k < 0) fail("stiffness " + num(k) + " is negative");
    if (k == 0) {
      ++rep_.skipped[type];
      return;
    }
    const real ck = value(a.compress, "compressstiffness", -1);
    const real damping = value(a.damping, "dampingratio", 0);
    if (damping < 0) fail("dampingratio " + num(damping) + " is negative");
    // compressstiffness 0 ("no resistance while compressed"): compress compliance +inf, a row that only pulls
    // (constraints/xpbd.hpp).
    const XpbdMaterial m = xpbd_material(k, ck, damping);

    const Primitive& prim = cons_.primitives[i];
    const auto [lo, hi] = vertex_range(kind);
    if (prim.points.size() < lo || prim.points.size() > hi)
      fail("has " + str(prim.points.size()) + " points, expected " + (lo == hi ? str(lo) : str(lo) + " to " + str(hi)));
    std::vector<int> p;
    for (int q : prim.points) {
      const int sp = cons_to_sim_.at(size_t(q));
      if (std::find(p.begin(), p.end(), sp) != p.end()) fail("uses point " + std::to_string(q) + " twice");
      p.push_back(sp);
    }
    const std::vector<Vec3>& x = s_.points.position;
    const auto X = [&](size_t k2) { return x[size_t(p[k2])]; };
    const bool has_rest = a.restlength != nullptr;
    const real rest = value(a.restlength, "restlength", 0);
    const auto restvector = [&](int q) {
      const real r = a.restvector->number(i, q);
      if (!isfinite_(r)) fail("restvector is not finite");
      return r;
    };
    Constraints& c = s_.constraints;
    switch (kind) {
      case Kind::Distance: {
        const real L = has_rest ? rest : norm(X(1) - X(0));
        if (L < 0) fail("restlength " + num(L) + " is negative");
        c.distance.push_back({p[0], p[1], L, m});
        break;
      }
      case Kind::Bend:
        // Vellum stores the rest angle in degrees.
        c.bend.push_back(
            {p[0], p[1], p[2], p[3], has_rest ? rest * pi / 180 : bend_rest_angle(X(0), X(1), X(2), X(3)), m});
        break;
      case Kind::Triarap:
      case Kind::TriarapNorm: {
        TriarapConstraint t{p[0], p[1], p[2], {0, 0, 0, 0}, 0, kind == Kind::TriarapNorm, m};
        triarap_rest(X(0), X(1), X(2), t.dm_inv, t.area);
        if (a.restvector) {
          if (a.restvector->size < 4)
            fail("restvector has " + std::to_string(a.restvector->size) + " components, expected 4");
          for (int q = 0; q < 4; ++q) t.dm_inv[q] = restvector(q);
        }
        if (has_rest) t.area = rest;
        if (!(t.area > 0)) fail("has zero rest area");
        c.triarap.push_back(t);
        break;
      }
      case Kind::Pin: {
        Vec3 goal = X(0);
        if (a.restvector) {
          if (a.restvector->size < 3)
            fail("restvector has " + std::to_string(a.restvector->size) + " components, expected 3 or 4");
          goal = {restvector(0), restvector(1), restvector(2)};
        }
        c.pin.push_back({p[0], goal, -1, rest, m});
        pin_rows_.push_back(c.pin.size() - 1);
        break;
      }
      case Kind::Attach: read_attach(i, a, p[0], rest, m, where); break;
      case Kind::PtPrim: {
        if (!a.restvector) fail("no primitive attribute 'restvector' with the (u, v) weights");
        const real u = restvector(0), v = restvector(1);
        PtPrimConstraint t{p[0], {0, 0, 0, 0}, {0, 0, 0, 0}, int(p.size()) - 1, 0, m};
        // Segment: (1-u, u); triangle: barycentric (1-u-v, u, v); quad: bilinear over the corners in order.
        const real w2[] = {1 - u, u}, w3[] = {1 - u - v, u, v},
                   w4[] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
        const real* w = t.nt == 2 ? w2 : t.nt == 3 ? w3 : w4;
        Vec3 target{};
        for (int q = 0; q < t.nt; ++q) {
          t.t[q] = p[size_t(q) + 1];
          t.w[q] = w[q];
          target = target + w[q] * X(size_t(q) + 1);
        }
        t.rest = has_rest ? rest : norm(target - X(0));
        if (t.rest < 0) fail("restlength " + num(t.rest) + " is negative");
        c.ptprim.push_back(t);
        break;
      }
      case Kind::Unsupported: break;
    }
    ++rep_.imported[type];
  }

  void read_attach(size_t i, const PrimAttributes& a, int p, real rest, const XpbdMaterial& m,
                   const std::string& where) {
    const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
    const std::string target = a.target_path ? a.target_path->strings[i] : std::string();
    const int col = collider_for(target, where);
    if (col < 0) {
      s_.constraints.pin.push_back({p, s_.points.position[size_t(p)], -1, rest, m});
      ++fixed_attach_[target.empty() ? "(no target_path)" : target];
      return;
    }
    const Collider& collider = s_.colliders[size_t(col)];
    const ColliderMesh& mesh = collider_meshes_[size_t(col)];
    const auto index = [&](const Attribute* attr) { return attr ? int64_t(attr->number(i)) : int64_t(-1); };
    const int64_t prim = index(a.target_prim), pt = index(a.target_pt);
    AttachConstraint t{p, col, -1, 0, 0, rest, m};
    if (prim >= 0) {
      if (!a.target_uv) fail("no primitive attribute 'target_uv'");
      const real u = a.target_uv->number(i, 0), v = a.target_uv->number(i, 1);
      if (!isfinite_(u) || !isfinite_(v)) fail("target_uv is not finite");
      if (mesh.from_geo) {
        if (size_t(prim) >= mesh.prim_triangle.size())
          fail("target_prim " + std::to_string(prim) + " is out of range: collider '" + collider.name + "' has " +
               str(mesh.prim_triangle.size()) + " primitives");
        t.tri = mesh.prim_triangle[size_t(prim)];
        if (t.tri < 0)
          fail("target_prim " + std::to_string(prim) + " of collider '" + collider.name + "' is not a triangle");
        // Houdini's (u, v) weigh vertices 1 and 2; triangulation reversed the winding to (0, 2, 1).
        t.u = v;
        t.v = u;
      } else {
        if (size_t(prim) >= collider.triangles.size())
          fail("target_prim " + std::to_string(prim) + " is out of range: collider '" + collider.name + "' has " +
               str(collider.triangles.size()) + " triangles");
        t.tri = int(prim);
        t.u = u;
        t.v = v;
      }
    } else if (pt >= 0) {
      // A point target: the first triangle that has it, weighted fully to that corner.
      for (size_t k = 0; k < collider.triangles.size() && t.tri < 0; ++k)
        for (int corner = 0; corner < 3; ++corner)
          if (collider.triangles[k][size_t(corner)] == pt) {
            t.tri = int(k);
            t.u = corner == 1 ? 1 : 0;
            t.v = corner == 2 ? 1 : 0;
          }
      if (t.tri < 0) fail("target_pt " + std::to_string(pt) + " is on no triangle of collider '" + collider.name + "'");
    } else {
      fail("neither target_prim nor target_pt names a target on collider '" + collider.name + "'");
    }
    s_.constraints.attach.push_back(t);
  }

  // Skipping leaves the list in the report (VellumImportReport::unsupported) for the caller to show.
  void refuse_unsupported() {
    if (rep_.unsupported.empty()) return;
    std::string list;
    for (const auto& [what, n] : rep_.unsupported) list += (list.empty() ? "" : ", ") + what + " (" + str(n) + ")";
    if (!opt_.skip_unsupported)
      throw InputError(sim_path_ + ", " + cons_path_ + ": weft cannot simulate " + list +
                       "; import with --skip-unsupported to leave them out");
  }

  const std::string& sim_path_;
  const std::string& cons_path_;
  const VellumImportOptions& opt_;
  VellumImportReport& rep_;
  Geometry sim_, cons_;
  std::vector<int> cons_to_sim_;
  Scene s_;
  std::vector<ColliderMesh> collider_meshes_;
  std::map<std::string, size_t> fixed_attach_;
  std::vector<size_t> pin_rows_;  // the pin constraints of type "pin" (not attach constraints turned pins)
};

}  // namespace

Collider read_collider(const std::string& name, const std::string& pattern, int first, int last) {
  return load_collider(name, pattern, first, last).collider;
}

std::string collider_name_from_pattern(const std::string& pattern) {
  const size_t slash = pattern.find_last_of('/');
  std::string n = slash == std::string::npos ? pattern : pattern.substr(slash + 1);
  const size_t var = n.find('$');
  if (var != std::string::npos)
    n.resize(var);
  else if (const size_t dot = n.find('.'); dot != std::string::npos && dot > 0)
    n.resize(dot);
  while (!n.empty() && (n.back() == '.' || n.back() == '_' || n.back() == '-')) n.pop_back();
  return n.empty() ? "collider" : n;
}

Scene import_vellum(const std::string& sim_geo, const std::string& constraint_geo, const VellumImportOptions& opt,
                    VellumImportReport* report) {
  VellumImportReport local;
  return Importer(sim_geo, constraint_geo, opt, report ? *report : local).run();
}

}  // namespace weft::io
