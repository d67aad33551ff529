// What the io readers and writers share: the triangle mesh they exchange, the error they throw on
// malformed input, and the all-or-nothing file writing they use.
#pragma once
#include "core/error.hpp"
#include "core/vec.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <system_error>
#include <vector>

namespace weft::io {

// Triangles index positions and run counter-clockwise seen from the front, as in OBJ.
struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> triangles;
};

// A malformed file (or geometry a format cannot hold): the message names the file and the element.
struct FormatError : InputError {
  using InputError::InputError;
};

// Writes `path` through `body` under a temporary name in the same folder, renamed into place once complete,
// so a reader (a Houdini File node on a cache being written) never sees half a file and a failure leaves
// none. I/O failures throw std::system_error; whatever `body` throws propagates.
inline void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& body) {
  static std::atomic<unsigned> serial{0};
  const std::string tmp = path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(serial++);
  const auto failed = [&](int err, const std::string& what) {
    std::remove(tmp.c_str());
    return std::system_error(err, std::generic_category(), what);
  };
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out) throw failed(errno, "cannot create " + tmp);
  try {
    body(out);
  } catch (...) {
    out.close();
    std::remove(tmp.c_str());
    throw;
  }
  out.close();
  if (!out) throw failed(errno ? errno : EIO, "cannot write " + tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw failed(errno, "cannot rename " + tmp + " to " + path);
}

}  // namespace weft::io
