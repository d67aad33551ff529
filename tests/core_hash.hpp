// The View hash, and pinned hashes of reductions and sorts that every backend and thread count must hit.
#include "core/hash.hpp"
#include "core/reduce.hpp"
#include "core/sort.hpp"

namespace {

TEST(WEFT_TEST_SUITE, hash_sees_every_bit_and_position) {
  using Exec = WEFT_TEST_EXECSPACE;
  std::vector<double> v(1001);
  for (size_t i = 0; i < v.size(); ++i) v[i] = 0.5 * double(i);
  const uint64_t h0 = weft::hash_view(Exec(), weft::test::to_device<Exec>(v));
  auto w = v;
  w[500] = -w[500] + 0.0;  // one sign bit
  EXPECT_NE(h0, weft::hash_view(Exec(), weft::test::to_device<Exec>(w)));
  w = v;
  std::swap(w[3], w[4]);  // same values, different places
  EXPECT_NE(h0, weft::hash_view(Exec(), weft::test::to_device<Exec>(w)));
  EXPECT_EQ(h0, weft::hash_view(Exec(), weft::test::to_device<Exec>(v)));
  EXPECT_EQ(weft::hash_hex(0x0123456789abcdefull), "0123456789abcdef");
}

// One number summarising reductions and a sort of awkward data. Pinned: a change on any backend, thread
// count or compiler shows up here.
TEST(WEFT_TEST_SUITE, reductions_and_sort_match_pinned_hash) {
  using Exec = WEFT_TEST_EXECSPACE;
  Exec exec;
  uint64_t h = 0;
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1023), size_t(1000003)}) {
    weft::test::TestRng rng(1234 + n);
    std::vector<double> v(n);
    std::vector<uint64_t> k(n);
    std::vector<uint32_t> idx(n);
    for (size_t i = 0; i < n; ++i) {
      v[i] = rng.uniform(-1, 1) * (i % 5 == 0 ? 1e9 : 1e-4);
      k[i] = rng.next() & 0xFFFFull;
      idx[i] = uint32_t(i);
    }
    auto dv = weft::test::to_device<Exec>(v);
    h = weft::hash_combine(h, weft::test::bits(weft::sum_fixed(exec, dv)));
    h = weft::hash_combine(h, weft::test::bits(weft::min_fixed(exec, dv)));
    h = weft::hash_combine(h, weft::test::bits(weft::max_fixed(exec, dv)));
    auto dk = weft::test::to_device<Exec>(k);
    auto di = weft::test::to_device<Exec>(idx);
    weft::radix_sort_pairs(exec, dk, di, 16);
    h = weft::hash_combine(h, weft::hash_view(exec, dk));
    h = weft::hash_combine(h, weft::hash_view(exec, di));
  }
  EXPECT_EQ(weft::hash_hex(h), "a4c9955e08071a61");
}

}  // namespace
