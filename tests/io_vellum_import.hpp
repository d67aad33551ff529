// Vellum import: Vellum-style assets written with weft's own .geo writer, every constraint kind and its rest
// data, unsupported types, Houdini-written files as simulation geometry, and each class of bad input.
#include "core/error.hpp"
#include "io/houdini_geo.hpp"
#include "io/obj.hpp"
#include "io/scene_file.hpp"
#include "io/vellum_import.hpp"
#include "tests/houdini_geometry_fixture.hpp"
#include "tests/io_checks_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace {

using weft::test::contains;
using weft::test::input_error;
using weft::test::cloth_sim;
using weft::test::ConstraintGeo;
using weft::test::ScratchDir;

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;

// The asset of most tests: one constraint of every kind, one skipped (stiffness 0) and one unsupported.
ConstraintGeo every_kind(const Geometry& sim) {
  ConstraintGeo c(sim);
  c.add("distance", {0, 1}, 1000, 0.5, {}, -1, 0.5)                                      // 0
      .add("stitch", {1, 2}, 2000, 0.25, {}, 500)                                        // 1
      .add("distance", {3, 4}, 0, 0.5)                                                   // 2: stiffness 0
      .add("bend", {1, 3, 0, 4}, 0.5, 30, {}, -1, 0.25)                                  // 3
      .add("triarap", {0, 1, 4}, 1e4, 0.125, {2, 0.5, 0, 2}, -1, 0, PrimKind::Polygon)   // 4
      .add("triarapnorm", {4, 5, 8}, 1e4, 0.25, {1, 0, 0, 1}, -1, 0, PrimKind::Polygon)  // 5
      .add("pin", {6}, 1e8, 0, {0, 2, 1, 0})                                             // 6
      .attach(7, "/obj/body/OUT", 1, 0.25, 0.5)                                          // 7
      .add("ptprim", {2, 4, 5}, 100, 0.125, {0.25, 0, 0, 0})                             // 8
      .add("ptprim", {8, 0, 1, 3}, 100, 0.125, {0.25, 0.5, 0, 0})                        // 9
      .add("ptprim", {4, 0, 1, 2, 3}, 100, 0, {0.5, 0.25, 0, 0})                         // 10
      .add("pressure", {0, 1, 2, 5, 8, 7, 6, 3}, 1, 2, {}, -1, 0, PrimKind::Polygon);    // 11
  return c;
}

// A two-triangle quad collider at y = 0 moving up 0.1 per frame, frames 1..3, as OBJ files.
std::string write_body(const ScratchDir& dir, int frames = 3) {
  for (int f = 1; f <= frames; ++f) {
    TriMesh m;
    const double y = 0.1 * (f - 1);
    m.positions = {{0, y, 0}, {1, y, 0}, {1, y, 1}, {0, y, 1}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}};
    char name[32];
    std::snprintf(name, sizeof name, "body.%04d.obj", f);
    write_obj(m, dir.file(name));
  }
  return dir.file("body.$F4.obj");
}

VellumImportOptions with_body(const ScratchDir& dir, bool skip = true) {
  VellumImportOptions opt;
  opt.colliders.push_back({"", write_body(dir)});
  opt.frames = std::array<int, 2>{1, 3};
  opt.skip_unsupported = skip;
  return opt;
}

TEST(WEFT_TEST_SUITE, io_vellum_compress_stiffness_zero_only_pulls) {
  ScratchDir dir("compress0");
  const Geometry sim = cloth_sim();
  write_geo(sim, dir.file("cloth.geo"));
  ConstraintGeo c(sim);
  c.add("distance", {0, 1}, 1000, 0.5, {}, 0).write(dir.file("constraints.geo"));
  const Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), with_body(dir));
  ASSERT_EQ(s.constraints.distance.size(), 1u);
  EXPECT_DOUBLE_EQ(s.constraints.distance[0].m.compliance, 1e-3);
  EXPECT_EQ(s.constraints.distance[0].m.compress_compliance, std::numeric_limits<real>::infinity());
}

