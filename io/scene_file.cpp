#include "io/scene_file.hpp"

#include "io/hdf5_util.hpp"

#include <cstring>
#include <utility>

namespace weft::io {
namespace {

// A field added to these structs must be added to the file (and the format version raised): the sizes are
// checked so that the scene file does not silently drop it (a field that fits in padding escapes the check).
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is stored as 3 doubles");
static_assert(sizeof(SolverSettings) == 240 && sizeof(CollisionSettings) == 112,
              "SolverSettings or CollisionSettings changed: update the settings tables below");
static_assert(sizeof(XpbdMaterial) == 24 && sizeof(DistanceConstraint) == 40 && sizeof(BendConstraint) == 48 &&
                  sizeof(TriarapConstraint) == 88 && sizeof(PinConstraint) == 72 && sizeof(AttachConstraint) == 64 &&
                  sizeof(PtPrimConstraint) == 96 && sizeof(FemConstraint) == 88,
              "a constraint struct changed: update the constraint tables of the scene file");

using Dims = std::vector<hsize_t>;

// A setting stored as one attribute: a field of SolverSettings itself or of its CollisionSettings.
template <class T>
struct Setting {
  const char* name;
  T SolverSettings::*own;
  T CollisionSettings::*collision;
};
template <class T>
constexpr Setting<T> own(const char* name, T SolverSettings::*m) { return {name, m, nullptr}; }
template <class T>
constexpr Setting<T> collision(const char* name, T CollisionSettings::*m) { return {name, nullptr, m}; }

// The field of s (SolverSettings, const or not) that a setting names.
template <class S, class T>
auto& field(S& s, const Setting<T>& f) { return f.own ? s.*f.own : s.collision.*f.collision; }

// Every SolverSettings field and CollisionSettings field, by type: one attribute each in the settings group
// (bools as 0/1 integers, vectors as 3 doubles); the enums are written by write_settings itself.
const Setting<real> kRealSettings[] = {
    own("fps", &SolverSettings::fps),
    own("velocity_damping", &SolverSettings::velocity_damping),
    collision("static_friction", &CollisionSettings::static_friction),
    collision("dynamic_friction", &CollisionSettings::dynamic_friction),
    collision("layer_shock", &CollisionSettings::layer_shock),
    collision("parallel_edge_degrees", &CollisionSettings::parallel_edge_degrees),
    collision("impact_zone_epsilon", &CollisionSettings::impact_zone_epsilon),
    own("tether_stretch", &SolverSettings::tether_stretch),
    collision("early_pass_fraction", &CollisionSettings::early_pass_fraction),
    collision("early_pass_excess", &CollisionSettings::early_pass_excess),
    collision("still_tolerance", &CollisionSettings::still_tolerance),
    own("chebyshev_rho", &SolverSettings::chebyshev_rho),
};
const Setting<int> kIntSettings[] = {
    own("frame_start", &SolverSettings::frame_start),
    own("frame_end", &SolverSettings::frame_end),
    own("substeps", &SolverSettings::substeps),
    own("iterations", &SolverSettings::iterations),
    own("collision_passes", &SolverSettings::collision_passes),
    own("smoothing_iterations", &SolverSettings::smoothing_iterations),
    collision("impact_zone_sweeps", &CollisionSettings::impact_zone_sweeps),
    collision("max_early_passes", &CollisionSettings::max_early_passes),
    collision("max_collider_early_passes", &CollisionSettings::max_collider_early_passes),
    own("chebyshev_delay", &SolverSettings::chebyshev_delay),
    own("stretch_limits", &SolverSettings::stretch_limits),
    own("coarse_levels", &SolverSettings::coarse_levels),
    own("coarse_iterations", &SolverSettings::coarse_iterations),
};
const Setting<bool> kBoolSettings[] = {
    collision("self_collision", &CollisionSettings::self_collision),
    collision("impact_zone_smoothing", &CollisionSettings::impact_zone_smoothing),
    collision("collision_failsafe", &CollisionSettings::collision_failsafe),
    collision("pair_refresh", &CollisionSettings::pair_refresh),
    collision("nearest_margins", &CollisionSettings::nearest_margins),
    collision("predicted_reference", &CollisionSettings::predicted_reference),
    collision("merge_contacts", &CollisionSettings::merge_contacts),
    own("profile", &SolverSettings::profile),
};
const Setting<Vec3> kVecSettings[] = {
    own("gravity", &SolverSettings::gravity),
    own("wind", &SolverSettings::wind),
};

const double* flat(const std::vector<Vec3>& v) { return v.empty() ? nullptr : &v[0].x; }

std::vector<Vec3> vec3s(const std::vector<double>& d) {
  std::vector<Vec3> v(d.size() / 3);
  for (size_t i = 0; i < v.size(); ++i) v[i] = {d[3 * i], d[3 * i + 1], d[3 * i + 2]};
  return v;
}

template <class T>
std::vector<T> flat(const std::vector<std::array<int, 3>>& v) {
  std::vector<T> d;
  d.reserve(3 * v.size());
  for (const auto& t : v) d.insert(d.end(), t.begin(), t.end());
  return d;
}

std::vector<std::array<int, 3>> triples(const std::vector<int>& d) {
  std::vector<std::array<int, 3>> v(d.size() / 3);
  for (size_t i = 0; i < v.size(); ++i) v[i] = {d[3 * i], d[3 * i + 1], d[3 * i + 2]};
  return v;
}

// Frames of an animation as one [frames x points x 3] dataset (every frame has the same point count: the
// scene was validated).
void write_animation(const h5::File& f, const std::string& name, const Animation& a) {
  const size_t nf = a.frames.size(), n = nf ? a.frames[0].size() : 0;
  std::vector<double> d;
  d.reserve(nf * n * 3);
  for (const auto& frame : a.frames)
    for (const Vec3& p : frame) d.insert(d.end(), {p.x, p.y, p.z});
  h5::write(f, name, d.data(), Dims{nf, n, 3});
}

Animation read_animation(const h5::File& f, const std::string& name) {
  Dims dims;
  const std::vector<double> d = h5::read<double>(f, name, {-1, -1, 3}, &dims);
  Animation a;
  a.frames.resize(dims[0]);
  for (size_t k = 0; k < dims[0]; ++k)
    a.frames[k] = vec3s(std::vector<double>(d.begin() + 3 * k * dims[1], d.begin() + 3 * (k + 1) * dims[1]));
  return a;
}

// One constraint kind as a table: a group with one dataset per column, rows = constraints.
template <class C>
struct TableOut {
  const h5::File& f;
  std::string group;
  const std::vector<C>& rows;

