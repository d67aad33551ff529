// CCD benchmark query files (Wang et al. 2021 and the Scalable-CCD data): each query is 8 rows of exact
// rational coordinates "x_num,x_den,y_num,y_den,z_num,z_den[,truth]". Vertex-face or edge-edge comes from the
// path; truth from the 7th column or, for files without one, from ../mma_bool/<name>_mma_bool.json.
#pragma once
#include "collision/ccd.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace weft {

struct CcdQueryFile {
  std::string path;
  CcdKind kind = CcdKind::VertexFace;
  std::vector<Vec3> rows;      // 8 per query, in the argument order of ccd_vertex_face / ccd_edge_edge
  std::vector<uint8_t> truth;  // 1 when the query collides (zero thickness); empty when no truth is known
  std::string truth_source;    // "csv", the mma_bool json path, or empty
  long size() const { return static_cast<long>(rows.size() / 8); }
};

// A folder named vertex-face / edge-edge, or a file name ending in vf / ee (as in 227vf.csv).
// Throws std::runtime_error when the path says neither.
CcdKind ccd_kind_from_path(const std::string& path);

// Throws std::runtime_error naming the file (and the line) on malformed input.
CcdQueryFile read_ccd_query_file(const std::string& path);

// Every *.csv below dir, recursively, sorted by path. Throws when dir is not a directory.
std::vector<std::string> find_ccd_query_files(const std::string& dir);

}  // namespace weft