TEST(WEFT_TEST_SUITE, io_vellum_imports_every_constraint_kind) {
  ScratchDir dir("kinds");
  const Geometry sim = cloth_sim();
  write_geo(sim, dir.file("cloth.geo"));
  every_kind(sim).write(dir.file("constraints.geo"));
  VellumImportReport rep;
  const Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), with_body(dir), &rep);
  const Constraints& c = s.constraints;

  ASSERT_EQ(c.distance.size(), 2u);
  EXPECT_EQ(c.distance[0].a, 0);
  EXPECT_EQ(c.distance[0].b, 1);
  EXPECT_EQ(c.distance[0].rest, 0.5);
  EXPECT_DOUBLE_EQ(c.distance[0].m.compliance, 1e-3);
  EXPECT_DOUBLE_EQ(c.distance[0].m.compress_compliance, 1e-3);  // compressstiffness -1: same as stiffness
  EXPECT_EQ(c.distance[0].m.damping_ratio, 0.5);
  EXPECT_EQ(c.distance[1].a, 1);
  EXPECT_EQ(c.distance[1].b, 2);  // stitch solves as distance
  EXPECT_EQ(c.distance[1].rest, 0.25);
  EXPECT_DOUBLE_EQ(c.distance[1].m.compliance, 1.0 / 2000);
  EXPECT_DOUBLE_EQ(c.distance[1].m.compress_compliance, 1.0 / 500);

  ASSERT_EQ(c.bend.size(), 1u);
  EXPECT_EQ(c.bend[0].o0, 1);
  EXPECT_EQ(c.bend[0].o1, 3);
  EXPECT_EQ(c.bend[0].e0, 0);
  EXPECT_EQ(c.bend[0].e1, 4);
  EXPECT_DOUBLE_EQ(c.bend[0].rest_rad, 30 * pi / 180);  // degrees in the file
  EXPECT_DOUBLE_EQ(c.bend[0].m.compliance, 2.0);
  EXPECT_EQ(c.bend[0].m.damping_ratio, 0.25);

  ASSERT_EQ(c.triarap.size(), 2u);
  const TriarapConstraint& t0 = c.triarap[0];
  EXPECT_EQ(t0.p0, 0);
  EXPECT_EQ(t0.p1, 1);
  EXPECT_EQ(t0.p2, 4);
  EXPECT_EQ(t0.dm_inv[0], 2);
  EXPECT_EQ(t0.dm_inv[1], 0.5);
  EXPECT_EQ(t0.dm_inv[2], 0);
  EXPECT_EQ(t0.dm_inv[3], 2);
  EXPECT_EQ(t0.area, 0.125);
  EXPECT_FALSE(t0.normalized);
  EXPECT_EQ(c.triarap[1].p0, 4);
  EXPECT_EQ(c.triarap[1].p2, 8);
  EXPECT_EQ(c.triarap[1].area, 0.25);
  EXPECT_TRUE(c.triarap[1].normalized);

  // The pin, and the pintoanimation point as a kinematic pin holding its position.
  ASSERT_EQ(c.pin.size(), 1u);
  EXPECT_EQ(c.pin[0].p, 6);
  EXPECT_TRUE(c.pin[0].goal == (Vec3{0, 2, 1}));
  EXPECT_EQ(c.pin[0].target, -1);
  EXPECT_DOUBLE_EQ(c.pin[0].m.compliance, 1e-8);
  ASSERT_EQ(s.kinematic_point, std::vector<int>{6});
  EXPECT_EQ(s.kinematic_target, std::vector<int>{0});
  ASSERT_EQ(s.pin_targets.frames.size(), 1u);
  EXPECT_TRUE(s.pin_targets.frames[0][0] == s.points.position[6]);

  ASSERT_EQ(c.attach.size(), 1u);
  EXPECT_EQ(c.attach[0].p, 7);
  EXPECT_EQ(c.attach[0].collider, 0);
  EXPECT_EQ(c.attach[0].tri, 1);  // an OBJ collider: target_prim is the triangle, (u, v) as given
  EXPECT_EQ(c.attach[0].u, 0.25);
  EXPECT_EQ(c.attach[0].v, 0.5);

  ASSERT_EQ(c.ptprim.size(), 3u);
  EXPECT_EQ(c.ptprim[0].p, 2);
  EXPECT_EQ(c.ptprim[0].nt, 2);
  EXPECT_EQ(c.ptprim[0].t[0], 4);
  EXPECT_EQ(c.ptprim[0].t[1], 5);
  EXPECT_EQ(c.ptprim[0].w[0], 0.75);
  EXPECT_EQ(c.ptprim[0].w[1], 0.25);
  EXPECT_EQ(c.ptprim[0].rest, 0.125);
  EXPECT_EQ(c.ptprim[1].nt, 3);
  EXPECT_EQ(c.ptprim[1].t[0], 0);
  EXPECT_EQ(c.ptprim[1].t[1], 1);
  EXPECT_EQ(c.ptprim[1].t[2], 3);
  EXPECT_EQ(c.ptprim[1].w[0], 0.25);
  EXPECT_EQ(c.ptprim[1].w[1], 0.25);
  EXPECT_EQ(c.ptprim[1].w[2], 0.5);
  EXPECT_EQ(c.ptprim[2].nt, 4);
  EXPECT_EQ(c.ptprim[2].w[0], 0.375);
  EXPECT_EQ(c.ptprim[2].w[1], 0.375);
  EXPECT_EQ(c.ptprim[2].w[2], 0.125);
  EXPECT_EQ(c.ptprim[2].w[3], 0.125);
  EXPECT_TRUE(c.fem.empty());

  EXPECT_EQ(rep.imported, (std::map<std::string, size_t>{{"attach", 1},
                                                         {"bend", 1},
                                                         {"distance", 1},
                                                         {"pin", 1},
                                                         {"ptprim", 3},
                                                         {"stitch", 1},
                                                         {"triarap", 1},
                                                         {"triarapnorm", 1}}));
  EXPECT_EQ(rep.skipped, (std::map<std::string, size_t>{{"distance", 1}}));
  EXPECT_EQ(rep.unsupported, (std::map<std::string, size_t>{{"pressure", 1}}));

  // The collider sequence, over the frame range.
  ASSERT_EQ(s.colliders.size(), 1u);
  EXPECT_EQ(s.colliders[0].name, "body");
  ASSERT_EQ(s.colliders[0].motion.frames.size(), 3u);
  EXPECT_DOUBLE_EQ(s.colliders[0].motion.frames[2][0].y, 0.2);
  EXPECT_TRUE(s.needs_collisions);
  EXPECT_EQ(s.settings.frame_start, 1);
  EXPECT_EQ(s.settings.frame_end, 3);
}

