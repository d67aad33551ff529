// HDF5 scene files: an exact round trip of everything a Scene holds, and errors that name the file and the
// dataset.
#include "constraints/vellum_cloth.hpp"
#include "io/builtin_scenes.hpp"
#include "io/hdf5_util.hpp"
#include "io/procedural.hpp"
#include "io/scene_file.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::ScratchDir;

// The skirt (kinematic pins following animated targets, an animated collider) plus a piece of every other
// constraint kind, a second collider and non-default settings.
Scene every_kind_scene() {
  Scene s = make_builtin_scene("skirt", {3});
  for (StretchModel model : {StretchModel::Triarap, StretchModel::TriarapNorm, StretchModel::Fem}) {
    ClothMaterial mat;
    mat.stretch = model;
    mat.layer = 7;
    const Mesh g = grid(2, 2, {2.0 + int(model), 1.0, 0.0}, {0.3, 0, 0}, {0, 0, 0.3});
    add_cloth_piece(s, g.x, g.tris, mat);
  }
  const real third = 1.0 / 3.0;
  s.constraints.pin.push_back({0, {0.1, third, -0.3}, -1, 0, xpbd_material(100, -1, 0.01)});
  s.constraints.pin.push_back({1, {}, 2, 1e-3, xpbd_material(50, 10, 0)});
  s.constraints.attach.push_back({2, 0, 5, 0.25, third, 0.0, xpbd_material(1e3, -1, 0.1)});
  s.constraints.ptprim.push_back({3, {4, 5, 6, -1}, {0.2, 0.3, 0.5, 0}, 3, 0.01, xpbd_material(1e4, 1e3, 0)});
  Collider ground;
  ground.name = "ground plane";
  const Mesh plane = grid(1, 1, {-2, 0, -2}, {0, 0, 4}, {4, 0, 0});
  ground.triangles = plane.tris;
  ground.motion.frames = {plane.x};
  ground.thickness = 1e-3;
  ground.friction = third;
  s.colliders.push_back(ground);
  for (size_t i = 0; i < s.points.size(); ++i) s.points.velocity[i] = {real(i) / 7, -third, 1e-300};
  s.points.friction[1] = 0.1;
  s.points.stopped[2] = 1;
  SolverSettings& st = s.settings;
  st.fps = 30;
  st.frame_start = -3;
  st.substeps = 7;
  st.smoothing_iterations = 2;
  st.gravity = {0.1, -third, 0};
  st.wind = {1e-17, 0, -2};
  st.velocity_damping = 0.5;
  st.collision.self_collision = false;
  st.collision.static_friction = third;
  st.collision.dynamic_friction = 0.25;
  st.collision.layer_shock = 2;
  st.collision.parallel_edge_degrees = 5;
  st.collision.impact_zone_smoothing = false;
  st.collision.impact_zone_epsilon = 0.2;
  st.collision.impact_zone_sweeps = 3;
  st.collision.nearest_margins = true;
  st.collision.merge_contacts = false;
  st.collision.predicted_reference = true;
  st.collision.contact_solver = ContactSolver::Jacobi;
  st.collision.ccd_span = CollisionSettings{}.ccd_span == CcdSpan::Pass ? CcdSpan::Substep : CcdSpan::Pass;
  st.tether_stretch = 1.25;
  st.stretch_limits = 2;
  st.coarse_levels = 5;
  st.coarse_iterations = 3;
  st.profile = true;
  return s;
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(Vec3 a, Vec3 b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }
bool same(const XpbdMaterial& a, const XpbdMaterial& b) {
  return same(a.compliance, b.compliance) && same(a.compress_compliance, b.compress_compliance) &&
         same(a.damping_ratio, b.damping_ratio);
}
template <size_t N>
bool same(const real (&a)[N], const real (&b)[N]) {
  return std::memcmp(a, b, sizeof a) == 0;
}
bool same(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}
bool same(const std::vector<real>& a, const std::vector<real>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(real)) == 0;
}
bool same(const Animation& a, const Animation& b) {
  if (a.frames.size() != b.frames.size()) return false;
  for (size_t f = 0; f < a.frames.size(); ++f)
    if (!same(a.frames[f], b.frames[f])) return false;
  return true;
}

