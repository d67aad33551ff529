// Helpers shared by the test bodies; each body uses WEFT_TEST_EXECSPACE and WEFT_TEST_SUITE.
#pragma once
#include "core/device_copy.hpp"

#include <Kokkos_Core.hpp>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

// nvcc rejects device lambdas inside private member functions, which gtest's TestBody is; so each TEST body
// here becomes a free function that the gtest test calls. Test bodies are written as usual.
#undef TEST
#define WEFT_CAT_(a, b) a##b
#define WEFT_CAT(a, b) WEFT_CAT_(a, b)
#define WEFT_BODY(suite, name) WEFT_CAT(WEFT_CAT(suite, _), WEFT_CAT(name, _body))
#define TEST(suite, name)                               \
  void WEFT_BODY(suite, name)();                        \
  GTEST_TEST(suite, name) { WEFT_BODY(suite, name)(); } \
  void WEFT_BODY(suite, name)()

namespace weft::test {

// Copy a host vector into a View of the execution space.
template <class Exec, class T>
Kokkos::View<T*, typename Exec::memory_space> to_device(const std::vector<T>& h, const char* label = "test") {
  return upload<typename Exec::memory_space>(h, label);
}

using weft::to_host;

inline uint64_t bits(double x) {
  uint64_t u;
  std::memcpy(&u, &x, 8);
  return u;
}

// Deterministic pseudo-random numbers for test data (no library RNG, same on every platform).
struct TestRng {
  uint64_t s;
  explicit TestRng(uint64_t seed) : s(seed) {}
  uint64_t next() {
    s += 0x9E3779B97F4A7C15ull;
    uint64_t z = s;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo = 0, double hi = 1) { return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53; }
};

std::string shared_dir();  // ../shared beside the checkout; empty when absent

}  // namespace weft::test
