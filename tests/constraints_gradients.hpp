// Constraint functions: gradients against central differences, the same bits inside kernels as on the host,
// and the documented values (bend angle and sign, triarap rigid invariance, FEM rest equilibrium, degeneracies).
#include "constraints/bend.hpp"
#include "constraints/fem_membrane.hpp"
#include "constraints/pin.hpp"
#include "constraints/stitch.hpp"
#include "constraints/triarap.hpp"

#include <cmath>

namespace {

using weft::real;
using weft::Vec3;
using weft::test::TestRng;

// A case packs one configuration into n_in doubles, positions of its n_points particles first; eval writes C,
// then the gradient of each particle.
KOKKOS_INLINE_FUNCTION Vec3 at(const double* in, int i) { return {in[3 * i], in[3 * i + 1], in[3 * i + 2]}; }

template <int N>
KOKKOS_INLINE_FUNCTION void put(real c, const Vec3 (&g)[N], double* out) {
  out[0] = c;
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k) out[1 + 3 * i + k] = g[i][k];
}

void set(double* in, int i, Vec3 v) {
  for (int k = 0; k < 3; ++k) in[3 * i + k] = v[k];
}

Vec3 random_point(TestRng& r, double s) { return {r.uniform(-s, s), r.uniform(-s, s), r.uniform(-s, s)}; }

// Random well-shaped triangle: twice its area at least 0.4 times its longest squared edge.
void random_triangle(TestRng& r, Vec3 (&p)[3]) {
  for (;;) {
    for (auto& q : p) q = random_point(r, 1);
    const real longest = std::fmax(weft::norm2(p[1] - p[0]), std::fmax(weft::norm2(p[2] - p[1]), weft::norm2(p[0] - p[2])));
    if (longest > 0.25 && weft::norm(weft::cross(p[1] - p[0], p[2] - p[0])) > 0.4 * longest) return;
  }
}

// Rest triangle into in[9..12] (Dm^-1), deformed positions (rest + noise of size s) into in[0..8].
void random_deformed_triangle(TestRng& r, double s, double* in) {
  Vec3 p[3];
  random_triangle(r, p);
  real dm[4], area;
  weft::triarap_rest(p[0], p[1], p[2], dm, area);
  for (int i = 0; i < 3; ++i) set(in, i, p[i] + random_point(r, s));
  for (int k = 0; k < 4; ++k) in[9 + k] = dm[k];
}

// Proper rotation from a random unit quaternion.
weft::Mat3 random_rotation(TestRng& r) {
  double q[4], n = 0;
  for (auto& c : q) { c = r.uniform(-1, 1); n += c * c; }
  n = std::sqrt(n);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  weft::Mat3 m;
  m.m[0][0] = 1 - 2 * (y * y + z * z); m.m[0][1] = 2 * (x * y - w * z);     m.m[0][2] = 2 * (x * z + w * y);
  m.m[1][0] = 2 * (x * y + w * z);     m.m[1][1] = 1 - 2 * (x * x + z * z); m.m[1][2] = 2 * (y * z - w * x);
  m.m[2][0] = 2 * (x * z - w * y);     m.m[2][1] = 2 * (y * z + w * x);     m.m[2][2] = 1 - 2 * (x * x + y * y);
  return m;
}

struct BendCase {  // o0, o1, e0, e1, rest
  static constexpr int n_points = 4, n_in = 13;
  static constexpr bool translation_invariant = true;
  KOKKOS_INLINE_FUNCTION static void eval(const double* in, double* out) {
    Vec3 g[4];
    put(weft::bend_eval(at(in, 0), at(in, 1), at(in, 2), at(in, 3), in[12], g), g, out);
  }
  // Away from degenerate triangles and from the two jumps: the angle at +-pi and C at +-pi.
  static bool make(TestRng& r, double* in) {
    Vec3 p[4];
    for (auto& q : p) q = random_point(r, 1);
    const Vec3 e = p[3] - p[2];
    const real len = weft::norm(e);
    const real h0 = weft::norm(weft::cross(p[2] - p[0], p[3] - p[0])) / len;
    const real h1 = weft::norm(weft::cross(p[3] - p[1], p[2] - p[1])) / len;
    const real theta = weft::bend_rest_angle(p[0], p[1], p[2], p[3]);
    const real rest = r.uniform(-3, 3);
    if (!(len > 0.5 && h0 > 0.3 && h1 > 0.3 && std::fabs(theta) < weft::pi - 0.2 &&
          std::fabs(std::fabs(theta - rest) - weft::pi) > 0.2))
      return false;
    for (int i = 0; i < 4; ++i) set(in, i, p[i]);
    in[12] = rest;
    return true;
  }
};

