// Integer scan, count-scan-fill compaction and the stable radix sort.
#include "core/compact.hpp"
#include "core/sort.hpp"

#include <algorithm>
#include <numeric>

namespace {

TEST(WEFT_TEST_SUITE, exclusive_scan_of_integers) {
  using Exec = WEFT_TEST_EXECSPACE;
  // Sizes on both sides of one block (128), of two levels (16384) and with three levels of block sums.
  for (int n : {0, 1, 7, 128, 129, 1023, 16384, 16385, 100003}) {
    std::vector<int> v(n);
    for (int i = 0; i < n; ++i) v[i] = (i * 7919) % 13;
    auto d = weft::test::to_device<Exec>(v);
    Kokkos::View<long*, Exec::memory_space> out("out", n);
    const long total = weft::exclusive_scan(Exec(), d, out);
    auto h = weft::test::to_host(out);
    long acc = 0;
    for (int i = 0; i < n; ++i) { ASSERT_EQ(h[i], acc) << i; acc += v[i]; }
    EXPECT_EQ(total, acc);
    // In place, and on the device without the total.
    std::vector<long> w(v.begin(), v.end());
    auto inplace = weft::test::to_device<Exec>(w);
    EXPECT_EQ(weft::exclusive_scan(Exec(), inplace, inplace), acc) << n;
    EXPECT_EQ(weft::test::to_host(inplace), h) << n;
    auto ondevice = weft::test::to_device<Exec>(w);
    weft::exclusive_scan_on_device(Exec(), ondevice, ondevice);
    EXPECT_EQ(weft::test::to_host(ondevice), h) << n;
  }
}

TEST(WEFT_TEST_SUITE, count_scan_fill_keeps_item_order) {
  using Exec = WEFT_TEST_EXECSPACE;
  const long n = 5000;
  Kokkos::View<long*, Exec::memory_space> offsets("offsets", n);
  Kokkos::View<long*, Exec::memory_space> out("out", n * 3);
  const long total = weft::count_scan_fill(
      Exec(), n, offsets, KOKKOS_LAMBDA(long i) { return i % 4; },
      KOKKOS_LAMBDA(long i, long first) {
        for (long k = 0; k < i % 4; ++k) out(first + k) = i;
      });
  auto h = weft::test::to_host(out);
  std::vector<long> expect;
  for (long i = 0; i < n; ++i)
    for (long k = 0; k < i % 4; ++k) expect.push_back(i);
  ASSERT_EQ(total, long(expect.size()));
  for (long i = 0; i < total; ++i) ASSERT_EQ(h[i], expect[i]) << i;
}

void check_sort(size_t n, uint64_t key_mask, int key_bits) {
  using Exec = WEFT_TEST_EXECSPACE;
  weft::test::TestRng rng(n * 31 + key_bits);
  std::vector<uint64_t> k(n);
  std::vector<uint32_t> v(n);
  for (size_t i = 0; i < n; ++i) { k[i] = rng.next() & key_mask; v[i] = uint32_t(i); }
  auto dk = weft::test::to_device<Exec>(k);
  auto dv = weft::test::to_device<Exec>(v);
  weft::radix_sort_pairs(Exec(), dk, dv, key_bits);
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return k[a] < k[b]; });
  auto hk = weft::test::to_host(dk);
  auto hv = weft::test::to_host(dv);
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(hk[i], k[order[i]]) << "n=" << n << " i=" << i;
    ASSERT_EQ(hv[i], uint32_t(order[i])) << "n=" << n << " i=" << i;
  }
}

TEST(WEFT_TEST_SUITE, radix_sort_full_keys) {
  for (size_t n : {0, 1, 7, 1023, 100003}) check_sort(n, ~0ull, 64);
}

TEST(WEFT_TEST_SUITE, radix_sort_is_stable_on_duplicate_keys) {
  check_sort(1000003, 0xF, 8);          // 16 distinct keys: ties everywhere
  check_sort(30011, 0xFFFFFull, 24);    // odd pass count
}

}  // namespace
