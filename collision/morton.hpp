// Morton codes that order boxes along a Z-curve for the LBVH, and the unique sort keys built from them.
// All integer work after one quantisation of + - * /, so every backend gives the same keys.
#pragma once
#include "collision/aabb.hpp"

#include <cstdint>

namespace weft {

// The 10 low bits of v spread to every third bit (bit k goes to bit 3k).
KOKKOS_INLINE_FUNCTION uint32_t morton_spread10(uint32_t v) {
  v &= 0x3FFu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

// Cell 0..1023 of x in [lo, lo + extent]; a zero extent, NaN or anything below lo gives 0, anything above 1023.
KOKKOS_INLINE_FUNCTION uint32_t morton_cell(real x, real lo, real extent) {
  const real s = extent > 0 ? (x - lo) / extent * 1024 : 0;
  return s > 0 ? (s < 1023 ? uint32_t(s) : 1023u) : 0u;
}

// 30-bit Morton code of p within bounds (x in the highest of each bit triple). The cells are cubes, sized
// by the largest side of the bounds: scaling each axis on its own would give the millimetres across a
// flat cloth as many bits as its metres, and the tree would split on that noise.
KOKKOS_INLINE_FUNCTION uint32_t morton30(Vec3 p, const Aabb& bounds) {
  const real e = max_(bounds.hi.x - bounds.lo.x, max_(bounds.hi.y - bounds.lo.y, bounds.hi.z - bounds.lo.z));
  return (morton_spread10(morton_cell(p.x, bounds.lo.x, e)) << 2) |
         (morton_spread10(morton_cell(p.y, bounds.lo.y, e)) << 1) |
         morton_spread10(morton_cell(p.z, bounds.lo.z, e));
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