// Every field of every part, compared bit for bit.
void expect_identical(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.needs_collisions, b.needs_collisions);
  const ClothPoints &p = a.points, &q = b.points;
  EXPECT_TRUE(same(p.position, q.position));
  EXPECT_TRUE(same(p.velocity, q.velocity));
  EXPECT_TRUE(same(p.mass, q.mass));
  EXPECT_TRUE(same(p.thickness, q.thickness));
  EXPECT_TRUE(same(p.friction, q.friction));
  EXPECT_TRUE(same(p.dynamic_friction, q.dynamic_friction));
  EXPECT_EQ(p.layer, q.layer);
  EXPECT_EQ(p.stopped, q.stopped);
  EXPECT_EQ(p.piece, q.piece);
  EXPECT_EQ(a.triangles, b.triangles);
  const Constraints &c = a.constraints, &d = b.constraints;
  ASSERT_EQ(c.distance.size(), d.distance.size());
  for (size_t i = 0; i < c.distance.size(); ++i) {
    const auto &x = c.distance[i], &y = d.distance[i];
    EXPECT_TRUE(x.a == y.a && x.b == y.b && same(x.rest, y.rest) && same(x.m, y.m)) << "distance " << i;
  }
  ASSERT_EQ(c.bend.size(), d.bend.size());
  for (size_t i = 0; i < c.bend.size(); ++i) {
    const auto &x = c.bend[i], &y = d.bend[i];
    EXPECT_TRUE(x.o0 == y.o0 && x.o1 == y.o1 && x.e0 == y.e0 && x.e1 == y.e1 && same(x.rest_rad, y.rest_rad) &&
                same(x.m, y.m)) << "bend " << i;
  }
  ASSERT_EQ(c.triarap.size(), d.triarap.size());
  for (size_t i = 0; i < c.triarap.size(); ++i) {
    const auto &x = c.triarap[i], &y = d.triarap[i];
    EXPECT_TRUE(x.p0 == y.p0 && x.p1 == y.p1 && x.p2 == y.p2 && same(x.dm_inv, y.dm_inv) && same(x.area, y.area) &&
                x.normalized == y.normalized && same(x.m, y.m)) << "triarap " << i;
  }
  ASSERT_EQ(c.pin.size(), d.pin.size());
  for (size_t i = 0; i < c.pin.size(); ++i) {
    const auto &x = c.pin[i], &y = d.pin[i];
    EXPECT_TRUE(x.p == y.p && same(x.goal, y.goal) && x.target == y.target && same(x.rest, y.rest) && same(x.m, y.m))
        << "pin " << i;
  }
  ASSERT_EQ(c.attach.size(), d.attach.size());
  for (size_t i = 0; i < c.attach.size(); ++i) {
    const auto &x = c.attach[i], &y = d.attach[i];
    EXPECT_TRUE(x.p == y.p && x.collider == y.collider && x.tri == y.tri && same(x.u, y.u) && same(x.v, y.v) &&
                same(x.rest, y.rest) && same(x.m, y.m)) << "attach " << i;
  }
  ASSERT_EQ(c.ptprim.size(), d.ptprim.size());
  for (size_t i = 0; i < c.ptprim.size(); ++i) {
    const auto &x = c.ptprim[i], &y = d.ptprim[i];
    EXPECT_TRUE(x.p == y.p && std::memcmp(x.t, y.t, sizeof x.t) == 0 && same(x.w, y.w) && x.nt == y.nt &&
                same(x.rest, y.rest) && same(x.m, y.m)) << "ptprim " << i;
  }
  ASSERT_EQ(c.fem.size(), d.fem.size());
  for (size_t i = 0; i < c.fem.size(); ++i) {
    const auto &x = c.fem[i], &y = d.fem[i];
    EXPECT_TRUE(x.p0 == y.p0 && x.p1 == y.p1 && x.p2 == y.p2 && same(x.dm_inv, y.dm_inv) && same(x.area, y.area) &&
                same(x.dev_compliance, y.dev_compliance) && same(x.hyd_compliance, y.hyd_compliance) &&
                same(x.gamma, y.gamma) && same(x.damping_ratio, y.damping_ratio)) << "fem " << i;
  }
  EXPECT_TRUE(same(a.pin_targets, b.pin_targets));
  EXPECT_EQ(a.kinematic_point, b.kinematic_point);
  EXPECT_EQ(a.kinematic_target, b.kinematic_target);
  ASSERT_EQ(a.colliders.size(), b.colliders.size());
  for (size_t i = 0; i < a.colliders.size(); ++i) {
    const Collider &x = a.colliders[i], &y = b.colliders[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.triangles, y.triangles);
    EXPECT_TRUE(same(x.motion, y.motion)) << "collider " << i;
    EXPECT_TRUE(same(x.thickness, y.thickness) && same(x.friction, y.friction)) << "collider " << i;
  }
  const SolverSettings &s = a.settings, &t = b.settings;
  const CollisionSettings &sc = s.collision, &tc = t.collision;
  EXPECT_TRUE(same(s.fps, t.fps) && same(s.gravity, t.gravity) && same(s.wind, t.wind) &&
              same(s.velocity_damping, t.velocity_damping) && same(sc.static_friction, tc.static_friction) &&
              same(sc.dynamic_friction, tc.dynamic_friction) && same(sc.layer_shock, tc.layer_shock) &&
              same(sc.parallel_edge_degrees, tc.parallel_edge_degrees) &&
              same(sc.impact_zone_epsilon, tc.impact_zone_epsilon) && same(s.tether_stretch, t.tether_stretch));
  EXPECT_TRUE(s.frame_start == t.frame_start && s.frame_end == t.frame_end && s.substeps == t.substeps &&
              s.iterations == t.iterations && s.collision_passes == t.collision_passes &&
              s.smoothing_iterations == t.smoothing_iterations && sc.impact_zone_sweeps == tc.impact_zone_sweeps &&
              sc.self_collision == tc.self_collision && sc.impact_zone_smoothing == tc.impact_zone_smoothing &&
              sc.contact_solver == tc.contact_solver && sc.ccd_span == tc.ccd_span && s.profile == t.profile &&
              s.stretch_limits == t.stretch_limits && s.coarse_levels == t.coarse_levels &&
              s.coarse_iterations == t.coarse_iterations);
  EXPECT_TRUE(differing_settings(s, t).empty());
}

