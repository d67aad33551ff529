// Wavefront OBJ triangle meshes, and Houdini-style frame patterns naming the files of a sequence.
#pragma once
#include "io/trimesh.hpp"

#include <string>
#include <vector>

namespace weft::io {

// Reads `v` positions and `f` faces (v, v/vt, v//vn, v/vt/vn; negative indices count back from the last
// vertex so far); faces of more than three vertices are fanned into triangles. Everything else (vt, vn, l,
// groups, materials) is ignored. Malformed lines throw FormatError naming the file and line.
TriMesh read_obj(const std::string& path);

// Writes positions and triangles, atomically; the positions read back exactly.
void write_obj(const TriMesh& mesh, const std::string& path);

// One file name per frame first..last: `$F` becomes the frame number, `$F4` (or `${F4}`) the frame number
// zero-padded to 4 digits. Other variables, first > last, or several frames without `$F` throw FormatError.
std::vector<std::string> expand_frame_pattern(const std::string& pattern, int first, int last);

}  // namespace weft::io
