// The built-in collision scenes stay intersection-free, keep cloth out of colliders, and settle.
#include "io/builtin_scenes.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::real;
using weft::Vec3;

TEST(WEFT_TEST_SUITE, drape_on_sphere_has_no_intersections_and_stays_outside) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("drape-sphere", {10});
  weft::SimulationOn<Exec> sim(s);
  long max_contacts = 0;
  for (int f = 0; f < 24; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    max_contacts = std::max(max_contacts, fs.collision.contacts);
    if (f % 6 == 5) ASSERT_EQ(sim.intersections(), 0) << "frame " << fs.frame;
    for (const Vec3& p : sim.positions())  // sphere: centre (0, 0.4, 0), radius 0.3 (faceted: allow 2 mm)
      ASSERT_GT(weft::norm(p - Vec3{0, 0.4, 0}), 0.3 - 0.002) << "frame " << fs.frame;
  }
  EXPECT_GT(max_contacts, 0);
}

// Each collider keeps cloth at its own thickness: two strips settle on two plates, 1 cm and 3 cm thick.
TEST(WEFT_TEST_SUITE, each_collider_holds_cloth_at_its_own_thickness) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::test::empty_scene("two-plates");
  weft::ClothMaterial mat;
  mat.thickness = 0.002;
  mat.stretch_stiffness = 1e6;
  const real x0[2] = {-0.7, 0.2}, plate[2] = {0.01, 0.03};
  size_t first[2];
  for (int k = 0; k < 2; ++k) {
    const weft::io::Mesh strip = weft::io::grid(5, 5, {x0[k], 0.08, -0.25}, {0.5, 0, 0}, {0, 0, 0.5});
    first[k] = s.points.size();
    weft::add_cloth_piece(s, strip.x, strip.tris, mat);
    const weft::io::Mesh b = weft::io::box({x0[k] - 0.1, -0.2, -0.4}, {x0[k] + 0.6, 0, 0.4});
    weft::Collider c;
    c.name = "plate" + std::to_string(k);
    c.triangles = b.tris;
    c.motion.frames.push_back(b.x);
    c.thickness = plate[k];
    s.colliders.push_back(c);
  }
  s.settings.frame_end = 30;
  s.needs_collisions = true;
  weft::SimulationOn<Exec> sim(s);
  for (int f = 0; f < 29; ++f) ASSERT_EQ(sim.step_frame().non_finite, 0);
  const std::vector<Vec3> x = sim.positions();
  for (int k = 0; k < 2; ++k) {
    real mean = 0;
    const size_t n = (k == 0 ? first[1] : x.size()) - first[k];
    for (size_t i = first[k]; i < first[k] + n; ++i) mean += x[i].y / real(n);
    // At rest on the plate (top at y = 0) the cloth is the two thicknesses away: 12 mm and 32 mm.
    EXPECT_NEAR(mean, plate[k] + mat.thickness, 0.002) << "strip on plate " << k;
  }
  EXPECT_EQ(sim.intersections(), 0);
}

// The scaling scene of fifty layers, at its coarsest: the stack lands on the sphere without a crossing.
TEST(WEFT_TEST_SUITE, layer_drop_lands_fifty_layers_without_intersections) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("layer-drop", {2});
  ASSERT_EQ(s.triangles.size(), 50u * 8u);
  weft::SimulationOn<Exec> sim(s);
  weft::FrameStats fs;
  for (int f = 0; f < 8; ++f) {
    fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
  }
  EXPECT_GT(fs.collision.contacts, 0);
  EXPECT_EQ(sim.intersections(), 0);
  for (const Vec3& p : sim.positions())  // sphere: centre (0, 0.4, 0), radius 0.3 (faceted: allow 2 mm)
    ASSERT_GT(weft::norm(p - Vec3{0, 0.4, 0}), 0.3 - 0.002);
}