TEST(WEFT_TEST_SUITE, io_vellum_point_attributes_and_triangles) {
  ScratchDir dir("points");
  const Geometry sim = cloth_sim();
  write_geo(sim, dir.file("cloth.geo"));
  ConstraintGeo(sim).add("distance", {0, 1}, 1000, 0.5).write(dir.file("constraints.geo"));
  const Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {});
  const ClothPoints& p = s.points;
  ASSERT_EQ(p.size(), 9u);
  EXPECT_TRUE(p.position[4] == (Vec3{0.5, 1, 0.5}));
  EXPECT_EQ(p.mass[0], 0);  // infinite mass
  EXPECT_EQ(p.mass[4], 0.5);
  EXPECT_EQ(p.thickness[4], double(0.02f));  // pscale, stored as float32
  EXPECT_EQ(p.thickness[0], double(0.01f));
  EXPECT_EQ(p.stopped, (std::vector<int>{0, 0, 1, 0, 0, 0, 0, 0, 1}));  // bit 0 of `stopped`
  EXPECT_EQ(p.layer[4], 2);
  EXPECT_EQ(p.friction[4], 0.5);
  EXPECT_EQ(p.dynamic_friction[4], 0.25);
  EXPECT_TRUE(p.velocity[4] == (Vec3{0, -2, 0}));
  EXPECT_EQ(p.piece, std::vector<int>(9, 0));
  // Quads fanned and turned counter-clockwise: Houdini polygon (0, 1, 4, 3) gives (0, 4, 1) and (0, 3, 4).
  ASSERT_EQ(s.triangles.size(), 8u);
  EXPECT_EQ(s.triangles[0], (std::array<int, 3>{0, 4, 1}));
  EXPECT_EQ(s.triangles[1], (std::array<int, 3>{0, 3, 4}));
  EXPECT_EQ(s.name, dir.file("cloth.geo"));
  EXPECT_FALSE(s.needs_collisions);
}

