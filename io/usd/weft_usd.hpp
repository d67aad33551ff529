// What weft hands its USD writer. The writer (io/usd/weft_usd.cpp) is a module, weft_usd.so beside the weft
// binary, built only when OpenUSD is found (cmake/WeftUsd.cmake) and loaded (dlopen) only by
// `weft export --format usd`: weft itself starts without OpenUSD, TBB or Python, and the rest of weft keeps
// working if the OpenUSD wheels are removed. Both sides are built together, by the same compiler.
#pragma once
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace weft::io::usd {

// A time-sampled triangle mesh, already in single precision.
struct MeshCache {
  std::string generator;      // "weft 0.1.0"
  std::string scene, source;  // the scene's name and the cache file, for the layer's customLayerData
  double fps = 24;            // time codes (frames) per second
  std::vector<int> frames;    // one time sample per frame, increasing
  size_t points = 0;
  std::vector<std::array<int, 3>> triangles;
  // Fills the positions and velocities (3 floats a point) of frames[k].
  std::function<void(size_t k, std::vector<float>& positions, std::vector<float>& velocities)> frame;
};

// The module's one entry point, looked up by this name (the version changes with MeshCache).
inline constexpr const char* kWriterSymbol = "weft_usd_write_v1";
// Writes `mesh` as a USD layer at `path`, whose extension picks the format (.usda text, .usdc or .usd
// binary crate). Returns "" on success, else what went wrong (the file may then be partly written).
using WriterFn = std::string (*)(const MeshCache& mesh, const std::string& path);

}  // namespace weft::io::usd
