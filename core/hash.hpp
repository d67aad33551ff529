// A 64-bit hash of a View's bytes: each 32-bit word is mixed with its index and the mixes are added as
// integers (exact and order-free, so parallel reduction is deterministic), then finalised with the length.
#pragma once
#include <Kokkos_Core.hpp>

#include <cstdint>
#include <cstring>
#include <string>

namespace weft {

KOKKOS_INLINE_FUNCTION uint64_t splitmix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

struct HashWords {
  const uint32_t* p;
  KOKKOS_INLINE_FUNCTION void operator()(long i, uint64_t& acc) const { acc += splitmix64((uint64_t(i) << 32) ^ p[i]); }
};

// Hash of the bytes of a contiguous View whose value size is a multiple of 4.
template <class Exec, class View>
uint64_t hash_view(const Exec& exec, const View& v) {
  using T = typename View::non_const_value_type;
  static_assert(sizeof(T) % 4 == 0, "hash_view needs 4-byte multiples");
  const long words = static_cast<long>(v.span() * sizeof(T) / 4);
  const uint32_t* p = reinterpret_cast<const uint32_t*>(v.data());
  uint64_t sum = 0;
  Kokkos::parallel_reduce("weft::hash_view", Kokkos::RangePolicy<Exec>(exec, 0, words), HashWords{p}, sum);
  return splitmix64(sum ^ splitmix64(uint64_t(words)));
}

// Combine a running hash with another (order matters: frame after frame).
inline uint64_t hash_combine(uint64_t h, uint64_t v) { return splitmix64(h ^ (v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2))); }

inline std::string hash_hex(uint64_t h) {
  char buf[17];
  for (int i = 15; i >= 0; --i, h >>= 4) buf[i] = "0123456789abcdef"[h & 15];
  buf[16] = 0;
  return buf;
}

}  // namespace weft