TEST(WEFT_TEST_SUITE, io_vellum_refuses_unsupported_types_by_default) {
  ScratchDir dir("unsupported");
  const Geometry sim = cloth_sim();
  write_geo(sim, dir.file("cloth.geo"));
  every_kind(sim).add("stretchshear", {0, 1}, 10).add("stretchshear", {1, 2}, 10).write(dir.file("constraints.geo"));
  const std::string e =
      input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), with_body(dir, false)); });
  EXPECT_TRUE(contains(e, "pressure (1)")) << e;
  EXPECT_TRUE(contains(e, "stretchshear (2)")) << e;
  EXPECT_TRUE(contains(e, "--skip-unsupported")) << e;
  VellumImportReport rep;
  import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), with_body(dir, true), &rep);
  EXPECT_EQ(rep.unsupported, (std::map<std::string, size_t>{{"pressure", 1}, {"stretchshear", 2}}));
}

TEST(WEFT_TEST_SUITE, io_vellum_unsupported_point_features_are_reported) {
  ScratchDir dir("weld");
  Geometry sim = cloth_sim();
  sim.point_attributes["weld"] = int_attribute(1, {-1, -1, -1, -1, -1, -1, -1, 3, -1});
  write_geo(sim, dir.file("cloth.geo"));
  ConstraintGeo(sim).add("distance", {0, 1}, 1000, 0.5).write(dir.file("constraints.geo"));
  const std::string e = input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {}); });
  EXPECT_TRUE(contains(e, "point attribute weld (1)")) << e;
}

TEST(WEFT_TEST_SUITE, io_vellum_matches_points_by_id) {
  ScratchDir dir("ids");
  Geometry sim = cloth_sim();
  sim.point_attributes["id"] = int_attribute(1, {10, 11, 12, 13, 14, 15, 16, 17, 18});
  write_geo(sim, dir.file("cloth.geo"));
  // The constraint geometry lists the points in reverse: its point k is sim point 8 - k.
  ConstraintGeo c(sim);
  std::reverse(c.g.points.begin(), c.g.points.end());
  c.g.point_attributes["id"] = int_attribute(1, {18, 17, 16, 15, 14, 13, 12, 11, 10});
  c.add("distance", {0, 1}, 1000, 0.5).add("bend", {0, 2, 4, 6}, 1, 0).write(dir.file("constraints.geo"));
  const Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {});
  ASSERT_EQ(s.constraints.distance.size(), 1u);
  EXPECT_EQ(s.constraints.distance[0].a, 8);
  EXPECT_EQ(s.constraints.distance[0].b, 7);
  EXPECT_EQ(s.constraints.bend[0].o0, 8);
  EXPECT_EQ(s.constraints.bend[0].e1, 2);

  c.g.point_attributes["id"].ints[3] = 99;
  c.write(dir.file("constraints.geo"));
  const std::string e = input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {}); });
  EXPECT_TRUE(
      contains(e, dir.file("constraints.geo") + ": point 3 has id 99, which no point of " + dir.file("cloth.geo")))
      << e;
}

