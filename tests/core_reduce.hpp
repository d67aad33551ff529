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

// The reductions keep their working memory between calls: sizes that grow and shrink, counts among them,
// and sums into parts of one View read back together give what each gives alone.
TEST(WEFT_TEST_SUITE, reductions_reuse_their_working_memory) {
  using Exec = WEFT_TEST_EXECSPACE;
  Exec exec;
  for (size_t n : {size_t(300007), size_t(3), size_t(1000003), size_t(1), size_t(70000)}) {
    const auto v = awkward_data(n, 3 * n + 7);
    auto d = weft::test::to_device<Exec>(v);
    EXPECT_EQ(weft::test::bits(weft::sum_fixed(exec, d)), weft::test::bits(weft::reduce_fixed_host(v, weft::SumOp{}))) << n;
    std::vector<int> flags(n);
    long set = 0;
    for (size_t i = 0; i < n; ++i) set += flags[i] = int((i * 7919) % 3 == 0);
    EXPECT_EQ(weft::sum_counts(exec, weft::test::to_device<Exec>(flags)), set) << n;
  }
  Kokkos::View<double[3], Exec::memory_space> out("out");
  std::vector<double> alone(3);
  for (int k = 0; k < 3; ++k) {
    const auto v = awkward_data(size_t(5000 + 1000 * k), size_t(k + 11));
    alone[k] = weft::reduce_fixed_host(v, weft::SumOp{});
    weft::reduce_fixed_into(exec, weft::test::to_device<Exec>(v), Kokkos::subview(out, k), weft::SumOp{});
  }
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(weft::test::bits(h(k)), weft::test::bits(alone[k])) << k;
}

}  // namespace
