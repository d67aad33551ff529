// Reading triangle meshes from PLY files (ASCII or binary little-endian).
#pragma once
#include "io/trimesh.hpp"

#include <string>

namespace weft::io {

// The `vertex` element's x, y, z (any numeric type) and the `face` element's vertex_indices (or
// vertex_index) lists, which must all be triangles with indices in range; no face element gives no
// triangles. Other elements and properties are read past. Throws FormatError naming the file and the
// element on malformed or unsupported input (big-endian data, polygons, truncated or trailing data), and
// std::system_error when the file cannot be read.
TriMesh read_ply(const std::string& path);

}  // namespace weft::io
