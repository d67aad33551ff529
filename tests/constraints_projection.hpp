// Each constraint alone, projected by the XPBD update with zero compliance and unit inverse masses, reaches
// C = 0 from a random perturbation of its rest configuration.
#include "constraints/bend.hpp"
#include "constraints/fem_membrane.hpp"
#include "constraints/pin.hpp"
#include "constraints/stitch.hpp"
#include "constraints/triarap.hpp"
#include "constraints/xpbd.hpp"

#include <cmath>

namespace {

using weft::real;
using weft::Vec3;
using weft::test::TestRng;

Vec3 jitter(TestRng& r, double s) { return {r.uniform(-s, s), r.uniform(-s, s), r.uniform(-s, s)}; }

// Applies the update (eval fills C's gradient and returns C) until |C| < 1e-9 or max_passes; returns the last |C|.
template <int N, class Eval>
real project(Vec3 (&x)[N], Eval eval, int max_passes) {
  const weft::XpbdMaterial rigid{};
  real w[N];
  Vec3 dx[N];  // damping is 0, so the substep displacement does not matter
  for (int i = 0; i < N; ++i) w[i] = 1;
  real lambda = 0, c = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    Vec3 g[N];
    c = eval(x, g);
    if (std::fabs(c) < 1e-9) break;
    const real dl = weft::xpbd_delta_lambda<N>(c, g, w, dx, lambda, rigid, 1.0 / 60);
    lambda += dl;
    for (int i = 0; i < N; ++i) x[i] += w[i] * dl * g[i];
  }
  return std::fabs(c);
}

// Rest triangles with every height at least 0.4 of the longest edge.
void rest_triangle(TestRng& r, Vec3 (&p)[3]) {
  for (;;) {
    for (auto& q : p) q = jitter(r, 1);
    const real longest = std::fmax(weft::norm2(p[1] - p[0]), std::fmax(weft::norm2(p[2] - p[1]), weft::norm2(p[0] - p[2])));
    if (longest > 0.25 && weft::norm(weft::cross(p[1] - p[0], p[2] - p[0])) > 0.4 * longest) return;
  }
}

TEST(WEFT_TEST_SUITE, bend_projection_reaches_rest_angle) {
  TestRng rng(21);
  for (double deg : {30.0, -60.0, 170.0}) {  // 170: perturbations cross +-180, the error must wrap
    const double rest = deg * weft::pi / 180;
    for (int n = 0; n < 10; ++n) {
      // Hinge along x, o1 folded by the rest angle toward the normal side of triangle (o0, e0, e1).
      Vec3 x[4] = {{0.4, -1, 0}, {0.6, std::cos(rest), -std::sin(rest)}, {0, 0, 0}, {1, 0, 0}};
      ASSERT_NEAR(weft::bend_rest_angle(x[0], x[1], x[2], x[3]), rest, 1e-12);
      for (auto& p : x) p += jitter(rng, 0.2);
      const real c = project(x, [&](const Vec3 (&q)[4], Vec3 (&g)[4]) {
        return weft::bend_eval(q[0], q[1], q[2], q[3], rest, g);
      }, 100);
      EXPECT_LT(c, 1e-9) << deg << " " << n;
      EXPECT_NEAR(weft::bend_rest_angle(x[0], x[1], x[2], x[3]), rest, 1e-9) << deg << " " << n;
    }
  }
}

TEST(WEFT_TEST_SUITE, triarap_projection_restores_rest_shape) {
  TestRng rng(22);
  for (int n = 0; n < 20; ++n) {
    Vec3 p[3], x[3];
    rest_triangle(rng, p);
    real dm[4], area;
    weft::triarap_rest(p[0], p[1], p[2], dm, area);
    for (int i = 0; i < 3; ++i) x[i] = p[0] + 1.5 * (p[i] - p[0]) + jitter(rng, 0.1);  // stretched
    const real c = project(x, [&](const Vec3 (&q)[3], Vec3 (&g)[3]) {
      return weft::triarap_eval(q[0], q[1], q[2], dm, g);
    }, 300);  // linear convergence: |F - R| is a cone, anisotropic in positions
    EXPECT_LT(c, 1e-9) << n;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      EXPECT_NEAR(weft::norm(x[j] - x[i]), weft::norm(p[j] - p[i]), 1e-8) << n;
    }
  }
}