// Layer shock: a light sheet (0.1 kg/m^2) under one a thousand times heavier, dropped on a sphere (the
// stability case mass-ratio-1000 at a quarter of its size). The lower layer acts layer_shock times heavier
// than what it carries, so it holds the heavy sheet instead of being pressed into the sphere and stretched
// (a lower point scaled by its own mass alone, the same sheets as a JSON scene reached max strain 0.14 by
// frame 30, sliding at 1 m/s).
TEST(WEFT_TEST_SUITE, layer_shock_lets_a_light_layer_carry_one_a_thousand_times_heavier) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::test::empty_scene("mass-ratio");
  const real density[2] = {0.1, 100};
  const weft::io::Mesh sheets[2] = {weft::io::grid(12, 12, {-0.6, 0.75, -0.6}, {1.2, 0, 0}, {0, 0, 1.2}),
                                    weft::io::grid(8, 8, {-0.4, 0.775, -0.4}, {0.8, 0, 0}, {0, 0, 0.8})};
  for (int l = 0; l < 2; ++l) {
    weft::ClothMaterial mat;
    mat.density = density[l];
    mat.layer = l;
    mat.thickness = 0.004;
    weft::add_cloth_piece(s, sheets[l].x, sheets[l].tris, mat);
  }
  const weft::io::Mesh ball = weft::io::uv_sphere({0, 0.4, 0}, 0.3, 32, 64);
  weft::Collider c;
  c.name = "sphere";
  c.triangles = ball.tris;
  c.motion.frames.push_back(ball.x);
  c.thickness = 0.002;
  s.colliders.push_back(c);
  s.settings.frame_end = 30;
  s.needs_collisions = true;
  weft::SimulationOn<Exec> sim(s);
  real worst = 0;
  weft::FrameStats fs;
  for (int f = 0; f < 29; ++f) {
    fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    worst = std::max(worst, fs.max_strain);
  }
  std::printf("light layer under a heavy one: max strain over frames 2-30 %.4f, rms speed at frame 30 %.3e m/s\n", worst,
              fs.rms_speed);
  EXPECT_GT(fs.collision.contacts, 0);
  EXPECT_LT(worst, 0.05);
  EXPECT_EQ(sim.intersections(), 0);
  for (const Vec3& p : sim.positions()) ASSERT_GT(weft::norm(p - Vec3{0, 0.4, 0}), 0.3 - 0.002);
}

// How deep inside the box (moving along +z at 10 m/s) a point is, 0 outside; `behind`: a point in the box's
// footprint behind it, where only a point the box jumped past could be.
real depth_in_box(const Vec3& p, real z, bool& behind) {
  const bool footprint = p.x > -0.1 && p.x < 0.1 && p.y > 0.5 && p.y < 0.7;
  behind = behind || (footprint && p.z < z - 0.1 - 1e-3 && p.z > z - 0.5);
  if (!footprint || p.z <= z - 0.1 || p.z >= z + 0.1) return 0;
  return std::min({p.x + 0.1, 0.1 - p.x, p.y - 0.5, 0.7 - p.y, p.z - (z - 0.1), z + 0.1 - p.z});
}

// The ccd model keeps every point out of the box at every frame.
TEST(WEFT_TEST_SUITE, fast_collider_never_leaves_cloth_inside_the_box) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("fast-collider", {10});
  s.settings.collision.contact_model = weft::ContactModel::Ccd;
  weft::SimulationOn<Exec> sim(s);
  for (int f = 0; f < 10; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    const real z = -1.0 + 10.0 * real(fs.frame - s.settings.frame_start) / s.settings.fps;
    bool behind = false;  // the coarse sheet's middle point slides round the box here: not asserted
    for (const Vec3& p : sim.positions())
      ASSERT_LT(depth_in_box(p, z, behind), 1e-3) << "frame " << fs.frame << " point (" << p.x << ", " << p.y << ", " << p.z << ")";
  }
  EXPECT_EQ(sim.intersections(), 0);
}

// Proximity contacts: the box (4 cm a substep) cannot jump past the cloth. The cloth in front of it moves at
// most its bound per query, so it may trail the front face by a little within a frame; the face's contact
// (found by CCD against the face's sweep at every query of the substep) pushes it out.
// With Chebyshev acceleration too: points the contacts moved are not blended.
void expect_fast_collider_never_jumps_past_the_cloth(real chebyshev_rho) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("fast-collider", {10});
  s.settings.chebyshev_rho = chebyshev_rho;
  weft::SimulationOn<Exec> sim(s);
  real deepest = 0;
  for (int f = 0; f < 10; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    const real z = -1.0 + 10.0 * real(fs.frame - s.settings.frame_start) / s.settings.fps;
    bool behind = false;
    for (const Vec3& p : sim.positions()) deepest = std::max(deepest, depth_in_box(p, z, behind));
    ASSERT_FALSE(behind) << "frame " << fs.frame;
  }
  std::printf("fast collider, proximity contacts, Chebyshev rate %.2f: deepest point inside the box at a frame's end %.4f m\n",
              chebyshev_rho, deepest);
  EXPECT_LT(deepest, 0.02);
  EXPECT_EQ(sim.intersections(), 0);
}

TEST(WEFT_TEST_SUITE, proximity_fast_collider_never_jumps_past_the_cloth) { expect_fast_collider_never_jumps_past_the_cloth(0); }