struct TriarapCase {  // p0, p1, p2, Dm^-1
  static constexpr int n_points = 3, n_in = 13;
  static constexpr bool translation_invariant = true;
  KOKKOS_INLINE_FUNCTION static void eval(const double* in, double* out) {
    Vec3 g[3];
    const real dm[4] = {in[9], in[10], in[11], in[12]};
    put(weft::triarap_eval(at(in, 0), at(in, 1), at(in, 2), dm, g), g, out);
  }
  // Away from collapsed triangles (J = 0) and from the rest shape, where C = |F - R| has a cone tip.
  static bool make(TestRng& r, double* in) {
    random_deformed_triangle(r, 0.4, in);
    double out[10];
    eval(in, out);
    Vec3 f0, f1;
    const real dm[4] = {in[9], in[10], in[11], in[12]};
    weft::triangle_deformation(at(in, 0), at(in, 1), at(in, 2), dm, f0, f1);
    return weft::norm(weft::cross(f0, f1)) > 0.2 && out[0] > 0.05;
  }
};

struct PinCase {  // p, goal, rest
  static constexpr int n_points = 1, n_in = 7;
  static constexpr bool translation_invariant = false;  // the goal does not move
  KOKKOS_INLINE_FUNCTION static void eval(const double* in, double* out) {
    Vec3 g[1];
    put(weft::pin_eval(at(in, 0), at(in, 1), in[6], g), g, out);
  }
  static bool make(TestRng& r, double* in) {
    const Vec3 p = random_point(r, 1), goal = random_point(r, 1);
    set(in, 0, p);
    set(in, 1, goal);
    in[6] = r.uniform(0, 1);
    return weft::norm(p - goal) > 0.2;
  }
};

struct PtprimCase {  // p, t0..t3, w0..w3, nt, rest
  static constexpr int n_points = 5, n_in = 21;
  static constexpr bool translation_invariant = true;  // weights sum to 1
  KOKKOS_INLINE_FUNCTION static void eval(const double* in, double* out) {
    const Vec3 t[4] = {at(in, 1), at(in, 2), at(in, 3), at(in, 4)};
    const real w[4] = {in[15], in[16], in[17], in[18]};
    Vec3 g[5];
    put(weft::ptprim_eval(at(in, 0), t, w, int(in[19]), in[20], g), g, out);
  }
  // Unused target slots hold random points and zero weight: they must be ignored.
  static bool make(TestRng& r, double* in) {
    const int nt = 2 + int(r.next() % 3);
    for (int i = 0; i < 5; ++i) set(in, i, random_point(r, 1));
    real sum = 0;
    for (int i = 0; i < 4; ++i) {
      in[15 + i] = i < nt - 1 ? r.uniform(-0.2, 0.8) : (i == nt - 1 ? 1 - sum : 0);
      sum += in[15 + i];
    }
    in[19] = nt;
    in[20] = r.uniform(0, 1);
    Vec3 q;
    for (int i = 0; i < nt; ++i) q += in[15 + i] * at(in, 1 + i);
    return weft::norm(q - at(in, 0)) > 0.2;
  }
};

struct FemDeviatoricCase {  // p0, p1, p2, Dm^-1
  static constexpr int n_points = 3, n_in = 13;
  static constexpr bool translation_invariant = true;
  KOKKOS_INLINE_FUNCTION static void eval(const double* in, double* out) {
    Vec3 g[3];
    const real dm[4] = {in[9], in[10], in[11], in[12]};
    put(weft::fem_deviatoric_eval(at(in, 0), at(in, 1), at(in, 2), dm, g), g, out);
  }
  static bool make(TestRng& r, double* in) {
    random_deformed_triangle(r, 0.4, in);
    return true;
  }
};