TEST(WEFT_TEST_SUITE, pin_projection_reaches_goal) {
  TestRng rng(23);
  for (double rest : {0.0, 0.25}) {
    for (int n = 0; n < 10; ++n) {
      const Vec3 goal = jitter(rng, 1);
      Vec3 x[1] = {goal + jitter(rng, 0.5)};
      const real c = project(x, [&](const Vec3 (&q)[1], Vec3 (&g)[1]) { return weft::pin_eval(q[0], goal, rest, g); }, 100);
      EXPECT_LT(c, 1e-9) << rest << " " << n;
      EXPECT_NEAR(weft::norm(x[0] - goal), rest, 1e-9) << rest << " " << n;
    }
  }
}

TEST(WEFT_TEST_SUITE, ptprim_projection_reaches_rest_distance) {
  TestRng rng(24);
  for (int nt = 2; nt <= 4; ++nt) {
    for (int n = 0; n < 10; ++n) {
      real w[4] = {0, 0, 0, 0}, sum = 0;
      for (int i = 0; i < nt - 1; ++i) {
        w[i] = rng.uniform(0, 1.0 / nt);
        sum += w[i];
      }
      w[nt - 1] = 1 - sum;
      const real rest = 0.1;
      Vec3 x[5];
      for (auto& p : x) p = jitter(rng, 1);
      const real c = project(x, [&](const Vec3 (&q)[5], Vec3 (&g)[5]) {
        const Vec3 t[4] = {q[1], q[2], q[3], q[4]};
        return weft::ptprim_eval(q[0], t, w, nt, rest, g);
      }, 100);
      EXPECT_LT(c, 1e-9) << nt << " " << n;
      Vec3 target;
      for (int i = 0; i < nt; ++i) target += w[i] * x[1 + i];
      EXPECT_NEAR(weft::norm(target - x[0]), rest, 1e-9) << nt << " " << n;
    }
  }
}

TEST(WEFT_TEST_SUITE, fem_hydrostatic_projection_reaches_gamma) {
  TestRng rng(25);
  const real gamma = 1.25;
  for (int n = 0; n < 20; ++n) {
    Vec3 p[3], x[3];
    rest_triangle(rng, p);
    real dm[4], area;
    weft::triarap_rest(p[0], p[1], p[2], dm, area);
    for (int i = 0; i < 3; ++i) x[i] = p[i] + jitter(rng, 0.1);
    const real c = project(x, [&](const Vec3 (&q)[3], Vec3 (&g)[3]) {
      return weft::fem_hydrostatic_eval(q[0], q[1], q[2], dm, gamma, g);
    }, 100);
    EXPECT_LT(c, 1e-9) << n;
    EXPECT_NEAR(weft::norm(weft::cross(x[1] - x[0], x[2] - x[0])) / 2, gamma * area, 1e-8) << n;  // area ratio gamma
  }
}

// Alone, with nothing opposing it, the deviatoric constraint |F| = 0 shrinks the triangle to a point.
TEST(WEFT_TEST_SUITE, fem_deviatoric_projection_collapses_the_triangle) {
  TestRng rng(26);
  for (int n = 0; n < 20; ++n) {
    Vec3 p[3], x[3];
    rest_triangle(rng, p);
    real dm[4], area;
    weft::triarap_rest(p[0], p[1], p[2], dm, area);
    for (int i = 0; i < 3; ++i) x[i] = p[i] + jitter(rng, 0.1);
    const real c = project(x, [&](const Vec3 (&q)[3], Vec3 (&g)[3]) {
      return weft::fem_deviatoric_eval(q[0], q[1], q[2], dm, g);
    }, 1000);
    EXPECT_LT(c, 1e-9) << n;
    EXPECT_LT(weft::norm(x[1] - x[0]) + weft::norm(x[2] - x[0]), 1e-8) << n;
  }
}

}  // namespace
