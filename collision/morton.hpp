// Morton codes that order boxes along a Z-curve for the LBVH (core/morton.hpp), and the unique sort keys
// built from them.
#pragma once
#include "collision/aabb.hpp"
#include "core/morton.hpp"

#include <cstdint>

namespace weft {

// 30-bit Morton code of p within bounds, in cubes sized by the largest side of the bounds.
KOKKOS_INLINE_FUNCTION uint32_t morton30(Vec3 p, const Aabb& bounds) {
  const real e = max_(bounds.hi.x - bounds.lo.x, max_(bounds.hi.y - bounds.lo.y, bounds.hi.z - bounds.lo.z));
  return morton30(p, bounds.lo, e);
}

// The LBVH sort key: code in the high 32 bits, primitive index in the low 32, so keys are unique and ties
// between equal codes go to the lower index.
KOKKOS_INLINE_FUNCTION uint64_t morton_key(uint32_t code, uint32_t index) { return (uint64_t(code) << 32) | index; }

// Leading zero bits of x (64 for 0).
KOKKOS_INLINE_FUNCTION int clz64(uint64_t x) {
  if (x == 0) return 64;
#if defined(__CUDA_ARCH__)
  return __clzll(static_cast<long long>(x));
#else
  return __builtin_clzll(x);
#endif
}

}  // namespace weft