TEST(WEFT_TEST_SUITE, io_vellum_attach_to_geo_collider_and_fixed_goals) {
  ScratchDir dir("attach");
  const Geometry sim = cloth_sim();
  write_geo(sim, dir.file("cloth.geo"));
  // Collider: one Houdini triangle (points 0, 1, 2) and one quad.
  Geometry body;
  body.points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {2, 0, 0}, {2, 0, 1}};
  body.primitives.resize(2);
  body.primitives[0].points = {0, 1, 2};
  body.primitives[1].points = {1, 4, 5, 3};
  write_geo(body, dir.file("body.geo"));
  ConstraintGeo(sim)
      .attach(3, "/obj/body", 0, 0.25, 0.5)
      .attach(4, "/obj/body", -1, 0, 0, 3)
      .write(dir.file("constraints.geo"));
  VellumImportOptions opt;
  opt.colliders.push_back({"", dir.file("body.geo")});
  const Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), opt);
  ASSERT_EQ(s.constraints.attach.size(), 2u);
  // The goal is Houdini's primuv: (1-u-v) V0 + u V1 + v V2 over the primitive's vertices in file order.
  const auto goal = [&](const AttachConstraint& a) {
    const Collider& col = s.colliders[size_t(a.collider)];
    const auto& t = col.triangles[size_t(a.tri)];
    const auto& x = col.motion.frames[0];
    return (1 - a.u - a.v) * x[size_t(t[0])] + a.u * x[size_t(t[1])] + a.v * x[size_t(t[2])];
  };
  const Vec3 want = 0.25 * body.points[0] + 0.25 * body.points[1] + 0.5 * body.points[2];
  EXPECT_LT(norm(goal(s.constraints.attach[0]) - want), 1e-12);
  EXPECT_LT(norm(goal(s.constraints.attach[1]) - body.points[3]), 1e-12);  // target_pt

  // A quad target is refused; without a collider, attach constraints hold their points, and say so.
  ConstraintGeo(sim).attach(3, "/obj/body", 1, 0.25, 0.5).write(dir.file("quad.geo"));
  const std::string e = input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("quad.geo"), opt); });
  EXPECT_TRUE(contains(e, dir.file("quad.geo") + ": primitive 0 (attach): target_prim 1")) << e;
  EXPECT_TRUE(contains(e, "not a triangle")) << e;
  VellumImportReport rep;
  const Scene fixed = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {}, &rep);
  ASSERT_EQ(fixed.constraints.pin.size(), 2u);
  EXPECT_TRUE(fixed.constraints.pin[0].goal == sim.points[3]);
  ASSERT_FALSE(rep.notes.empty());
  EXPECT_TRUE(contains(rep.notes.back(), "attach constraints to '/obj/body': 2")) << rep.notes.back();

  // With two colliders, target_path chooses by name.
  write_geo(body, dir.file("other.geo"));
  opt.colliders.insert(opt.colliders.begin(), VellumCollider{"", dir.file("other.geo")});
  const Scene two = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), opt);
  EXPECT_EQ(two.constraints.attach[0].collider, 1);
  opt.colliders[1].name = "skin";
  const std::string none = input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), opt); });
  EXPECT_TRUE(contains(none, "target_path '/obj/body' names none of the colliders (other, skin)")) << none;
}

TEST(WEFT_TEST_SUITE, io_vellum_settings_from_detail_attributes) {
  ScratchDir dir("settings");
  Geometry sim = cloth_sim();
  sim.detail_attributes["substeps"] = int_attribute(1, {5});
  sim.detail_attributes["constraintiterations"] = int_attribute(1, {50});
  sim.detail_attributes["gravity"] = float_attribute(3, {0, -5, 0});
  sim.detail_attributes["frameend"] = int_attribute(1, {10});
  write_geo(sim, dir.file("cloth.geo"));
  ConstraintGeo c(sim);
  c.g.detail_attributes["substeps"] = int_attribute(1, {7});
  c.g.detail_attributes["smoothingiterations"] = int_attribute(1, {3});
  c.add("distance", {0, 1}, 1000, 0.5).write(dir.file("constraints.geo"));
  Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {});
  EXPECT_EQ(s.settings.substeps, 5);  // the simulation geometry's value wins
  EXPECT_EQ(s.settings.iterations, 50);
  EXPECT_EQ(s.settings.smoothing_iterations, 3);
  EXPECT_TRUE(s.settings.gravity == (Vec3{0, -5, 0}));
  EXPECT_EQ(s.settings.frame_end, 10);
  EXPECT_EQ(s.settings.collision_passes, SolverSettings{}.collision_passes);
  VellumImportOptions opt;
  opt.frames = std::array<int, 2>{2, 4};
  s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), opt);
  EXPECT_EQ(s.settings.frame_start, 2);
  EXPECT_EQ(s.settings.frame_end, 4);

  sim.detail_attributes["substeps"] = float_attribute(1, {2.5});
  write_geo(sim, dir.file("cloth.geo"));
  const std::string e = input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), {}); });
  EXPECT_TRUE(contains(e, dir.file("cloth.geo") + ": detail attribute 'substeps' = 2.5: expected an integer")) << e;
}

