// JSON scenes: a scene with an OBJ cloth, a generated cloth, pins of each kind and colliders of each source
// gives the Scene built by hand; every class of error names the file and the JSON path; load_scene dispatch.
#include "constraints/vellum_cloth.hpp"
#include "core/error.hpp"
#include "io/json_scene.hpp"
#include "io/obj.hpp"
#include "io/procedural.hpp"
#include "io/scene_file.hpp"
#include "io/scene_source.hpp"
#include "tests/io_checks_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace {

using weft::test::contains;
using weft::test::input_error;
using weft::test::ScratchDir;

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;

const char* kFlagObj = "v 0 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4\n";

// body.0001.obj .. body.0003.obj: a quad rising 0.1 m per frame.
void write_body(const ScratchDir& dir) {
  for (int f = 1; f <= 3; ++f) {
    TriMesh m;
    const double y = 0.1 * (f - 1);
    m.positions = {{0, y, 0}, {1, y, 0}, {1, y, 1}, {0, y, 1}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}};
    write_obj(m, dir.file("body.000" + std::to_string(f) + ".obj"));
  }
}

const char* kScene = R"({
  "settings": {"fps": 30, "frames": [1, 3], "substeps": 4, "iterations": 15, "collision_passes": 3,
               "smoothing": 2, "gravity": [0, -10, 0], "wind": [1, 0, 0], "damping": 0.5,
               "impact_zone_smoothing": false, "contact_solver": "jacobi", "ccd_span": "substep",
               "tethers": 1.1, "stretch_limits": 1, "coarse_levels": 3, "coarse_iterations": 2, "contact_model": "ccd", "early_pass_fraction": 0.05, "early_pass_excess": 2, "max_early_passes": 2, "max_collider_early_passes": 0,
               "pair_refresh": false, "merge_contacts": false, "nearest_margins": true, "predicted_reference": true, "layer_shock": 10,
               "still_tolerance": 0.3},
  "cloth": [
    {"obj": "flag.obj", "material": {"density": 0.2, "thickness": 0.003}, "pins": [{"points": [0, 3]}]},
    {"generator": "grid", "res": [4, 2], "origin": [0, 2, 0], "u": [1, 0, 0], "v": [0, 0, 0.5],
     "material": {"stretch": "triarapnorm", "stretch_stiffness": 1e4, "compress_stiffness": 100,
                  "stretch_damping": 0.01, "bend_stiffness": 0, "layer": 1, "friction": 0.5},
     "groups": {"corner": [14]},
     "pins": [{"group": "corner", "stiffness": 1000, "damping": 0.1},
              {"box": {"min": [-1, 1.9, -1], "max": [0.1, 2.1, 1]}}]}
  ],
  "colliders": [
    {"obj": "body.$F4.obj", "thickness": 0.002, "friction": 0.3},
    {"generator": "sphere", "center": [0, 0, 0], "radius": 0.25, "rings": 4, "segments": 8},
    {"generator": "plane", "center": [0, -1, 0], "size": 4}
  ]
})";

