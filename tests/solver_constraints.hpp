// Each constraint kind alone, solved by the frame loop, reaches its rest value; colouring is race-free.
#include "constraints/bend.hpp"
#include "constraints/triangle_strain.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

using weft::real;
using weft::Vec3;

// Two triangles sharing edge 2-3, with no gravity; Chebyshev acceleration at chebyshev_rho.
weft::Scene hinge_scene(real chebyshev_rho) {
  weft::Scene s = weft::test::empty_scene("test-hinge");
  const std::vector<Vec3> x = {{0, 0, -1}, {0.2, 0.3, 1}, {-1, 0, 0}, {1, 0, 0}};
  for (const Vec3& p : x) {
    s.points.position.push_back(p);
    s.points.velocity.push_back({});
    s.points.mass.push_back(1);
    s.points.thickness.push_back(0.001);
    s.points.friction.push_back(1);
    s.points.dynamic_friction.push_back(1);
    s.points.layer.push_back(0);
    s.points.stopped.push_back(0);
    s.points.piece.push_back(0);
  }
  s.triangles = {{0, 2, 3}, {1, 3, 2}};
  s.settings.gravity = {0, 0, 0};
  s.settings.iterations = 50;
  s.settings.chebyshev_rho = chebyshev_rho;
  return s;
}

template <class Exec>
std::vector<Vec3> settle(const weft::Scene& s, int frames = 24) {
  return weft::test::run_frames<Exec>(s, frames);
}

void expect_each_constraint_alone_reaches_rest(real chebyshev_rho) {
  using Exec = WEFT_TEST_EXECSPACE;
  const auto rigid = weft::xpbd_material(1.0 / 0.0, -1, 0);
  {
    weft::Scene s = hinge_scene(chebyshev_rho);
    s.constraints.distance.push_back({2, 3, 1.5, rigid});
    const auto x = settle<Exec>(s);
    EXPECT_NEAR(weft::norm(x[3] - x[2]), 1.5, 1e-9);
  }
  {
    weft::Scene s = hinge_scene(chebyshev_rho);
    const real rest = 30 * weft::pi / 180;
    s.constraints.bend.push_back({0, 1, 2, 3, rest, rigid});
    const auto x = settle<Exec>(s);
    EXPECT_NEAR(weft::bend_rest_angle(x[0], x[1], x[2], x[3]), rest, 1e-9);
  }
  {
    weft::Scene s = hinge_scene(chebyshev_rho);
    s.constraints.pin.push_back({1, {0.5, 0.5, 0.5}, -1, 0, rigid});
    const auto x = settle<Exec>(s);
    EXPECT_LT(weft::norm(x[1] - Vec3{0.5, 0.5, 0.5}), 1e-9);
  }
  {
    weft::Scene s = hinge_scene(chebyshev_rho);
    weft::PtPrimConstraint q{1, {2, 3, -1, -1}, {0.25, 0.75, 0, 0}, 2, 0.2, rigid};
    s.constraints.ptprim.push_back(q);
    const auto x = settle<Exec>(s);
    EXPECT_NEAR(weft::norm(0.25 * x[2] + 0.75 * x[3] - x[1]), 0.2, 1e-9);
  }
  {  // triangle stretch: a stretched triangle returns to its rest shape
    weft::Scene s = hinge_scene(chebyshev_rho);
    weft::TriarapConstraint t{0, 2, 3, {0, 0, 0, 0}, 0, false, rigid};
    weft::triarap_rest(Vec3{0, 0, -0.5}, Vec3{-0.5, 0, 0}, Vec3{0.5, 0, 0}, t.dm_inv, t.area);
    s.constraints.triarap.push_back(t);
    const auto x = settle<Exec>(s);
    EXPECT_NEAR(weft::norm(x[3] - x[2]), 1.0, 1e-7);
    EXPECT_NEAR(weft::norm(x[0] - x[2]), std::sqrt(0.5), 1e-7);
  }
  {  // attach to a collider triangle (static), its attachment point 5 cm above the point: a point far from
     // everything moves at most gamma times its query margin a query (docs/collisions.md, "Margins")
    weft::Scene s = hinge_scene(chebyshev_rho);
    weft::Collider c;
    c.name = "plate";
    c.triangles = {{0, 1, 2}};
    c.motion.frames.push_back({{-0.25, 0.05, -1.5}, {0.75, 0.05, -1.5}, {-0.25, 0.05, -0.5}});
    s.colliders.push_back(c);
    // Rest distance 1 cm: the point hangs below the plate, clear of contact with it.
    s.constraints.attach.push_back({0, 0, 0, 0.25, 0.5, 0.01, rigid});
    const auto x = settle<Exec>(s);
    EXPECT_NEAR(weft::norm(x[0] - Vec3{0, 0.05, -1}), 0.01, 1e-9);
    EXPECT_LT(x[0].y, 0.05);
  }
}

TEST(WEFT_TEST_SUITE, each_constraint_alone_reaches_rest) { expect_each_constraint_alone_reaches_rest(0); }

// The blend carries the rows' multipliers along with the points: compliance-0 rows still reach rest.
TEST(WEFT_TEST_SUITE, each_constraint_alone_reaches_rest_with_chebyshev) { expect_each_constraint_alone_reaches_rest(0.95); }