struct FemHydrostaticCase {  // p0, p1, p2, Dm^-1, gamma
  static constexpr int n_points = 3, n_in = 14;
  static constexpr bool translation_invariant = true;
  KOKKOS_INLINE_FUNCTION static void eval(const double* in, double* out) {
    Vec3 g[3];
    const real dm[4] = {in[9], in[10], in[11], in[12]};
    put(weft::fem_hydrostatic_eval(at(in, 0), at(in, 1), at(in, 2), dm, in[13], g), g, out);
  }
  static bool make(TestRng& r, double* in) {
    random_deformed_triangle(r, 0.4, in);
    in[13] = r.uniform(0.8, 1.5);
    Vec3 f0, f1;
    const real dm[4] = {in[9], in[10], in[11], in[12]};
    weft::triangle_deformation(at(in, 0), at(in, 1), at(in, 2), dm, f0, f1);
    return weft::norm(weft::cross(f0, f1)) > 0.2;
  }
};

template <class Case, class Mem>
struct EvalKernel {
  Kokkos::View<const double*, Mem> in;
  Kokkos::View<double*, Mem> out;
  KOKKOS_INLINE_FUNCTION void operator()(int i) const {
    Case::eval(&in(i * Case::n_in), &out(i * (1 + 3 * Case::n_points)));
  }
};

// On 128 random configurations: kernel bits equal host bits; each gradient component matches a central
// difference (step 1e-6) to 1e-5 of the gradient's largest component; translation invariance sums to zero.
template <class Exec, class Case>
void check_case(uint64_t seed) {
  constexpr int n = 128, ni = Case::n_in, no = 1 + 3 * Case::n_points;
  TestRng rng(seed);
  std::vector<double> in(n * ni), host(n * no);
  for (int i = 0; i < n; ++i)
    while (!Case::make(rng, &in[i * ni])) {}
  for (int i = 0; i < n; ++i) Case::eval(&in[i * ni], &host[i * no]);

  using Mem = typename Exec::memory_space;
  Kokkos::View<double*, Mem> out("out", n * no);
  Kokkos::parallel_for(Kokkos::RangePolicy<Exec>(0, n), EvalKernel<Case, Mem>{weft::test::to_device<Exec>(in), out});
  const auto dev = weft::test::to_host(out);
  for (int k = 0; k < n * no; ++k) ASSERT_EQ(weft::test::bits(dev[k]), weft::test::bits(host[k])) << k;

  const double h = 1e-6;
  for (int i = 0; i < n; ++i) {
    const double* g = &host[i * no + 1];
    double gmax = 0;
    for (int j = 0; j < 3 * Case::n_points; ++j) gmax = std::fmax(gmax, std::fabs(g[j]));
    ASSERT_GT(gmax, 0) << i;
    std::vector<double> x(in.begin() + i * ni, in.begin() + (i + 1) * ni), o(no);
    for (int j = 0; j < 3 * Case::n_points; ++j) {
      const double x0 = x[j];
      x[j] = x0 + h;
      Case::eval(x.data(), o.data());
      const double cp = o[0], xp = x[j];
      x[j] = x0 - h;
      Case::eval(x.data(), o.data());
      const double cm = o[0], xm = x[j];
      x[j] = x0;
      EXPECT_NEAR((cp - cm) / (xp - xm), g[j], 1e-5 * gmax) << "configuration " << i << ", coordinate " << j;
    }
    if (Case::translation_invariant)
      for (int k = 0; k < 3; ++k) {
        double sum = 0;
        for (int p = 0; p < Case::n_points; ++p) sum += g[3 * p + k];
        EXPECT_NEAR(sum, 0, 1e-12 * gmax) << "configuration " << i;
      }
  }
}

TEST(WEFT_TEST_SUITE, bend_gradient) {
  using Exec = WEFT_TEST_EXECSPACE;
  check_case<Exec, BendCase>(101);
}

TEST(WEFT_TEST_SUITE, triarap_gradient) {
  using Exec = WEFT_TEST_EXECSPACE;
  check_case<Exec, TriarapCase>(102);
}

TEST(WEFT_TEST_SUITE, pin_gradient) {
  using Exec = WEFT_TEST_EXECSPACE;
  check_case<Exec, PinCase>(103);
}

TEST(WEFT_TEST_SUITE, ptprim_gradient) {
  using Exec = WEFT_TEST_EXECSPACE;
  check_case<Exec, PtprimCase>(104);
}