  template <class T, class Get>
  void column(const char* name, hsize_t width, Get get) const {
    std::vector<T> d(rows.size() * width);
    for (size_t i = 0; i < rows.size(); ++i)
      for (hsize_t k = 0; k < width; ++k) d[i * width + k] = get(rows[i], int(k));
    h5::write(f, group + "/" + name, d.data(), width == 1 ? Dims{rows.size()} : Dims{rows.size(), width});
  }
  void material(const XpbdMaterial C::*m) const {
    column<double>("compliance", 1, [&](const C& c, int) { return (c.*m).compliance; });
    column<double>("compress_compliance", 1, [&](const C& c, int) { return (c.*m).compress_compliance; });
    column<double>("damping_ratio", 1, [&](const C& c, int) { return (c.*m).damping_ratio; });
  }
};

template <class C>
struct TableIn {
  const h5::File& f;
  std::string group;
  std::vector<C>& rows;
  bool sized = false;

  // Column `name` into rows[i] through set(row, k, value); the first column read gives the row count.
  template <class T, class Set>
  void column(const char* name, long width, Set set) {
    Dims dims;
    const long n = sized ? long(rows.size()) : -1;
    const std::vector<long> shape = width == 1 ? std::vector<long>{n} : std::vector<long>{n, width};
    const std::vector<T> d = h5::read<T>(f, group + "/" + name, shape, &dims);
    if (!sized) rows.resize(dims[0]);
    sized = true;
    for (size_t i = 0; i < rows.size(); ++i)
      for (long k = 0; k < width; ++k) set(rows[i], int(k), d[i * width + k]);
  }
  void material(XpbdMaterial C::*m) {
    column<double>("compliance", 1, [&](C& c, int, double v) { (c.*m).compliance = v; });
    column<double>("compress_compliance", 1, [&](C& c, int, double v) { (c.*m).compress_compliance = v; });
    column<double>("damping_ratio", 1, [&](C& c, int, double v) { (c.*m).damping_ratio = v; });
  }
};

void write_constraints(const h5::File& f, const Constraints& c) {
  {
    const TableOut<DistanceConstraint> t{f, "/constraints/distance", c.distance};
    t.column<int>("points", 2, [](const DistanceConstraint& d, int k) { return k == 0 ? d.a : d.b; });
    t.column<double>("rest", 1, [](const DistanceConstraint& d, int) { return d.rest; });
    t.material(&DistanceConstraint::m);
  }
  {
    const TableOut<BendConstraint> t{f, "/constraints/bend", c.bend};
    t.column<int>("points", 4, [](const BendConstraint& b, int k) {
      return k == 0 ? b.o0 : k == 1 ? b.o1 : k == 2 ? b.e0 : b.e1;
    });
    t.column<double>("rest_angle", 1, [](const BendConstraint& b, int) { return b.rest_rad; });
    t.material(&BendConstraint::m);
  }
  {
    const TableOut<TriarapConstraint> t{f, "/constraints/triarap", c.triarap};
    t.column<int>("points", 3, [](const TriarapConstraint& r, int k) { return k == 0 ? r.p0 : k == 1 ? r.p1 : r.p2; });
    t.column<double>("dm_inv", 4, [](const TriarapConstraint& r, int k) { return r.dm_inv[k]; });
    t.column<double>("area", 1, [](const TriarapConstraint& r, int) { return r.area; });
    t.column<int>("normalized", 1, [](const TriarapConstraint& r, int) { return int(r.normalized); });
    t.material(&TriarapConstraint::m);
  }
  {
    const TableOut<PinConstraint> t{f, "/constraints/pin", c.pin};
    t.column<int>("point", 1, [](const PinConstraint& p, int) { return p.p; });
    t.column<double>("goal", 3, [](const PinConstraint& p, int k) { return p.goal[k]; });
    t.column<int>("target", 1, [](const PinConstraint& p, int) { return p.target; });
    t.column<double>("rest", 1, [](const PinConstraint& p, int) { return p.rest; });
    t.material(&PinConstraint::m);
  }
  {
    const TableOut<AttachConstraint> t{f, "/constraints/attach", c.attach};
    t.column<int>("point", 1, [](const AttachConstraint& a, int) { return a.p; });
    t.column<int>("collider", 1, [](const AttachConstraint& a, int) { return a.collider; });
    t.column<int>("triangle", 1, [](const AttachConstraint& a, int) { return a.tri; });
    t.column<double>("uv", 2, [](const AttachConstraint& a, int k) { return k == 0 ? a.u : a.v; });
    t.column<double>("rest", 1, [](const AttachConstraint& a, int) { return a.rest; });
    t.material(&AttachConstraint::m);
  }
  {
    const TableOut<PtPrimConstraint> t{f, "/constraints/ptprim", c.ptprim};
    t.column<int>("point", 1, [](const PtPrimConstraint& q, int) { return q.p; });
    t.column<int>("targets", 4, [](const PtPrimConstraint& q, int k) { return q.t[k]; });
    t.column<double>("weights", 4, [](const PtPrimConstraint& q, int k) { return q.w[k]; });
    t.column<int>("target_count", 1, [](const PtPrimConstraint& q, int) { return q.nt; });
    t.column<double>("rest", 1, [](const PtPrimConstraint& q, int) { return q.rest; });
    t.material(&PtPrimConstraint::m);
  }
  {
    const TableOut<FemConstraint> t{f, "/constraints/fem", c.fem};
    t.column<int>("points", 3, [](const FemConstraint& e, int k) { return k == 0 ? e.p0 : k == 1 ? e.p1 : e.p2; });
    t.column<double>("dm_inv", 4, [](const FemConstraint& e, int k) { return e.dm_inv[k]; });
    t.column<double>("area", 1, [](const FemConstraint& e, int) { return e.area; });
    t.column<double>("deviatoric_compliance", 1, [](const FemConstraint& e, int) { return e.dev_compliance; });
    t.column<double>("hydrostatic_compliance", 1, [](const FemConstraint& e, int) { return e.hyd_compliance; });
    t.column<double>("gamma", 1, [](const FemConstraint& e, int) { return e.gamma; });
    t.column<double>("damping_ratio", 1, [](const FemConstraint& e, int) { return e.damping_ratio; });
  }
}

Constraints read_constraints(const h5::File& f) {
  Constraints c;
  {
    TableIn<DistanceConstraint> t{f, "/constraints/distance", c.distance};
    t.column<int>("points", 2, [](DistanceConstraint& d, int k, int v) { (k == 0 ? d.a : d.b) = v; });
    t.column<double>("rest", 1, [](DistanceConstraint& d, int, double v) { d.rest = v; });
    t.material(&DistanceConstraint::m);
  }
  {
    TableIn<BendConstraint> t{f, "/constraints/bend", c.bend};
    t.column<int>("points", 4, [](BendConstraint& b, int k, int v) {
      (k == 0 ? b.o0 : k == 1 ? b.o1 : k == 2 ? b.e0 : b.e1) = v;
    });
    t.column<double>("rest_angle", 1, [](BendConstraint& b, int, double v) { b.rest_rad = v; });
    t.material(&BendConstraint::m);
  }
  {
    TableIn<TriarapConstraint> t{f, "/constraints/triarap", c.triarap};
    t.column<int>("points", 3, [](TriarapConstraint& r, int k, int v) { (k == 0 ? r.p0 : k == 1 ? r.p1 : r.p2) = v; });
    t.column<double>("dm_inv", 4, [](TriarapConstraint& r, int k, double v) { r.dm_inv[k] = v; });
    t.column<double>("area", 1, [](TriarapConstraint& r, int, double v) { r.area = v; });
    t.column<int>("normalized", 1, [](TriarapConstraint& r, int, int v) { r.normalized = v != 0; });
    t.material(&TriarapConstraint::m);
  }
  {
    TableIn<PinConstraint> t{f, "/constraints/pin", c.pin};
    t.column<int>("point", 1, [](PinConstraint& p, int, int v) { p.p = v; });
    t.column<double>("goal", 3, [](PinConstraint& p, int k, double v) { p.goal[k] = v; });
    t.column<int>("target", 1, [](PinConstraint& p, int, int v) { p.target = v; });
    t.column<double>("rest", 1, [](PinConstraint& p, int, double v) { p.rest = v; });
    t.material(&PinConstraint::m);
  }
  {
    TableIn<AttachConstraint> t{f, "/constraints/attach", c.attach};
    t.column<int>("point", 1, [](AttachConstraint& a, int, int v) { a.p = v; });
    t.column<int>("collider", 1, [](AttachConstraint& a, int, int v) { a.collider = v; });
    t.column<int>("triangle", 1, [](AttachConstraint& a, int, int v) { a.tri = v; });
    t.column<double>("uv", 2, [](AttachConstraint& a, int k, double v) { (k == 0 ? a.u : a.v) = v; });
    t.column<double>("rest", 1, [](AttachConstraint& a, int, double v) { a.rest = v; });
    t.material(&AttachConstraint::m);
  }
  {
    TableIn<PtPrimConstraint> t{f, "/constraints/ptprim", c.ptprim};
    t.column<int>("point", 1, [](PtPrimConstraint& q, int, int v) { q.p = v; });
    t.column<int>("targets", 4, [](PtPrimConstraint& q, int k, int v) { q.t[k] = v; });
    t.column<double>("weights", 4, [](PtPrimConstraint& q, int k, double v) { q.w[k] = v; });
    t.column<int>("target_count", 1, [](PtPrimConstraint& q, int, int v) { q.nt = v; });
    t.column<double>("rest", 1, [](PtPrimConstraint& q, int, double v) { q.rest = v; });
    t.material(&PtPrimConstraint::m);
  }
  {
    TableIn<FemConstraint> t{f, "/constraints/fem", c.fem};
    t.column<int>("points", 3, [](FemConstraint& e, int k, int v) { (k == 0 ? e.p0 : k == 1 ? e.p1 : e.p2) = v; });
    t.column<double>("dm_inv", 4, [](FemConstraint& e, int k, double v) { e.dm_inv[k] = v; });
    t.column<double>("area", 1, [](FemConstraint& e, int, double v) { e.area = v; });
    t.column<double>("deviatoric_compliance", 1, [](FemConstraint& e, int, double v) { e.dev_compliance = v; });
    t.column<double>("hydrostatic_compliance", 1, [](FemConstraint& e, int, double v) { e.hyd_compliance = v; });
    t.column<double>("gamma", 1, [](FemConstraint& e, int, double v) { e.gamma = v; });
    t.column<double>("damping_ratio", 1, [](FemConstraint& e, int, double v) { e.damping_ratio = v; });
  }
  return c;
}

void write_points(const h5::File& f, const ClothPoints& p) {
  const hsize_t n = p.size();
  h5::write(f, "/points/position", flat(p.position), {n, 3});
  h5::write(f, "/points/velocity", flat(p.velocity), {n, 3});
  h5::write(f, "/points/mass", p.mass.data(), {n});
  h5::write(f, "/points/thickness", p.thickness.data(), {n});
  h5::write(f, "/points/friction", p.friction.data(), {n});
  h5::write(f, "/points/dynamic_friction", p.dynamic_friction.data(), {n});
  h5::write(f, "/points/layer", p.layer.data(), {n});
  h5::write(f, "/points/stopped", p.stopped.data(), {n});
  h5::write(f, "/points/piece", p.piece.data(), {n});
}

ClothPoints read_points(const h5::File& f) {
  ClothPoints p;
  Dims dims;
  p.position = vec3s(h5::read<double>(f, "/points/position", {-1, 3}, &dims));
  const long n = long(dims[0]);
  p.velocity = vec3s(h5::read<double>(f, "/points/velocity", {n, 3}));
  p.mass = h5::read<double>(f, "/points/mass", {n});
  p.thickness = h5::read<double>(f, "/points/thickness", {n});
  p.friction = h5::read<double>(f, "/points/friction", {n});
  p.dynamic_friction = h5::read<double>(f, "/points/dynamic_friction", {n});
  p.layer = h5::read<int>(f, "/points/layer", {n});
  p.stopped = h5::read<int>(f, "/points/stopped", {n});
  p.piece = h5::read<int>(f, "/points/piece", {n});
  return p;
}

void write_colliders(const h5::File& f, const std::vector<Collider>& colliders) {
  h5::create_group(f, "/colliders");
  h5::write_attribute(f, "/colliders", "count", int(colliders.size()));
  for (size_t i = 0; i < colliders.size(); ++i) {
    const Collider& c = colliders[i];
    const std::string g = "/colliders/" + std::to_string(i);
    h5::write(f, g + "/triangles", flat<int>(c.triangles).data(), {c.triangles.size(), 3});
    write_animation(f, g + "/positions", c.motion);
    h5::write_attribute(f, g, "name", c.name);
    h5::write_attribute(f, g, "thickness", c.thickness);
    h5::write_attribute(f, g, "friction", c.friction);
  }
}

std::vector<Collider> read_colliders(const h5::File& f) {
  const int count = h5::read_attribute<int>(f, "/colliders", "count");
  if (count < 0) h5::fail(f, "/colliders", "negative count " + std::to_string(count));
  std::vector<Collider> colliders(count);
  for (int i = 0; i < count; ++i) {
    Collider& c = colliders[i];
    const std::string g = "/colliders/" + std::to_string(i);
    c.triangles = triples(h5::read<int>(f, g + "/triangles", {-1, 3}));
    c.motion = read_animation(f, g + "/positions");
    c.name = h5::read_string_attribute(f, g, "name");
    c.thickness = h5::read_attribute<double>(f, g, "thickness");
    c.friction = h5::read_attribute<double>(f, g, "friction");
  }
  return colliders;
}

}  // namespace

void write_settings(const h5::File& f, const std::string& group, const SolverSettings& s) {
  h5::create_group(f, group);
  for (const auto& m : kRealSettings) h5::write_attribute(f, group, m.name, field(s, m));
  for (const auto& m : kIntSettings) h5::write_attribute(f, group, m.name, field(s, m));
  for (const auto& m : kBoolSettings) h5::write_attribute(f, group, m.name, int(field(s, m)));
  for (const auto& m : kVecSettings) {
    const Vec3& v = field(s, m);
    h5::write_vector_attribute(f, group, m.name, {v.x, v.y, v.z});
  }
  h5::write_attribute(f, group, "contact_model", contact_model_name(s.collision.contact_model));
  // Two choices keep the 0/1 attributes they were first stored as (docs/formats.md).
  h5::write_attribute(f, group, "jacobi_contacts", int(s.collision.contact_solver == ContactSolver::Jacobi));
  h5::write_attribute(f, group, "ccd_per_pass", int(s.collision.ccd_span == CcdSpan::Pass));
}

SolverSettings read_settings(const h5::File& f, const std::string& group) {
  SolverSettings s;
  for (const auto& m : kRealSettings) {
    const char* name = m.name;
    // Absent in files written before tethers existed: none.
    if (std::strcmp(name, "tether_stretch") == 0 && !h5::has_attribute(f, group, name)) continue;
    // Absent in files written before proximity contacts: they ran the ccd model, which has none.
    if (std::strcmp(name, "early_pass_fraction") == 0 && !h5::has_attribute(f, group, name)) continue;
    // Absent in files written before it existed: every point cut back counted.
    if (std::strcmp(name, "early_pass_excess") == 0 && !h5::has_attribute(f, group, name)) { s.collision.early_pass_excess = 0; continue; }
    // Absent in files written before Chebyshev acceleration: they ran without it.
    if (std::strcmp(name, "chebyshev_rho") == 0 && !h5::has_attribute(f, group, name)) { s.chebyshev_rho = 0; continue; }
    // Absent in files written before still passes: every refresh measured its pairs.
    if (std::strcmp(name, "still_tolerance") == 0 && !h5::has_attribute(f, group, name)) { s.collision.still_tolerance = 0; continue; }
    field(s, m) = h5::read_attribute<double>(f, group, name);
  }
  for (const auto& m : kIntSettings) {
    const char* name = m.name;
    if (std::strcmp(name, "max_early_passes") == 0 && !h5::has_attribute(f, group, name)) continue;
    if (std::strcmp(name, "chebyshev_delay") == 0 && !h5::has_attribute(f, group, name)) continue;
    // Absent in files written before it existed: max_early_passes alone decided.
    if (std::strcmp(name, "max_collider_early_passes") == 0 && !h5::has_attribute(f, group, name)) {
      s.collision.max_collider_early_passes = 0;
      continue;
    }
    // Absent in files written before stretch limits: none.
    if (std::strcmp(name, "stretch_limits") == 0 && !h5::has_attribute(f, group, name)) continue;
    // Absent in files written before coarse levels: none.
    if ((std::strcmp(name, "coarse_levels") == 0 || std::strcmp(name, "coarse_iterations") == 0) &&
        !h5::has_attribute(f, group, name))
      continue;
    field(s, m) = h5::read_attribute<int>(f, group, name);
  }
  // Files written before the proximity model ran the paper's.
  s.collision.contact_model = ContactModel::Ccd;
  if (h5::has_attribute(f, group, "contact_model")) {
    const std::string m = h5::read_string_attribute(f, group, "contact_model");
    const auto model = parse_contact_model(m);
    if (!model) throw FormatError(f.path() + ": " + group + ": unknown contact_model '" + m + "' (proximity or ccd)");
    s.collision.contact_model = *model;
  }
  // Absent in files written before the Jacobi contact solver: Gauss-Seidel.
  if (h5::has_attribute(f, group, "jacobi_contacts") && h5::read_attribute<int>(f, group, "jacobi_contacts") != 0)
    s.collision.contact_solver = ContactSolver::Jacobi;
  // Absent in files written before the span existed, whose passes all tested the whole substep.
  s.collision.ccd_span = CcdSpan::Substep;
  if (h5::has_attribute(f, group, "ccd_per_pass") && h5::read_attribute<int>(f, group, "ccd_per_pass") != 0)
    s.collision.ccd_span = CcdSpan::Pass;
  for (const auto& m : kBoolSettings) {
    const char* name = m.name;
    // Added after the first files of this format version were written: absent means the default.
    const bool optional = std::strcmp(name, "collision_failsafe") == 0 || std::strcmp(name, "nearest_margins") == 0 ||
                          std::strcmp(name, "predicted_reference") == 0 || std::strcmp(name, "merge_contacts") == 0;
    // Absent in files written before it existed, whose passes all queried afresh.
    if (std::strcmp(name, "pair_refresh") == 0 && !h5::has_attribute(f, group, name)) {
      field(s, m) = false;
      continue;
    }
    if (optional && !h5::has_attribute(f, group, name)) continue;
    field(s, m) = h5::read_attribute<int>(f, group, name) != 0;
  }
  for (const auto& m : kVecSettings) {
    const std::vector<double> v = h5::read_vector_attribute(f, group, m.name, 3);
    field(s, m) = {v[0], v[1], v[2]};
  }
  return s;
}

std::vector<std::string> differing_settings(const SolverSettings& a, const SolverSettings& b) {
  const auto same = [](real x, real y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  std::vector<std::string> names;
  for (const auto& m : kRealSettings)
    if (!same(field(a, m), field(b, m))) names.push_back(m.name);
  for (const auto& m : kIntSettings)
    if (field(a, m) != field(b, m)) names.push_back(m.name);
  for (const auto& m : kBoolSettings)
    if (field(a, m) != field(b, m)) names.push_back(m.name);
  if (a.collision.contact_model != b.collision.contact_model) names.push_back("contact_model");
  if (a.collision.contact_solver != b.collision.contact_solver) names.push_back("contact_solver");
  if (a.collision.ccd_span != b.collision.ccd_span) names.push_back("ccd_span");
  for (const auto& m : kVecSettings) {
    const Vec3 &u = field(a, m), &v = field(b, m);
    if (!same(u.x, v.x) || !same(u.y, v.y) || !same(u.z, v.z)) names.push_back(m.name);
  }
  return names;
}

void write_scene(const Scene& s, const std::string& path) {
  validate_scene(s);
  h5::write_atomically(path, [&](const h5::File& f) {
    h5::write_attribute(f, "/", "weft_format", kSceneFormat);
    h5::write_attribute(f, "/", "format_version", kSceneFormatVersion);
    h5::write_attribute(f, "/", "name", s.name);
    h5::write_attribute(f, "/", "needs_collisions", int(s.needs_collisions));
    write_points(f, s.points);
    h5::write(f, "/triangles", flat<int>(s.triangles).data(), {s.triangles.size(), 3});
    write_constraints(f, s.constraints);
    write_animation(f, "/pin_targets", s.pin_targets);
    h5::write(f, "/kinematic/point", s.kinematic_point.data(), {s.kinematic_point.size()});
    h5::write(f, "/kinematic/target", s.kinematic_target.data(), {s.kinematic_target.size()});
    write_colliders(f, s.colliders);
    write_settings(f, "/settings", s.settings);
  });
}

Scene read_scene(const std::string& path) {
  const h5::File f = h5::File::open(path);
  h5::check_format(f, kSceneFormat, kSceneFormatVersion);
  Scene s;
  s.name = h5::read_string_attribute(f, "/", "name");
  s.needs_collisions = h5::read_attribute<int>(f, "/", "needs_collisions") != 0;
  s.points = read_points(f);
  s.triangles = triples(h5::read<int>(f, "/triangles", {-1, 3}));
  s.constraints = read_constraints(f);
  s.pin_targets = read_animation(f, "/pin_targets");
  Dims dims;
  s.kinematic_point = h5::read<int>(f, "/kinematic/point", {-1}, &dims);
  s.kinematic_target = h5::read<int>(f, "/kinematic/target", {long(dims[0])});
  s.colliders = read_colliders(f);
  s.settings = read_settings(f, "/settings");
  try {
    validate_scene(s);
  } catch (const InputError& e) {
    throw FormatError(path + ": " + e.what());
  }
  return s;
}

}  // namespace weft::io