// The 6 x 6 FEM sheet of Young's modulus `young`, pinned at two corners, after 48 frames.
template <class Exec>
weft::FrameStats hanging_fem_sheet(weft::real young) {
  weft::ClothMaterial mat;
  mat.stretch = weft::StretchModel::Fem;
  mat.young = young;
  weft::Scene s = weft::test::sheet_scene(6, mat);
  s.points.stopped[0] = s.points.stopped[6] = 1;
  s.settings.velocity_damping = 1;
  weft::FrameStats last;
  weft::test::run_frames<Exec>(s, 48, nullptr, &last);
  return last;
}

TEST(WEFT_TEST_SUITE, fem_membrane_sheet_hangs_like_a_stiff_membrane) {
  const weft::FrameStats last = hanging_fem_sheet<WEFT_TEST_EXECSPACE>(1e6);
  EXPECT_EQ(last.non_finite, 0);
  // Stiff: the triangles stretch a hundredth of what a membrane 10^4 times softer does (0.23 here against 40;
  // the solve is far from converged at this stiffness, see docs/solver.md, "Strain").
  EXPECT_LT(last.max_strain, 0.3);
  EXPECT_GT(last.max_strain, 0.0);
}

// The strain statistics read the triangles, whatever holds them (this sheet has no distance rows): a
// membrane ten thousand times softer hangs visibly stretched and says so.
TEST(WEFT_TEST_SUITE, fem_membrane_soft_sheet_reports_its_stretch) {
  const weft::FrameStats last = hanging_fem_sheet<WEFT_TEST_EXECSPACE>(1e2);
  EXPECT_EQ(last.non_finite, 0);
  EXPECT_GT(last.max_strain, 10.0);
  EXPECT_GT(last.p99_strain, 0);
  EXPECT_LE(last.p99_strain, last.max_strain);
}

// Triangle strain: the largest principal stretch, less 1.
TEST(WEFT_TEST_SUITE, triangle_strain_is_the_largest_principal_strain) {
  const Vec3 p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0};
  real dm[4], area;
  weft::triarap_rest(p0, p1, p2, dm, area);
  const real tol = 1e-12;
  EXPECT_NEAR(weft::triangle_strain(p0, p1, p2, dm), 0, tol);
  // Rotated and moved: no strain.
  EXPECT_NEAR(weft::triangle_strain(Vec3{3, 1, 2}, Vec3{3, 1, 3}, Vec3{3, 2, 2}, dm), 0, tol);
  // Stretched by 1.2 along x: 0.2 (its edges along x and y say 0.2 and 0; the diagonal less).
  EXPECT_NEAR(weft::triangle_strain(p0, Vec3{1.2, 0, 0}, p2, dm), 0.2, tol);
  // Squeezed in both directions: none. Squeezed along y, stretched by 1.1 along x: 0.1.
  EXPECT_NEAR(weft::triangle_strain(p0, Vec3{0.6, 0, 0}, Vec3{0, 0.6, 0}, dm), 0, tol);
  EXPECT_NEAR(weft::triangle_strain(p0, Vec3{1.1, 0, 0}, Vec3{0, 0.5, 0}, dm), 0.1, tol);
  // A unit shear, which leaves the edges along x and y as they were: principal stretch 1.618.
  EXPECT_NEAR(weft::triangle_strain(p0, p1, Vec3{1, 1, 0}, dm), (1 + std::sqrt(5.0)) / 2 - 1, 1e-9);
}

TEST(WEFT_TEST_SUITE, colouring_never_puts_two_rows_on_one_moving_particle) {
  weft::Scene s = weft::test::sheet_scene(12);
  s.points.stopped[0] = 1;
  auto rows = weft::build_rows(s, {});
  std::vector<char> movable(s.points.size(), 1);
  movable[0] = 0;
  auto col = weft::colour_greedy(long(rows.size()), long(s.points.size()), movable,
                                 [&](long r, int(&out)[8]) { return weft::row_particles(rows[r], out); });
  EXPECT_GT(col.count, 1);
  EXPECT_LT(col.count, 40);
  std::vector<std::vector<int>> seen(col.count, std::vector<int>(s.points.size(), -1));
  for (size_t r = 0; r < rows.size(); ++r) {
    int p[8];
    const int n = weft::row_particles(rows[r], p);
    for (int k = 0; k < n; ++k) {
      if (!movable[p[k]]) continue;
      ASSERT_EQ(seen[col.colour[r]][p[k]], -1) << "rows " << seen[col.colour[r]][p[k]] << " and " << r;
      seen[col.colour[r]][p[k]] = int(r);
    }
  }
  auto again = weft::colour_greedy(long(rows.size()), long(s.points.size()), movable,
                                   [&](long r, int(&out)[8]) { return weft::row_particles(rows[r], out); });
  EXPECT_EQ(again.colour, col.colour);
}

TEST(WEFT_TEST_SUITE, jacobi_smoothing_keeps_constraints_and_determinism) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::Scene s = weft::test::sheet_scene(8);
  s.points.stopped[0] = s.points.stopped[8] = 1;
  s.settings.smoothing_iterations = 5;
  uint64_t h1 = 0, h2 = 0;
  weft::FrameStats last;
  weft::test::run_frames<Exec>(s, 12, &h1, &last);
  weft::test::run_frames<Exec>(s, 12, &h2);
  EXPECT_EQ(h1, h2);
  EXPECT_EQ(last.non_finite, 0);
  EXPECT_LT(last.max_strain, 0.5);
}

}  // namespace