TEST(WEFT_TEST_SUITE, fem_deviatoric_gradient) {
  using Exec = WEFT_TEST_EXECSPACE;
  check_case<Exec, FemDeviatoricCase>(105);
}

TEST(WEFT_TEST_SUITE, fem_hydrostatic_gradient) {
  using Exec = WEFT_TEST_EXECSPACE;
  check_case<Exec, FemHydrostaticCase>(106);
}

// Independent reference: the interior angle psi between the two half-planes, seen along the edge, from
// std::atan2; the dihedral is pi - psi, signed by the side of triangle 0 that o1 lies on.
TEST(WEFT_TEST_SUITE, bend_angle_matches_std_atan2_reference) {
  TestRng rng(7);
  for (int n = 0; n < 200;) {
    double in[13];
    if (!BendCase::make(rng, in)) continue;
    ++n;
    const Vec3 o0 = at(in, 0), o1 = at(in, 1), e0 = at(in, 2), e1 = at(in, 3);
    const Vec3 eh = weft::normalized(e1 - e0);
    const Vec3 u0 = (o0 - e0) - weft::dot(o0 - e0, eh) * eh, u1 = (o1 - e0) - weft::dot(o1 - e0, eh) * eh;
    const double psi = std::atan2(weft::norm(weft::cross(u0, u1)), weft::dot(u0, u1));
    const Vec3 n0 = weft::cross(e0 - o0, e1 - o0);
    const double ref = (weft::dot(n0, o1 - e0) > 0 ? 1 : -1) * (weft::pi - psi);
    EXPECT_NEAR(weft::bend_rest_angle(o0, o1, e0, e1), ref, 1e-12) << n;
  }
}

// The hinge along x: triangle 0 = (o0, e0, e1) lies in z = 0 with normal -z; o1 is rotated by phi about the
// edge toward -z (the normal side of triangle 0), which the convention calls positive.
void folded_pair(double phi, Vec3 (&p)[4]) {
  p[0] = {0.4, -1, 0};
  p[1] = {0.6, std::cos(phi), -std::sin(phi)};
  p[2] = {0, 0, 0};
  p[3] = {1, 0, 0};
}

TEST(WEFT_TEST_SUITE, bend_sign_convention) {
  Vec3 p[4];
  folded_pair(0, p);
  EXPECT_EQ(weft::cross(p[2] - p[0], p[3] - p[0]), (Vec3{0, 0, -1}));
  EXPECT_EQ(weft::bend_rest_angle(p[0], p[1], p[2], p[3]), 0.0);
  for (double deg : {30.0, -30.0, 150.0, -150.0, 180.0}) {
    const double phi = deg * weft::pi / 180;
    folded_pair(phi, p);
    EXPECT_NEAR(weft::bend_rest_angle(p[0], p[1], p[2], p[3]), phi, 1e-12) << deg;
    Vec3 g[4];
    EXPECT_NEAR(weft::bend_eval(p[0], p[1], p[2], p[3], phi, g), 0, 1e-12) << deg;
  }
}

TEST(WEFT_TEST_SUITE, bend_error_wraps_the_short_way) {
  Vec3 p[4], g[4];
  const double deg = weft::pi / 180;
  folded_pair(-175 * deg, p);
  EXPECT_NEAR(weft::bend_eval(p[0], p[1], p[2], p[3], 170 * deg, g), 15 * deg, 1e-12);
  folded_pair(175 * deg, p);
  EXPECT_NEAR(weft::bend_eval(p[0], p[1], p[2], p[3], -170 * deg, g), -15 * deg, 1e-12);
}

TEST(WEFT_TEST_SUITE, triarap_rest_data) {
  real dm[4], area;
  weft::triarap_rest({1, 1, 1}, {3, 1, 1}, {1.5, 1, 2}, dm, area);
  EXPECT_EQ(dm[0], 0.5);
  EXPECT_EQ(dm[1], -0.25);
  EXPECT_EQ(dm[2], 0.0);
  EXPECT_EQ(dm[3], 1.0);
  EXPECT_EQ(area, 1.0);
}

