// Morton (Z-curve) codes: 10 bits a coordinate, interleaved. Integer work after one quantisation of + - * /,
// so every backend gives the same codes. Used by the LBVH (collision/morton.hpp) and by the sweep's patches
// (constraints/sweep_patches.hpp).
#pragma once
#include "core/real.hpp"
#include "core/vec.hpp"

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

// 30-bit Morton code of p in the cube [lo, lo + extent]^3 (x in the highest of each bit triple). One extent
// for all axes: scaling each axis on its own would give the millimetres across a flat cloth as many bits as
// its metres.
KOKKOS_INLINE_FUNCTION uint32_t morton30(Vec3 p, Vec3 lo, real extent) {
  return (morton_spread10(morton_cell(p.x, lo.x, extent)) << 2) | (morton_spread10(morton_cell(p.y, lo.y, extent)) << 1) |
         morton_spread10(morton_cell(p.z, lo.z, extent));
}

}  // namespace weft