std::string read_error(const std::string& path) {
  try {
    read_scene(path);
  } catch (const FormatError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FormatError reading " << path;
  return "";
}

// Opens a written scene file to damage it.
struct Edit {
  h5::Handle file;
  explicit Edit(const std::string& path) : file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose) {
    EXPECT_TRUE(file.valid());
  }
};

TEST(WEFT_TEST_SUITE, hdf5_scene_round_trip_is_exact) {
  const ScratchDir dir("round_trip");
  const Scene s = every_kind_scene();
  const Constraints& c = s.constraints;
  ASSERT_TRUE(!c.distance.empty() && !c.bend.empty() && !c.triarap.empty() && !c.pin.empty() && !c.attach.empty() &&
              !c.ptprim.empty() && !c.fem.empty());
  ASSERT_TRUE(!s.pin_targets.empty() && !s.kinematic_point.empty() && s.colliders[0].motion.frames.size() > 1);
  const std::string path = dir.file("scene.h5");
  write_scene(s, path);
  expect_identical(s, read_scene(path));
  EXPECT_EQ(dir.entries().size(), 1u);  // no temporary file left behind
}

TEST(WEFT_TEST_SUITE, hdf5_scene_round_trip_of_an_empty_animation_and_no_colliders) {
  const ScratchDir dir("plain");
  const Scene s = make_builtin_scene("hanging-sheet", {3});
  ASSERT_TRUE(s.pin_targets.empty() && s.colliders.empty());
  write_scene(s, dir.file("sheet.h5"));
  expect_identical(s, read_scene(dir.file("sheet.h5")));
}

// --contact-solver and --ccd-span are stored as the 0/1 attributes jacobi_contacts and ccd_per_pass; files
// written before either existed lack them and read as Gauss-Seidel contacts over the whole substep.
TEST(WEFT_TEST_SUITE, hdf5_scene_contact_solver_and_ccd_span_attributes) {
  const ScratchDir dir("solver_span");
  Scene s = make_builtin_scene("hanging-sheet", {3});
  s.settings.collision.contact_solver = ContactSolver::Jacobi;
  s.settings.collision.ccd_span = CcdSpan::Pass;
  const std::string path = dir.file("sheet.h5");
  write_scene(s, path);
  {
    const h5::File f = h5::File::open(path);
    EXPECT_EQ(h5::read_attribute<int>(f, "/settings", "jacobi_contacts"), 1);
    EXPECT_EQ(h5::read_attribute<int>(f, "/settings", "ccd_per_pass"), 1);
  }
  {
    const Edit edit(path);
    ASSERT_GE(H5Adelete_by_name(edit.file.get(), "/settings", "jacobi_contacts", H5P_DEFAULT), 0);
    ASSERT_GE(H5Adelete_by_name(edit.file.get(), "/settings", "ccd_per_pass", H5P_DEFAULT), 0);
  }
  const SolverSettings older = read_scene(path).settings;
  EXPECT_EQ(older.collision.contact_solver, ContactSolver::GaussSeidel);
  EXPECT_EQ(older.collision.ccd_span, CcdSpan::Substep);
}