TEST(WEFT_TEST_SUITE, triarap_zero_for_rigid_motion_and_grows_with_stretch) {
  TestRng rng(8);
  for (int n = 0; n < 100; ++n) {
    Vec3 p[3], q[3], g[3];
    random_triangle(rng, p);
    real dm[4], area;
    weft::triarap_rest(p[0], p[1], p[2], dm, area);
    const weft::Mat3 rot = random_rotation(rng);
    const Vec3 shift = random_point(rng, 10);
    for (int i = 0; i < 3; ++i) q[i] = rot * p[i] + shift;
    EXPECT_LT(weft::triarap_eval(q[0], q[1], q[2], dm, g), 1e-12) << n;
    // Uniform in-plane scale s: singular values (s, s), C = sqrt(2) (s - 1).
    const double s = rng.uniform(1.05, 2);
    for (int i = 0; i < 3; ++i) q[i] = p[0] + s * (p[i] - p[0]);
    EXPECT_NEAR(weft::triarap_eval(q[0], q[1], q[2], dm, g), std::sqrt(2.0) * (s - 1), 1e-12) << n;
    // Stretch by s along one in-plane axis: singular values (s, 1), C = s - 1.
    const Vec3 u = weft::normalized(p[1] - p[0]);
    for (int i = 0; i < 3; ++i) q[i] = p[i] + (s - 1) * weft::dot(p[i] - p[0], u) * u;
    EXPECT_NEAR(weft::triarap_eval(q[0], q[1], q[2], dm, g), s - 1, 1e-12) << n;
  }
}

TEST(WEFT_TEST_SUITE, fem_lame_parameters) {
  real mu, lambda;
  weft::fem_lame(2e5, 0.25, mu, lambda);
  EXPECT_DOUBLE_EQ(mu, 8e4);
  EXPECT_DOUBLE_EQ(lambda, 2e5 * 0.25 / (1 - 0.25 * 0.25) + 8e4);  // plane-stress Lame lambda + mu
  EXPECT_DOUBLE_EQ(weft::fem_gamma(mu, lambda), 1 + 8e4 / lambda);
}

// At rest under any rigid motion: C_D = sqrt 2, J = 1, and the two elastic forces cancel.
TEST(WEFT_TEST_SUITE, fem_rest_is_force_free) {
  TestRng rng(9);
  real mu, lambda;
  weft::fem_lame(1e6, 0.3, mu, lambda);
  const real gamma = weft::fem_gamma(mu, lambda);
  for (int n = 0; n < 100; ++n) {
    Vec3 p[3], q[3], gd[3], gh[3];
    random_triangle(rng, p);
    real dm[4], area;
    weft::triarap_rest(p[0], p[1], p[2], dm, area);
    const weft::Mat3 rot = random_rotation(rng);
    const Vec3 shift = random_point(rng, 10);
    for (int i = 0; i < 3; ++i) q[i] = rot * p[i] + shift;
    const real cd = weft::fem_deviatoric_eval(q[0], q[1], q[2], dm, gd);
    const real ch = weft::fem_hydrostatic_eval(q[0], q[1], q[2], dm, gamma, gh);
    EXPECT_NEAR(cd, std::sqrt(2.0), 1e-12) << n;
    EXPECT_NEAR(ch + gamma, 1, 1e-12) << n;
    EXPECT_NEAR(weft::fem_hydrostatic_eval(q[0], q[1], q[2], dm, 1, gh), 0, 1e-12) << n;
    double gmax = 0;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) gmax = std::fmax(gmax, std::fabs(mu * cd * gd[i][k]));
    for (int i = 0; i < 3; ++i) {
      const Vec3 force = mu * cd * gd[i] + lambda * ch * gh[i];
      EXPECT_LT(weft::norm(force), 1e-12 * gmax) << n;
    }
  }
}

