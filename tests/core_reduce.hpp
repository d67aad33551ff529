// Fixed-tree reductions: the same bits as the host reference for awkward sizes, on every backend.
#include "core/reduce.hpp"

namespace {

std::vector<double> awkward_data(size_t n, uint64_t seed) {
  weft::test::TestRng rng(seed);
  std::vector<double> v(n);
  for (auto& x : v) x = rng.uniform(-1, 1) * (rng.next() % 3 == 0 ? 1e8 : 1e-3);  // mixed magnitudes
  return v;
}

TEST(WEFT_TEST_SUITE, reductions_match_the_host_tree_bitwise) {
  using Exec = WEFT_TEST_EXECSPACE;
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1023), size_t(1000003)}) {
    const auto v = awkward_data(n, n + 1);
    auto d = weft::test::to_device<Exec>(v);
    Exec exec;
    EXPECT_EQ(weft::test::bits(weft::sum_fixed(exec, d)), weft::test::bits(weft::reduce_fixed_host(v, weft::SumOp{}))) << n;
    EXPECT_EQ(weft::test::bits(weft::min_fixed(exec, d)), weft::test::bits(weft::reduce_fixed_host(v, weft::MinOp{}))) << n;
    EXPECT_EQ(weft::test::bits(weft::max_fixed(exec, d)), weft::test::bits(weft::reduce_fixed_host(v, weft::MaxOp{}))) << n;
  }
}

TEST(WEFT_TEST_SUITE, reduce_into_stays_on_the_device) {
  using Exec = WEFT_TEST_EXECSPACE;
  auto d = weft::test::to_device<Exec>(std::vector<double>{1, 2, 3, 4});
  Kokkos::View<double, Exec::memory_space> out("out");
  weft::reduce_fixed_into(Exec(), d, out, weft::SumOp{});
  double h = 0;
  Kokkos::deep_copy(h, out);
  EXPECT_EQ(h, 10.0);
}

}  // namespace
