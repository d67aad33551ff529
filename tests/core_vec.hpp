// 3-vector and 3x3 matrix math.
#include "core/vec.hpp"

#include <cmath>

namespace {

TEST(WEFT_TEST_SUITE, vec3_identities) {
  using weft::Vec3;
  const Vec3 a{1, 2, 3}, b{-4, 5, 0.5};
  EXPECT_EQ(weft::dot(weft::cross(a, b), a), 0.0);
  EXPECT_EQ(weft::dot(weft::cross(a, b), b), 0.0);
  EXPECT_DOUBLE_EQ(weft::norm(Vec3{3, 4, 12}), 13.0);
  EXPECT_DOUBLE_EQ(weft::norm(weft::normalized(b)), 1.0);
  EXPECT_EQ(weft::normalized(Vec3{}), Vec3{});
}

TEST(WEFT_TEST_SUITE, mat3_inverse_and_det) {
  weft::Mat3 m = weft::Mat3::from_cols({2, 1, 0}, {0, 3, 1}, {1, 0, 4});
  EXPECT_DOUBLE_EQ(weft::det(m), 25.0);
  const weft::Mat3 p = m * weft::inverse(m);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(p.m[i][j], i == j ? 1.0 : 0.0, 1e-15);
  const weft::Mat3 t = weft::transpose(m);
  EXPECT_EQ(t.m[0][2], m.m[2][0]);
}

// weft's atan2 (+ - * / and sqrt only, so that every backend rounds alike) against the C library's, over
// every quadrant, ratios near 0 and 1, and pairs from 1e-100 to 1e100 (its reductions square them).
TEST(WEFT_TEST_SUITE, atan2_is_within_a_few_ulp_of_the_c_library) {
  weft::test::TestRng rng(5);
  for (int n = 0; n < 200000; ++n) {
    const double scale = std::pow(10.0, rng.uniform(-100, 100));
    double y = rng.uniform(-1, 1) * scale, x = rng.uniform(-1, 1) * scale;
    if (n % 7 == 0) y *= 1e-9;  // near the axes
    if (n % 11 == 0) x *= 1e-9;
    if (n % 13 == 0) y = x * (1 + rng.uniform(-1e-12, 1e-12));  // near the diagonal, where the branch turns
    const double ref = std::atan2(y, x);
    const double ulp = std::abs(std::nextafter(ref, INFINITY) - ref);
    EXPECT_LE(std::abs(weft::atan2_(y, x) - ref), 4 * ulp) << y << " " << x;
  }
  EXPECT_EQ(weft::atan2_(0, 0), 0.0);
  EXPECT_EQ(weft::atan2_(0, -1), weft::pi);
  EXPECT_EQ(weft::atan2_(0, 1), 0.0);
}

TEST(WEFT_TEST_SUITE, vec3_math_in_kernels_matches_host) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(11);
  const int n = 257;
  std::vector<double> in(6 * n);
  for (auto& x : in) x = rng.uniform(-2, 2);
  auto d = weft::test::to_device<Exec>(in);
  Kokkos::View<double*, Exec::memory_space> out("out", n);
  auto f = [](const double* v) {
    const weft::Vec3 a{v[0], v[1], v[2]}, b{v[3], v[4], v[5]};
    const weft::Mat3 m = weft::outer(a, b) + weft::Mat3::identity();
    return weft::norm(weft::cross(a, b)) + weft::det(weft::inverse(m)) + weft::dot(m * a, weft::normalized(b));
  };
  Kokkos::parallel_for(Kokkos::RangePolicy<Exec>(0, n), KOKKOS_LAMBDA(int i) {
    double v[6];
    for (int k = 0; k < 6; ++k) v[k] = d(6 * i + k);
    const weft::Vec3 a{v[0], v[1], v[2]}, b{v[3], v[4], v[5]};
    const weft::Mat3 m = weft::outer(a, b) + weft::Mat3::identity();
    out(i) = weft::norm(weft::cross(a, b)) + weft::det(weft::inverse(m)) + weft::dot(m * a, weft::normalized(b));
  });
  auto h = weft::test::to_host(out);
  for (int i = 0; i < n; ++i) ASSERT_EQ(weft::test::bits(h[i]), weft::test::bits(f(&in[6 * i]))) << i;
}

}  // namespace