TEST(WEFT_TEST_SUITE, hdf5_scene_errors_name_the_file_and_the_dataset) {
  const ScratchDir dir("errors");
  const Scene s = every_kind_scene();

  const std::string text = dir.file("text.h5");
  std::ofstream(text) << "not HDF5\n";
  std::string e = read_error(text);
  EXPECT_NE(e.find(text), std::string::npos) << e;
  EXPECT_NE(e.find("not an HDF5 file"), std::string::npos) << e;

  e = read_error(dir.file("absent.h5"));
  EXPECT_NE(e.find(dir.file("absent.h5") + ": no such file"), std::string::npos) << e;

  const std::string version = dir.file("version.h5");
  write_scene(s, version);
  {
    const Edit edit(version);
    const h5::Handle a(H5Aopen(edit.file.get(), "format_version", H5P_DEFAULT), H5Aclose);
    const int two = 2;
    ASSERT_GE(H5Awrite(a.get(), H5T_NATIVE_INT, &two), 0);
  }
  e = read_error(version);
  EXPECT_NE(e.find(version + ": format_version is 2"), std::string::npos) << e;

  const std::string missing = dir.file("missing.h5");
  write_scene(s, missing);
  ASSERT_GE(H5Ldelete(Edit(missing).file.get(), "/points/mass", H5P_DEFAULT), 0);
  e = read_error(missing);
  EXPECT_NE(e.find(missing + ": /points/mass: missing dataset"), std::string::npos) << e;

  const std::string shape = dir.file("shape.h5");
  write_scene(s, shape);
  {
    const Edit edit(shape);
    ASSERT_GE(H5Ldelete(edit.file.get(), "/constraints/bend/rest_angle", H5P_DEFAULT), 0);
  }
  {
    const Edit edit(shape);
    const hsize_t n = 3;
    const h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    const h5::Handle d(H5Dcreate2(edit.file.get(), "/constraints/bend/rest_angle", H5T_IEEE_F64LE, space.get(),
                                  H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       H5Dclose);
    ASSERT_TRUE(d.valid());
  }
  e = read_error(shape);
  EXPECT_NE(e.find(shape + ": /constraints/bend/rest_angle: has shape [3], expected [" +
                   std::to_string(s.constraints.bend.size()) + "]"),
            std::string::npos)
      << e;

  const std::string invalid = dir.file("invalid.h5");
  write_scene(s, invalid);
  {
    const Edit edit(invalid);
    const h5::Handle d(H5Dopen2(edit.file.get(), "/triangles", H5P_DEFAULT), H5Dclose);
    std::vector<int> tris(3 * s.triangles.size());
    ASSERT_GE(H5Dread(d.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, tris.data()), 0);
    tris[4] = int(s.points.size());
    ASSERT_GE(H5Dwrite(d.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, tris.data()), 0);
  }
  e = read_error(invalid);
  EXPECT_NE(e.find(invalid + ": " + s.name + ": triangle 1 refers to point"), std::string::npos) << e;
}

TEST(WEFT_TEST_SUITE, hdf5_scene_write_failures_leave_nothing) {
  const ScratchDir dir("write_failures");
  Scene s = make_builtin_scene("hanging-sheet", {3});
  std::ofstream(dir.file("plain-file")) << "x";
  EXPECT_THROW(write_scene(s, dir.file("plain-file") + "/scene.h5"), std::runtime_error);
  s.points.mass[2] = -1;
  EXPECT_THROW(write_scene(s, dir.file("invalid.h5")), InputError);
  EXPECT_EQ(dir.entries().size(), 1u);
}

TEST(WEFT_TEST_SUITE, hdf5_scene_reader_rejects_other_weft_files) {
  const ScratchDir dir("kind");
  const std::string path = dir.file("other.h5");
  h5::write_atomically(path, [](const h5::File& f) {
    h5::write_attribute(f, "/", "weft_format", "weft-cache");
    h5::write_attribute(f, "/", "format_version", 1);
  });
  const std::string e = read_error(path);
  EXPECT_NE(e.find(path + ": not a weft-scene file (weft_format is 'weft-cache')"), std::string::npos) << e;
}

}  // namespace
