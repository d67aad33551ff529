// A cache as one time-sampled USD mesh (`weft export cache.h5 --format usd OUT.usd`), written by OpenUSD's
// own libraries. Optional at build time (cmake/WeftUsd.cmake, -DWEFT_USD=AUTO|ON|OFF); the OpenUSD code
// lives in a module weft loads only here (io/usd/weft_usd.hpp). Layout in docs/formats.md ("USD").
#pragma once
#include <string>

namespace weft::io {

class CacheReader;

// Whether this weft was built with USD export.
bool usd_export_built();
// What to tell a user of a weft built without it.
inline constexpr const char* kNoUsdExport =
    "this weft was built without USD (install the pxr-sdf-dev wheel: scripts/setup.sh, then rebuild)";

// Whether `path` ends in .usd, .usda or .usdc, the extensions write_usd_cache takes.
bool is_usd_path(const std::string& path);

// Writes the cache's stored frames `first`..`last` (frame numbers) to `path` (.usda: text; .usdc or .usd:
// binary crate): the prim /cloth, a Mesh of the cloth triangles whose points (positions), velocities and
// extent are sampled at each frame, the frame number being the time code; timeCodesPerSecond is the
// cache's fps. Positions and velocities become 32-bit floats, as USD's point3f and vector3f hold them.
// Atomic: the layer is written under a temporary name beside `path` and renamed once complete, so a
// failure leaves nothing. Throws std::runtime_error naming `path` (its message is kNoUsdExport when this
// weft was built without USD, and says so when the USD module cannot be loaded).
void write_usd_cache(const std::string& path, const CacheReader& cache, int first, int last);

}  // namespace weft::io