TEST(WEFT_TEST_SUITE, io_vellum_houdini_files_as_simulation_geometry) {
  if (weft::test::shared_dir().empty()) GTEST_SKIP() << "no shared/ folder";
  ScratchDir dir("houdini");
  struct Case {
    const char* file;
    size_t points, triangles;
  };
  // default: 12 triangles and 6 quads; box: 6 quads.
  for (const Case& k :
       {Case{"default.geo", 16, 24}, Case{"default.bgeo", 16, 24}, Case{"box.geo", 8, 12}, Case{"box.bgeo", 8, 12}}) {
    const std::string path = weft::test::shared_dir() + "/data/houdini/" + k.file;
    if (!fs::exists(path)) continue;
    Geometry cons;
    cons.points = read_geo(path).points;
    write_geo(cons, dir.file("constraints.geo"));
    VellumImportReport rep;
    const Scene s = import_vellum(path, dir.file("constraints.geo"), {}, &rep);
    EXPECT_EQ(s.points.size(), k.points) << k.file;
    EXPECT_EQ(s.triangles.size(), k.triangles) << k.file;
    EXPECT_EQ(s.constraints.size(), 0u) << k.file;
    for (real m : s.points.mass) EXPECT_GT(m, 0) << k.file;  // from the default density: every point is on a triangle
    bool noted = false;
    for (const std::string& n : rep.notes) noted = noted || contains(n, "no point attribute 'mass'");
    EXPECT_TRUE(noted) << k.file;
  }
}

// ---- bad input ---------------------------------------------------------------------------------------------

struct BadInput : ScratchDir {
  Geometry sim = cloth_sim();
  BadInput(const std::string& name) : ScratchDir(name) {
    write_geo(sim, file("cloth.geo"));
    ConstraintGeo(sim).add("distance", {0, 1}, 1000, 0.5).write(file("constraints.geo"));
  }
  std::string error(const VellumImportOptions& opt = {}) {
    return input_error([&] { import_vellum(file("cloth.geo"), file("constraints.geo"), opt); });
  }
};

TEST(WEFT_TEST_SUITE, io_vellum_bad_files) {
  BadInput b("files");
  std::string e = input_error([&] { import_vellum(b.file("missing.geo"), b.file("constraints.geo"), {}); });
  EXPECT_TRUE(contains(e, b.file("missing.geo"))) << e;

  std::ofstream(b.file("constraints.geo")) << "[\"fileversion\",\"20.5\",\"pointcount\",";
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("constraints.geo"))) << e;

  // A constraint vertex naming a point the file does not have.
  ConstraintGeo(b.sim).add("distance", {0, 8}, 1000, 0.5).write(b.file("constraints.geo"));
  std::string text = b.read("constraints.geo");
  const size_t at = text.find("[0,8]");
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, 5, "[0,9]");
  std::ofstream(b.file("constraints.geo"), std::ios::trunc) << text;
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("constraints.geo"))) << e;
  EXPECT_TRUE(contains(e, "refers to point 9")) << e;

  Geometry fewer = b.sim;
  fewer.points.pop_back();
  for (auto& [name, a] : fewer.point_attributes) {
    a.floats.resize(a.floats.empty() ? 0 : a.floats.size() - size_t(a.size));
    a.ints.resize(a.ints.empty() ? 0 : a.ints.size() - size_t(a.size));
  }
  ConstraintGeo(fewer).write(b.file("constraints.geo"));
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("cloth.geo") + " has 9 points")) << e;
  EXPECT_TRUE(contains(e, b.file("constraints.geo") + " has 8")) << e;
}