// Small strain eps (in the plane of the triangle): energy density mu/2 C_D^2 + lambda/2 C_H^2 above its rest
// value equals the linear plane-stress energy mu |eps|^2 + lambda_ps/2 tr(eps)^2, lambda_ps = E nu / (1 - nu^2).
TEST(WEFT_TEST_SUITE, fem_small_strain_is_linear_plane_stress) {
  TestRng rng(10);
  for (double nu : {0.0, 0.3, 0.45}) {
    const double E = 1e6, lambda_ps = E * nu / (1 - nu * nu);
    real mu, lambda;
    weft::fem_lame(E, nu, mu, lambda);
    const real gamma = weft::fem_gamma(mu, lambda);
    auto energy = [&](const Vec3 (&q)[3], const real (&dm)[4]) {
      Vec3 g[3];
      const real cd = weft::fem_deviatoric_eval(q[0], q[1], q[2], dm, g);
      const real ch = weft::fem_hydrostatic_eval(q[0], q[1], q[2], dm, gamma, g);
      return mu / 2 * cd * cd + lambda / 2 * ch * ch;
    };
    for (int n = 0; n < 20; ++n) {
      Vec3 p[3], q[3];
      random_triangle(rng, p);
      for (auto& v : p) v.z = 0;  // strain below is in the xy plane
      real dm[4], area;
      weft::triarap_rest(p[0], p[1], p[2], dm, area);
      if (!(area > 0.1)) continue;
      const double exx = rng.uniform(-1e-4, 1e-4), eyy = rng.uniform(-1e-4, 1e-4), exy = rng.uniform(-1e-4, 1e-4);
      for (int i = 0; i < 3; ++i) q[i] = p[i] + Vec3{exx * p[i].x + exy * p[i].y, exy * p[i].x + eyy * p[i].y, 0};
      const double linear = mu * (exx * exx + eyy * eyy + 2 * exy * exy) + lambda_ps / 2 * (exx + eyy) * (exx + eyy);
      EXPECT_NEAR(energy(q, dm) - energy(p, dm), linear, 1e-3 * linear) << "nu " << nu << ", case " << n;
    }
  }
}

void expect_zero(const Vec3* g, int n) {
  for (int i = 0; i < n; ++i) EXPECT_EQ(g[i], Vec3{}) << i;
}

TEST(WEFT_TEST_SUITE, degenerate_configurations_give_finite_c_and_zero_gradient) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0.3, 0, 0}, d{0.5, 1, 0};
  Vec3 g1[1], g3[3], g4[4], g5[5];
  // bend: o0 on the edge line, then a zero-length edge
  EXPECT_TRUE(weft::isfinite_(weft::bend_eval(c, d, a, b, 0.5, g4)));
  expect_zero(g4, 4);
  EXPECT_TRUE(weft::isfinite_(weft::bend_eval(d, c, a, a, 0.5, g4)));
  expect_zero(g4, 4);
  // triarap: collinear deformed triangle; degenerate rest triangle
  real dm[4], area;
  weft::triarap_rest(a, b, d, dm, area);
  EXPECT_EQ(weft::triarap_eval(a, b, {0.5, 0, 0}, dm, g3), 1.0);  // F = [(1, 0, 0), 0]: singular values (1, 0)
  expect_zero(g3, 3);
  real dm0[4], area0;
  weft::triarap_rest(a, b, c, dm0, area0);
  EXPECT_EQ(area0, 0.0);
  EXPECT_TRUE(weft::isfinite_(weft::triarap_eval(a, b, d, dm0, g3)));
  expect_zero(g3, 3);
  // FEM: a triangle collapsed to a point, then to a segment
  EXPECT_EQ(weft::fem_deviatoric_eval(d, d, d, dm, g3), 0.0);
  expect_zero(g3, 3);
  EXPECT_EQ(weft::fem_hydrostatic_eval(a, b, c, dm, 1.2, g3), -1.2);
  expect_zero(g3, 3);
  // pin at its goal; ptprim with p on the attachment point
  EXPECT_EQ(weft::pin_eval(d, d, 0.1, g1), -0.1);
  expect_zero(g1, 1);
  const Vec3 t[4] = {a, b, d, d};
  const real w[4] = {0.5, 0.5, 0, 0};
  EXPECT_EQ(weft::ptprim_eval({0.5, 0, 0}, t, w, 2, 0.1, g5), -0.1);
  expect_zero(g5, 5);
}

TEST(WEFT_TEST_SUITE, attach_goal_uses_houdini_triangle_uv) {
  const Vec3 t0{1, 0, 0}, t1{0, 2, 0}, t2{0, 0, 4};
  EXPECT_EQ(weft::attach_goal(t0, t1, t2, 0, 0), t0);
  EXPECT_EQ(weft::attach_goal(t0, t1, t2, 1, 0), t1);
  EXPECT_EQ(weft::attach_goal(t0, t1, t2, 0, 1), t2);
  EXPECT_EQ(weft::attach_goal(t0, t1, t2, 0.25, 0.5), (Vec3{0.25, 0.5, 2}));
}

}  // namespace
