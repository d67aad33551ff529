// Canaries for the floating-point policy: if these fail, bitwise equality across backends is gone.
#include "core/real.hpp"

namespace {

TEST(WEFT_TEST_SUITE, multiply_add_is_not_fused) {
  using Exec = WEFT_TEST_EXECSPACE;
  // (1 + 2^-30)(1 - 2^-30) = 1 - 2^-60 rounds to 1, so a*b + c is 0 unfused but -2^-60 fused.
  auto in = weft::test::to_device<Exec>(std::vector<double>{1 + 0x1p-30, 1 - 0x1p-30, -1.0});
  Kokkos::View<double*, Exec::memory_space> out("out", 1);
  Kokkos::parallel_for(Kokkos::RangePolicy<Exec>(0, 1), KOKKOS_LAMBDA(int) { out(0) = in(0) * in(1) + in(2); });
  EXPECT_EQ(weft::test::to_host(out)[0], 0.0);
}

TEST(WEFT_TEST_SUITE, sqrt_and_division_round_like_the_host) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(7);
  std::vector<double> a(1000), b(1000);
  for (size_t i = 0; i < a.size(); ++i) { a[i] = rng.uniform(1e-3, 1e3); b[i] = rng.uniform(-1e3, 1e3); }
  auto da = weft::test::to_device<Exec>(a), db = weft::test::to_device<Exec>(b);
  Kokkos::View<double*, Exec::memory_space> out("out", a.size());
  Kokkos::parallel_for(Kokkos::RangePolicy<Exec>(0, a.size()),
                       KOKKOS_LAMBDA(int i) { out(i) = weft::sqrt_(da(i)) / db(i) + weft::atan2_(db(i), da(i)); });
  auto h = weft::test::to_host(out);
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(weft::test::bits(h[i]), weft::test::bits(weft::sqrt_(a[i]) / b[i] + weft::atan2_(b[i], a[i]))) << i;
}

TEST(WEFT_TEST_SUITE, atan2_matches_the_library_closely) {
  weft::test::TestRng rng(3);
  for (int i = 0; i < 10000; ++i) {
    const double y = rng.uniform(-10, 10), x = rng.uniform(-10, 10);
    ASSERT_NEAR(weft::atan2_(y, x), std::atan2(y, x), 4e-16 * (1 + std::fabs(std::atan2(y, x)))) << y << " " << x;
  }
  EXPECT_EQ(weft::atan2_(0, 0), 0.0);
  EXPECT_NEAR(weft::atan2_(0, -1), weft::pi, 1e-15);
  EXPECT_NEAR(weft::atan2_(1, 0), weft::pi / 2, 1e-15);
}

}  // namespace