TEST(WEFT_TEST_SUITE, io_vellum_bad_geometry) {
  BadInput b("geometry");
  // NaN cannot be written as JSON text: patch it into a binary file, replacing point 4's x (0.5 is shared, so
  // give it a unique value first).
  Geometry sim = b.sim;
  sim.points[4].x = 0.625;
  write_bgeo(sim, b.file("cloth.geo"));
  std::string bytes = b.read("cloth.geo");
  const float unique = 0.625f, nan = std::nanf("");
  const std::string from(reinterpret_cast<const char*>(&unique), 4), to(reinterpret_cast<const char*>(&nan), 4);
  const size_t at = bytes.find(from);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(from, at + 1), std::string::npos);
  bytes.replace(at, 4, to);
  std::ofstream(b.file("cloth.geo"), std::ios::binary | std::ios::trunc) << bytes;
  std::string e = b.error();
  EXPECT_TRUE(contains(e, b.file("cloth.geo") + ": point 4 has a non-finite position")) << e;

  // Zero-area triangle: a sixth primitive on three points of one row.
  sim = b.sim;
  sim.primitives.emplace_back();
  sim.primitives.back().points = {0, 1, 2};
  write_geo(sim, b.file("cloth.geo"));
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("cloth.geo") + ": primitive 4 (points 0, 1, 2) has zero area")) << e;

  // Packed geometry.
  sim = b.sim;
  sim.primitive_attributes["vellum_type"] = string_attribute(1, {"geometry", "geometry", "geometry", "geometry"});
  write_geo(sim, b.file("cloth.geo"));
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("cloth.geo") + ": packed Vellum geometry")) << e;
  EXPECT_TRUE(contains(e, "unpack")) << e;
}

TEST(WEFT_TEST_SUITE, io_vellum_bad_constraints) {
  BadInput b("constraints");
  ConstraintGeo(b.sim).add("distance", {0, 1, 2}, 1000, 0.5).write(b.file("constraints.geo"));
  std::string e = b.error();
  EXPECT_TRUE(contains(e, b.file("constraints.geo") + ": primitive 0 (distance): has 3 points, expected 2")) << e;

  ConstraintGeo(b.sim).add("distance", {0, 1}, 1000).add("bend", {0, 1, 3, 4}, -1).write(b.file("constraints.geo"));
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("constraints.geo") + ": primitive 1 (bend): stiffness -1 is negative")) << e;

  ConstraintGeo(b.sim).add("triarap", {0, 1, 4}, 1000, 0, {2, 0, 0, 2}).write(b.file("constraints.geo"));
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("constraints.geo") + ": primitive 0 (triarap): has zero rest area")) << e;

  ConstraintGeo(b.sim).attach(3, "/obj/body", 5, 0, 0).write(b.file("constraints.geo"));
  e = b.error(with_body(b));
  EXPECT_TRUE(contains(e, "primitive 0 (attach): target_prim 5 is out of range: collider 'body' has 2 triangles")) << e;

  ConstraintGeo c(b.sim);
  c.add("distance", {0, 1}, 1000);
  c.write(b.file("constraints.geo"));
  Geometry g = read_geo(b.file("constraints.geo"));
  g.primitive_attributes.erase("type");
  write_geo(g, b.file("constraints.geo"));
  e = b.error();
  EXPECT_TRUE(contains(e, b.file("constraints.geo") + ": no primitive attribute 'type'")) << e;
}