// The scene kScene describes, built with the library directly.
Scene expected_scene() {
  Scene s;
  ClothMaterial flag;
  flag.density = 0.2;
  flag.thickness = 0.003;
  add_cloth_piece(s, {{0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, {{0, 1, 2}, {0, 2, 3}}, flag);
  s.points.stopped[0] = s.points.stopped[3] = 1;
  ClothMaterial sheet;
  sheet.stretch = StretchModel::TriarapNorm;
  sheet.stretch_stiffness = 1e4;
  sheet.compress_stiffness = 100;
  sheet.stretch_damping = 0.01;
  sheet.bend_stiffness = 0;
  sheet.layer = 1;
  sheet.friction = 0.5;
  const Mesh g = grid(4, 2, {0, 2, 0}, {1, 0, 0}, {0, 0, 0.5});
  const int first = add_cloth_piece(s, g.x, g.tris, sheet);
  s.constraints.pin.push_back({first + 14, g.x[14], -1, 0, xpbd_material(1000, -1, 0.1)});
  for (int i : {0, 5, 10}) s.points.stopped[size_t(first + i)] = 1;  // x = 0: inside the box
  return s;
}

TEST(WEFT_TEST_SUITE, io_json_scene_gives_the_expected_scene) {
  ScratchDir dir("scene");
  dir.write("flag.obj", kFlagObj);
  write_body(dir);
  const std::string path = dir.write("scene.json", kScene);
  const Scene s = read_json_scene(path);
  const Scene want = expected_scene();

  EXPECT_EQ(s.name, path);
  const SolverSettings& st = s.settings;
  EXPECT_EQ(st.fps, 30);
  EXPECT_EQ(st.frame_start, 1);
  EXPECT_EQ(st.frame_end, 3);
  EXPECT_EQ(st.substeps, 4);
  EXPECT_EQ(st.iterations, 15);
  EXPECT_EQ(st.collision_passes, 3);
  EXPECT_EQ(st.smoothing_iterations, 2);
  EXPECT_TRUE(st.gravity == (Vec3{0, -10, 0}));
  EXPECT_TRUE(st.wind == (Vec3{1, 0, 0}));
  EXPECT_EQ(st.velocity_damping, 0.5);
  EXPECT_FALSE(st.collision.impact_zone_smoothing);
  EXPECT_EQ(st.collision.contact_solver, ContactSolver::Jacobi);
  EXPECT_EQ(st.collision.ccd_span, CcdSpan::Substep);
  EXPECT_EQ(st.tether_stretch, 1.1);
  EXPECT_EQ(st.stretch_limits, 1);
  EXPECT_EQ(st.coarse_levels, 3);
  EXPECT_EQ(st.coarse_iterations, 2);
  EXPECT_EQ(st.collision.contact_model, ContactModel::Ccd);
  EXPECT_EQ(st.collision.early_pass_fraction, 0.05);
  EXPECT_EQ(st.collision.early_pass_excess, 2);
  EXPECT_EQ(st.collision.max_early_passes, 2);
  EXPECT_EQ(st.collision.max_collider_early_passes, 0);
  EXPECT_FALSE(st.collision.pair_refresh);
  EXPECT_FALSE(st.collision.merge_contacts);
  EXPECT_TRUE(st.collision.nearest_margins);
  EXPECT_TRUE(st.collision.predicted_reference);
  EXPECT_EQ(st.collision.layer_shock, 10);
  EXPECT_EQ(st.collision.still_tolerance, 0.3);

  const ClothPoints &p = s.points, &q = want.points;
  ASSERT_EQ(p.size(), 4u + 15u);
  for (size_t i = 0; i < p.size(); ++i) {
    EXPECT_TRUE(p.position[i] == q.position[i]) << i;
    EXPECT_EQ(p.mass[i], q.mass[i]) << i;
    EXPECT_EQ(p.thickness[i], q.thickness[i]) << i;
    EXPECT_EQ(p.friction[i], q.friction[i]) << i;
    EXPECT_EQ(p.layer[i], q.layer[i]) << i;
    EXPECT_EQ(p.piece[i], q.piece[i]) << i;
  }
  EXPECT_EQ(p.stopped, q.stopped);
  EXPECT_EQ(s.triangles, want.triangles);

  const Constraints &c = s.constraints, &w = want.constraints;
  ASSERT_EQ(c.distance.size(), w.distance.size());
  for (size_t i = 0; i < c.distance.size(); ++i) {
    EXPECT_EQ(c.distance[i].a, w.distance[i].a);
    EXPECT_EQ(c.distance[i].b, w.distance[i].b);
    EXPECT_EQ(c.distance[i].rest, w.distance[i].rest);
  }
  ASSERT_EQ(c.triarap.size(), 16u);
  for (size_t i = 0; i < c.triarap.size(); ++i) {
    EXPECT_EQ(c.triarap[i].p0, w.triarap[i].p0);
    EXPECT_EQ(c.triarap[i].area, w.triarap[i].area);
    EXPECT_TRUE(c.triarap[i].normalized);
    EXPECT_EQ(c.triarap[i].m.compliance, 1e-4);
    EXPECT_EQ(c.triarap[i].m.compress_compliance, 1e-2);
    EXPECT_EQ(c.triarap[i].m.damping_ratio, 0.01);
  }
  EXPECT_EQ(c.bend.size(), w.bend.size());  // the flag bends, the sheet (bend_stiffness 0) does not
  ASSERT_EQ(c.pin.size(), 1u);
  EXPECT_EQ(c.pin[0].p, 4 + 14);
  EXPECT_TRUE(c.pin[0].goal == (Vec3{1, 2, 0.5}));
  EXPECT_EQ(c.pin[0].m.compliance, 1e-3);
  EXPECT_EQ(c.pin[0].m.damping_ratio, 0.1);

  ASSERT_EQ(s.colliders.size(), 3u);
  const Collider& body = s.colliders[0];
  EXPECT_EQ(body.name, "body");
  EXPECT_EQ(body.thickness, 0.002);
  EXPECT_EQ(body.friction, 0.3);
  ASSERT_EQ(body.motion.frames.size(), 3u);  // one per frame of the range
  EXPECT_DOUBLE_EQ(body.motion.frames[2][1].y, 0.2);
  EXPECT_EQ(s.colliders[1].name, "sphere1");
  EXPECT_EQ(s.colliders[1].triangles, uv_sphere({0, 0, 0}, 0.25, 4, 8).tris);
  const Collider& plane = s.colliders[2];
  ASSERT_EQ(plane.triangles.size(), 2u);
  const auto& x = plane.motion.frames[0];
  const auto& t = plane.triangles[0];
  const Vec3 n = cross(x[size_t(t[1])] - x[size_t(t[0])], x[size_t(t[2])] - x[size_t(t[0])]);
  EXPECT_GT(n.y, 0);              // faces along its normal (default +y)
  EXPECT_DOUBLE_EQ(norm(n), 16);  // 4 m square
  for (const Vec3& v : x) EXPECT_DOUBLE_EQ(v.y, -1);
  EXPECT_TRUE(s.needs_collisions);
}

TEST(WEFT_TEST_SUITE, io_json_builtin_base) {
  ScratchDir dir("builtin");
  const std::string path = dir.write("scene.json", R"({"builtin": "hanging-sheet", "res": 4,
      "settings": {"frames": [1, 5], "collisions": false},
      "cloth": [{"generator": "grid", "res": [1, 1]}]})");
  const Scene s = read_json_scene(path);
  EXPECT_EQ(s.points.size(), 25u + 4u);
  EXPECT_EQ(s.points.piece.back(), 1);
  EXPECT_EQ(s.settings.frame_end, 5);
  EXPECT_FALSE(s.needs_collisions);
  EXPECT_EQ(s.points.stopped[4], 1);  // the base scene's pins stay
}

TEST(WEFT_TEST_SUITE, io_json_load_scene_dispatch) {
  ScratchDir dir("dispatch");
  dir.write("flag.obj", kFlagObj);
  write_body(dir);
  const std::string path = dir.write("scene.json", kScene);
  const Scene s = load_scene(path, {});
  EXPECT_EQ(s.points.size(), 19u);
  write_scene(s, dir.file("scene.h5"));
  const Scene h = load_scene(dir.file("scene.h5"), {});
  EXPECT_EQ(h.points.size(), 19u);
  EXPECT_EQ(h.constraints.triarap.size(), 16u);
  EXPECT_EQ(h.colliders.size(), 3u);
  std::string e = input_error([&] { load_scene(dir.file("scene.txt"), {}); });
  EXPECT_TRUE(contains(e, "scene.txt: unknown scene source")) << e;
  e = input_error([&] { load_scene(path, BuiltinOptions{8}); });
  EXPECT_TRUE(contains(e, "--res")) << e;
}

// Each error class: the message starts with the file and names the JSON path.
TEST(WEFT_TEST_SUITE, io_json_errors_name_file_and_path) {
  ScratchDir dir("errors");
  dir.write("flag.obj", kFlagObj);
  dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv x 1 0\nf 1 2 3\n");
  dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
  write_body(dir);
  const std::string path = dir.file("scene.json");
  const auto error = [&](const std::string& text) {
    dir.write("scene.json", text);
    return input_error([&] { read_json_scene(path); });
  };
  const std::string cloth0 = R"({"cloth": [{"generator": "grid"}, )";
  struct Case {
    std::string json, message;
  };
  const Case cases[] = {
      {R"({"cloth": [)", ": parse error at line 1, column 12"},
      {"[1, 2]", ": top level: expected an object"},
      {R"({"clothes": []})", ": clothes: unknown key (known here: builtin, res, settings, cloth, colliders, stitches)"},
      {R"({"res": 3})", ": res: 'res' sets the resolution of a 'builtin' base scene"},
      {R"({"builtin": "nope"})", ": builtin: unknown built-in scene 'nope'"},
      {R"({"settings": {"substeps": 0}})", ": settings.substeps: expected an integer in 1.."},
      {R"({"settings": {"frames": [5, 2]}})", ": settings.frames[1]: expected an integer in 5.."},
      {R"({"settings": {"gravity": [0, -9.81]}})", ": settings.gravity: expected [x, y, z]"},
      {R"({"settings": {"fps": "24"}})", ": settings.fps: expected a number"},
      {R"({"settings": {"contact_solver": "sor"}})", ": settings.contact_solver: expected \"gauss-seidel\" or \"jacobi\""},
      {R"({"settings": {"ccd_span": "frame"}})", ": settings.ccd_span: expected \"substep\" or \"pass\""},
      {R"({"settings": {"contact_model": "ipc"}})", ": settings.contact_model: expected \"proximity\" or \"ccd\""},
      {R"({"settings": {"pair_refresh": 1}})", ": settings.pair_refresh: expected true or false"},
      {R"({"settings": {"tethers": 0.9}})", ": settings.tethers: expected 0 (no tethers) or a stretch of at least 1"},
      {R"({"settings": {"layer_shock": 0.5}})", ": settings.layer_shock: expected a number >= 1 (1: off)"},
      {cloth0 + R"({"generator": "grid", "material": {"density": "heavy"}}]})",
       ": cloth[1].material.density: expected a number"},
      {cloth0 + R"({"generator": "grid", "material": {"density": -1}}]})",
       ": cloth[1].material.density: expected a positive number, got -1"},
      {R"({"cloth": [{"generator": "grid", "material": {"stretch": "springs"}}]})",
       ": cloth[0].material.stretch: unknown stretch model 'springs' (distance, triarap, triarapnorm, fem)"},
      {R"({"cloth": [{"generator": "grid", "material": {"compress_stiffness": 0}}]})",
       ": cloth[0].material.compress_stiffness: expected -1 (same as stretch) or a positive number"},
      {R"({"cloth": [{"generator": "grid", "material": {"densty": 1}}]})", ": cloth[0].material.densty: unknown key"},
      {R"({"cloth": [{"generator": "disc"}]})", ": cloth[0].generator: unknown cloth generator 'disc' (grid)"},
      {R"({"cloth": [{"obj": "flag.obj", "generator": "grid"}]})",
       ": cloth[0]: give exactly one of 'obj' and 'generator'"},
      {R"({"cloth": [{"obj": "missing.obj"}]})", ": cloth[0].obj: cannot open " + dir.file("missing.obj")},
      {R"({"cloth": [{"obj": "bad.obj"}]})",
       ": cloth[0].obj: " + dir.file("bad.obj") + ": line 3: 'x' is not a number"},
      {R"({"cloth": [{"obj": "flat.obj"}]})",
       ": cloth[0].obj: " + dir.file("flat.obj") + ": triangle 0 (vertices 1, 2, 3) has zero area"},
      {R"({"cloth": [{"generator": "grid", "res": [1, 1], "pins": [{"points": [0, 4]}]}]})",
       ": cloth[0].pins[0].points[1]: expected an integer in 0..3, got 4"},
      {R"({"cloth": [{"generator": "grid", "pins": [{"group": "top"}]}]})",
       ": cloth[0].pins[0].group: no group 'top' in this cloth piece's 'groups'"},
      {R"({"cloth": [{"generator": "grid", "res": [1, 1], "groups": {"top": [7]}}]})",
       ": cloth[0].groups.top[0]: expected an integer in 0..3, got 7"},
      {R"({"cloth": [{"generator": "grid", "pins": [{"box": {"min": [5, 5, 5], "max": [6, 6, 6]}}]}]})",
       ": cloth[0].pins[0].box: no point of this cloth piece is inside the box"},
      {R"({"cloth": [{"generator": "grid", "pins": [{"points": [0], "box": {"min": [0, 0, 0], "max": [1, 1, 1]}}]}]})",
       ": cloth[0].pins[0]: give exactly one of 'points', 'group', 'box'"},
      {R"({"cloth": [{"generator": "grid", "pins": [{"points": [0], "stiffness": 0}]}]})",
       ": cloth[0].pins[0].stiffness: expected a positive number, got 0"},
      {R"({"colliders": [{"generator": "sphere"}]})", ": colliders[0]: missing key 'radius'"},
      {R"({"colliders": [{"generator": "cone"}]})",
       ": colliders[0].generator: unknown collider generator 'cone' (sphere, box, capsule, plane)"},
      {R"({"colliders": [{"generator": "box", "min": [1, 0, 0], "max": [0, 1, 1]}]})",
       ": colliders[0]: min must be below max in x, y and z"},
      {R"({"colliders": [{"generator": "plane", "thickness": -0.1}]})",
       ": colliders[0].thickness: expected a number >= 0, got -0.1"},
      {R"({"settings": {"frames": [1, 4]}, "colliders": [{"obj": "body.$F4.obj"}]})",
       ": colliders[0].obj: cannot open " + dir.file("body.0004.obj")},
  };
  for (const Case& c : cases) {
    const std::string e = error(c.json);
    EXPECT_EQ(e.rfind(path + ":", 0), 0u) << e;
    EXPECT_TRUE(contains(e, path + c.message)) << "got: " << e << "\nwant: " << c.message;
  }
  // A collider sequence whose topology changes names the frame file.
  write_obj(TriMesh{{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}, {{0, 2, 1}}}, dir.file("body.0002.obj"));
  const std::string e = error(R"({"settings": {"frames": [1, 3]}, "colliders": [{"obj": "body.$F4.obj"}]})");
  EXPECT_TRUE(contains(
      e, path + ": colliders[0].obj: " + dir.file("body.0002.obj") + ": the collider's topology changes at frame 2"))
      << e;
  EXPECT_TRUE(
      contains(input_error([&] { read_json_scene(dir.file("none.json")); }), dir.file("none.json") + ": cannot open"));
}

// A cloth too thick for its triangles is flagged once per piece, with the triangle and the thickness to use;
// every built-in scene at its own resolution is not.
TEST(WEFT_TEST_SUITE, a_cloth_too_thick_for_its_triangles_gets_a_warning) {
  for (const std::string& name : builtin_scene_names())
    EXPECT_TRUE(thickness_warnings(make_builtin_scene(name, {})).empty()) << name;
  Scene s = make_builtin_scene("drape-sphere", {120});  // 1.2 m / 120: triangles 7.07 mm high, thickness 5 mm
  const std::vector<std::string> w = thickness_warnings(s);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("cloth piece 0"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("0.00283 m"), std::string::npos) << w[0];
  s.settings.collision.self_collision = false;  // no self contacts, nothing to warn about
  EXPECT_TRUE(thickness_warnings(s).empty());
}

}  // namespace