TEST(WEFT_TEST_SUITE, proximity_fast_collider_never_jumps_past_the_cloth_with_chebyshev) {
  expect_fast_collider_never_jumps_past_the_cloth(0.95);
}

// Early passes for points a collider pushes (max_collider_early_passes) run only where the collider moves:
// the still sphere under drape-sphere adds none (the same bits as without them), the 10 m/s box adds some.
TEST(WEFT_TEST_SUITE, collider_early_passes_run_only_where_a_collider_moves) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene drape = weft::io::make_builtin_scene("drape-sphere", {8});
  uint64_t with = 0, without = 0;
  weft::test::run_frames<Exec>(drape, 12, &with);
  drape.settings.collision.max_collider_early_passes = 0;
  weft::test::run_frames<Exec>(drape, 12, &without);
  EXPECT_EQ(with, without);
  const auto early_passes = [](weft::Scene s, int cap) {
    s.settings.collision.max_collider_early_passes = cap;
    weft::SimulationOn<Exec> sim(s);
    long n = 0;
    for (int f = 0; f < 6; ++f) n += sim.step_frame().collision.early_passes;
    return n;
  };
  const weft::Scene box = weft::io::make_builtin_scene("fast-collider", {10});
  EXPECT_GT(early_passes(box, 4), early_passes(box, 0));
}

// An early pass counts only points held to less than 1 / (1 + early_pass_excess) of their move: points cut
// back a little wait for the next scheduled pass (drape-sphere runs fewer early passes), while points a
// moving collider pushes count however little they were cut back (the 10 m/s box keeps its early passes).
TEST(WEFT_TEST_SUITE, early_passes_count_only_points_held_to_less_than_half) {
  using Exec = WEFT_TEST_EXECSPACE;
  const auto early_passes = [](weft::Scene s, real excess, int frames) {
    s.settings.collision.early_pass_excess = excess;
    weft::SimulationOn<Exec> sim(s);
    long n = 0;
    for (int f = 0; f < frames; ++f) n += sim.step_frame().collision.early_passes;
    return n;
  };
  const weft::Scene drape = weft::io::make_builtin_scene("drape-sphere", {8});
  const long every = early_passes(drape, 0, 12), half = early_passes(drape, 1, 12);
  EXPECT_GT(every, 0);
  EXPECT_LT(half, every);
  EXPECT_LE(early_passes(drape, 1e9, 12), half);
  const weft::Scene box = weft::io::make_builtin_scene("fast-collider", {10});
  EXPECT_GT(early_passes(box, 1e9, 6), 0);
}

// A frame's "cut back" figure is counted per point on the device over every truncation of that frame (the
// early-pass checks read counts only while an early pass can follow): each early pass needed more than
// early_pass_fraction of the moving points cut back, and the figure starts anew each frame.
TEST(WEFT_TEST_SUITE, frame_cut_back_tally_covers_its_early_passes) {
  using Exec = WEFT_TEST_EXECSPACE;
  const weft::Scene box = weft::io::make_builtin_scene("fast-collider", {10});
  long movable = 0;
  for (size_t i = 0; i < box.points.size(); ++i) movable += box.points.mass[i] > 0 && !(box.points.stopped[i] & 1);
  const real many = box.settings.collision.early_pass_fraction * real(movable);
  weft::SimulationOn<Exec> sim(box);
  long early = 0, total = 0, largest = 0;
  for (int f = 0; f < 6; ++f) {
    const weft::CollisionStats c = sim.step_frame().collision;
    EXPECT_GE(real(c.points_cut_back), real(c.early_passes) * many) << "frame " << f;
    early += c.early_passes;
    total += c.points_cut_back;
    largest = std::max(largest, c.points_cut_back);
  }
  EXPECT_GT(early, 0);
  EXPECT_LT(largest, total);  // not a running sum
}

real settled_rms_speed(bool smoothing, weft::ContactSolver solver = weft::ContactSolver::GaussSeidel,
                       weft::CcdSpan span = weft::CcdSpan::Pass, weft::ContactModel model = weft::ContactModel::Ccd) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("layer-stack", {4});
  s.settings.collision.contact_model = model;
  s.settings.collision.impact_zone_smoothing = smoothing;
  s.settings.collision.contact_solver = solver;
  s.settings.collision.ccd_span = span;
  weft::SimulationOn<Exec> sim(s);
  weft::FrameStats fs;
  for (int f = 0; f < 24; ++f) {
    fs = sim.step_frame();
    EXPECT_EQ(fs.non_finite, 0);
  }
  EXPECT_EQ(sim.intersections(), 0);
  return fs.rms_speed;
}