// --pin-target: pintoanimation points follow the animated cloth exactly, pin constraints are pulled to it.
TEST(WEFT_TEST_SUITE, io_vellum_pins_follow_the_pin_target_animation) {
  ScratchDir dir("pin_target");
  const Geometry sim = cloth_sim();  // point 6 has pintoanimation
  write_geo(sim, dir.file("cloth.geo"));
  ConstraintGeo(sim).add("pin", {2}, 1e4).write(dir.file("constraints.geo"));
  for (int f = 1; f <= 3; ++f) {
    Geometry moved = sim;
    for (Vec3& p : moved.points) p = p + Vec3{0.1 * (f - 1), 0, 0};
    char name[32];
    std::snprintf(name, sizeof name, "anim.%04d.geo", f);
    write_geo(moved, dir.file(name));
  }
  VellumImportOptions opt;
  opt.frames = std::array<int, 2>{1, 3};
  opt.pin_target = dir.file("anim.$F4.geo");
  VellumImportReport rep;
  const Scene s = import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), opt, &rep);
  ASSERT_EQ(s.kinematic_point, std::vector<int>{6});
  ASSERT_EQ(s.constraints.pin.size(), 1u);
  ASSERT_EQ(s.pin_targets.frames.size(), 3u);
  const int k = s.kinematic_target[0], pk = s.constraints.pin[0].target;
  ASSERT_GE(pk, 0);
  for (int f = 0; f < 3; ++f) {
    // (.geo stores 32-bit floats)
    EXPECT_LT(norm(s.pin_targets.frames[size_t(f)][size_t(k)] - (sim.points[6] + Vec3{0.1 * f, 0, 0})), 1e-6) << f;
    EXPECT_LT(norm(s.pin_targets.frames[size_t(f)][size_t(pk)] - (sim.points[2] + Vec3{0.1 * f, 0, 0})), 1e-6) << f;
  }
  EXPECT_TRUE(contains(rep.notes.back(), "1 pintoanimation points exactly, 1 pin constraints")) << rep.notes.back();
  // A target with other points is refused, naming both files.
  Geometry fewer = sim;
  fewer.points.pop_back();
  fewer.primitives.pop_back();
  for (auto& [name, a] : fewer.point_attributes) {
    if (!a.floats.empty()) a.floats.resize(a.floats.size() - size_t(a.size));
    if (!a.ints.empty()) a.ints.resize(a.ints.size() - size_t(a.size));
  }
  write_geo(fewer, dir.file("fewer.geo"));
  opt.pin_target = dir.file("fewer.geo");
  const std::string e = input_error([&] { import_vellum(dir.file("cloth.geo"), dir.file("constraints.geo"), opt); });
  EXPECT_TRUE(contains(e, dir.file("fewer.geo") + ": the pin target has 8 points, the simulation geometry " +
                              dir.file("cloth.geo") + " 9")) << e;
}

TEST(WEFT_TEST_SUITE, io_vellum_collider_frames) {
  BadInput b("collider");
  write_body(b);
  // Frame 2 gains a triangle.
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}};
  write_obj(m, b.file("body.0002.obj"));
  VellumImportOptions opt;
  opt.colliders.push_back({"", b.file("body.$F4.obj")});
  opt.frames = std::array<int, 2>{1, 3};
  std::string e = b.error(opt);
  EXPECT_TRUE(contains(e, b.file("body.0002.obj") + ": the collider's topology changes at frame 2")) << e;

  fs::remove(b.file("body.0002.obj"));
  e = b.error(opt);
  EXPECT_TRUE(contains(e, b.file("body.0002.obj"))) << e;

  EXPECT_EQ(collider_name_from_pattern("anim/body.$F4.geo"), "body");
  EXPECT_EQ(collider_name_from_pattern("skin_$F.obj"), "skin");
  EXPECT_EQ(collider_name_from_pattern("/a/b/rock.bgeo"), "rock");
  const Collider still = read_collider("rock", b.file("body.0001.obj"), 1, 10);  // no $F: one static frame
  EXPECT_EQ(still.motion.frames.size(), 1u);
}

}  // namespace