TEST(WEFT_TEST_SUITE, layer_stack_settles_with_and_without_smoothing) {
  const real on = settled_rms_speed(true), off = settled_rms_speed(false);
  std::printf("layer-stack rms speed after 1 s (ccd model): smoothing on %.3e m/s, off %.3e m/s\n", on, off);
  EXPECT_LT(on, 1e-3);
  EXPECT_LT(off, 1e-2);
}

// The default, proximity contacts with displacement bounds, lands and settles the stack as well.
TEST(WEFT_TEST_SUITE, layer_stack_settles_with_proximity_contacts) {
  const real v = settled_rms_speed(true, weft::ContactSolver::Jacobi, weft::CcdSpan::Pass, weft::ContactModel::Proximity);
  std::printf("layer-stack rms speed after 1 s, proximity contacts: %.3e m/s\n", v);
  EXPECT_LT(v, 1e-3);
}

// Still passes (docs/collisions.md): once the stack rests, most passes measure no pair and keep the last
// measured contacts, measured again where the cloth stands; it stays at rest, free of intersections
// (rms speed about twice that with every pass measured: 4-9e-4 against 2-5e-4 m/s at frames 13-31; the
// contacts kept frozen instead, 2.1e-3 against 3.9e-4 at --res 6).
TEST(WEFT_TEST_SUITE, layer_stack_rests_with_still_passes) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("layer-stack", {4});
  ASSERT_GT(s.settings.collision.still_tolerance, 0);  // the default
  weft::SimulationOn<Exec> sim(s);
  weft::FrameStats fs;
  long still = 0, passes = 0;
  for (int f = 0; f < 30; ++f) {
    fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    if (f >= 24) {
      still += fs.collision.still_passes;
      passes += fs.schedule.collision_passes;
    }
  }
  std::printf("layer-stack at rest: %ld of %ld passes still, rms speed %.3e m/s\n", still, passes, fs.rms_speed);
  EXPECT_GT(still, passes / 2);
  EXPECT_LT(fs.rms_speed, 2e-3);
  EXPECT_EQ(sim.intersections(), 0);
}

// Contacts projected Jacobi-style: the stack also lands without a crossing and comes to rest (less calm
// than with Gauss-Seidel: 2.6e-4 against 3.2e-5 m/s).
TEST(WEFT_TEST_SUITE, layer_stack_settles_with_jacobi_contacts) {
  const real jacobi = settled_rms_speed(true, weft::ContactSolver::Jacobi);
  std::printf("layer-stack rms speed after 1 s, Jacobi contacts: %.3e m/s\n", jacobi);
  EXPECT_LT(jacobi, 1e-3);
}

// Collision passes whose CCD spans the whole substep (--ccd-span substep) land and settle the
// stack as well.
TEST(WEFT_TEST_SUITE, layer_stack_settles_with_substep_long_ccd) {
  const real substep = settled_rms_speed(true, weft::ContactSolver::GaussSeidel, weft::CcdSpan::Substep);
  std::printf("layer-stack rms speed after 1 s, CCD over the whole substep in every pass: %.3e m/s\n", substep);
  EXPECT_LT(substep, 1e-3);
}

// The paper's Fig. 4 case: layers squeezed under a press 2000 times heavier than each of them (paper-3:
// 10 iterations, 1 pass, 20 substeps). The layers below carry the press (layer shock), so the stack comes
// to rest whether or not impact-zone smoothing runs; with a lower layer scaled by its own mass alone
// (before the carrying layer shock) the contacts did not converge, and only smoothing calmed them (6.5e-2
// against 2.6e-1 m/s).
real squeezed_rms_speed(bool smoothing) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("layer-stack", {4});
  for (size_t i = 0; i < s.points.size(); ++i)
    if (s.points.layer[i] == 5) s.points.mass[i] *= 100;  // a press of 200 kg/m^2
  s.settings.substeps = 20;
  s.settings.iterations = 10;
  s.settings.collision_passes = 1;
  s.settings.collision.impact_zone_smoothing = smoothing;
  weft::SimulationOn<Exec> sim(s);
  weft::FrameStats fs;
  real sum = 0;
  for (int f = 0; f < 30; ++f) {
    fs = sim.step_frame();
    EXPECT_EQ(fs.non_finite, 0);
    if (f >= 18) sum += fs.rms_speed;  // the last half second
  }
  EXPECT_EQ(sim.intersections(), 0);
  return sum / 12;
}

TEST(WEFT_TEST_SUITE, heavy_press_comes_to_rest_on_the_layers_it_squeezes) {
  const real on = squeezed_rms_speed(true), off = squeezed_rms_speed(false);
  std::printf("squeezed layer-stack mean rms speed over frames 20-31: smoothing on %.3e m/s, off %.3e m/s\n", on, off);
  EXPECT_LT(on, 1e-3);
  EXPECT_LT(off, 1e-3);
}

// Twisted two turns each way, the contacts of the rope do not converge: the crossing fail-safe keeps the
// cloth free of intersections (without it, frame 31 has hundreds). At this coarse resolution the rope jams
// from about frame 40 and only holding pins back keeps it free (before pins could be held, frame 37 had one
// intersecting pair); until a pin is first held, every pin sits exactly on its target.
TEST(WEFT_TEST_SUITE, twist_stays_free_of_intersections_with_the_failsafe) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("twist", {12});
  s.settings.collision.contact_model = weft::ContactModel::Ccd;
  weft::SimulationOn<Exec> sim(s);
  long moved_back = 0, pinned = 0;
  real lag = 0;
  for (int f = 0; f < 45; ++f) {
    const weft::FrameStats fs = sim.step_frame();
    ASSERT_EQ(fs.non_finite, 0);
    moved_back += fs.collision.failsafe_points;
    pinned += fs.collision.failsafe_pinned;
    if (pinned == 0) ASSERT_EQ(fs.max_pin_lag, 0.0) << "frame " << fs.frame;
    lag = std::max(lag, fs.max_pin_lag);
    if (f % 3 == 2 || f >= 33) ASSERT_EQ(sim.intersections(), 0) << "frame " << fs.frame;
  }
  EXPECT_GT(moved_back, 0);
  EXPECT_GT(pinned, 0);
  EXPECT_GT(lag, 0.0);
}

// Where the contacts converge, the fail-safe moves nothing and changes no bit.
TEST(WEFT_TEST_SUITE, failsafe_leaves_converged_contacts_alone) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("drape-sphere", {8});
  s.settings.collision.contact_model = weft::ContactModel::Ccd;
  uint64_t on = 0, off = 0;
  weft::test::run_frames<Exec>(s, 12, &on);
  s.settings.collision.collision_failsafe = false;
  weft::test::run_frames<Exec>(s, 12, &off);
  EXPECT_EQ(on, off);
}

// The ccd model's Jacobi contacts sum their corrections as fixed-point integers: the same bits on every backend.
TEST(WEFT_TEST_SUITE, jacobi_contacts_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("layer-stack", {4});
  s.settings.collision.contact_model = weft::ContactModel::Ccd;
  s.settings.collision.contact_solver = weft::ContactSolver::Jacobi;
  uint64_t h = 0;
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "22aa742b3cd5a50c");
  s.settings.collision.ccd_span = weft::CcdSpan::Substep;  // every pass's CCD over the whole substep
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "8c7cbcfe3147978c");
}

TEST(WEFT_TEST_SUITE, collision_scene_hash_is_pinned) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::io::make_builtin_scene("drape-sphere", {8});
  uint64_t h = 0;
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "41d690143bf34cb3");  // proximity contacts, the default (passes keep pairs)
  s.settings.collision.early_pass_excess = 0;  // every point cut back counts towards an early pass
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "8cf4184bb6db4e32");
  s.settings.collision.early_pass_excess = 1;
  s.settings.collision.merge_contacts = true;  // contacts on the same points as one row
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "8c3bf14772bcbfc8");
  s.settings.collision.merge_contacts = false;
  s.settings.collision.pair_refresh = false;                   // every pass queries afresh
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "9281c7a8d0346e10");
  s.settings.collision.pair_refresh = true;
  s.settings.collision.nearest_margins = true;  // margins no wider than the nearest features
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "6f76f84be6093eef");
  s.settings.collision.nearest_margins = false;
  s.settings.collision.predicted_reference = true;  // bounds beside each point's own wanted move
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "29a0caebaf2fb2ab");
  s.settings.collision.predicted_reference = false;
  s.settings.collision.max_early_passes = 4;  // up to four early passes wherever points are cut back
  s.settings.collision.early_pass_excess = 0;
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "c7494c988e35050b");
  s.settings.collision.max_early_passes = 1;
  s.settings.collision.early_pass_excess = 1;
  s.settings.collision.contact_model = weft::ContactModel::Ccd;
  weft::test::run_frames<Exec>(s, 12, &h);
  EXPECT_EQ(weft::hash_hex(h), "aa2339ca6d2e6cc6");  // either CCD span; no Chebyshev with the ccd model
}

}  // namespace
