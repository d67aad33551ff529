#include "collision/ccd_query_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace weft {

namespace {

[[noreturn]] void fail(const std::string& path, long line, const std::string& msg) {
  throw std::runtime_error(path + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + msg);
}

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

// A numerator must be an integer a double holds exactly, so that num / den is the one rounding.
double parse_numerator(const std::string& f, const std::string& path, long line) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(f.c_str(), &end, 10);
  if (f.empty() || *end != '\0') fail(path, line, "numerator '" + f + "' is not an integer");
  if (errno == ERANGE || v > (1LL << 53) || v < -(1LL << 53))
    fail(path, line, "numerator '" + f + "' is not exactly representable as a double");
  return static_cast<double>(v);
}

// Denominators reach 2^111, beyond any integer type; strtod is exact for powers of two.
double parse_denominator(const std::string& f, const std::string& path, long line) {
  char* end = nullptr;
  const double v = std::strtod(f.c_str(), &end);
  if (f.empty() || *end != '\0') fail(path, line, "denominator '" + f + "' is not a number");
  if (!(v > 0) || !std::isfinite(v)) fail(path, line, "denominator '" + f + "' is not positive and finite");
  return v;
}

// Truth of the Scalable-CCD layout: <case>/queries/<name>.csv -> <case>/mma_bool/<name>_mma_bool.json.
std::string mma_bool_path(const std::string& path) {
  const fs::path p(path);
  const fs::path j = p.parent_path().parent_path() / "mma_bool" / (p.stem().string() + "_mma_bool.json");
  return fs::is_regular_file(j) ? j.string() : std::string();
}

std::vector<uint8_t> read_mma_bool(const std::string& path, long expected) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "cannot open");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail(path, 0, std::string("invalid JSON: ") + e.what());
  }
  if (!j.is_array()) fail(path, 0, "expected an array of booleans");
  if (static_cast<long>(j.size()) != expected)
    fail(path, 0, std::to_string(j.size()) + " labels for " + std::to_string(expected) + " queries");
  std::vector<uint8_t> truth;
  truth.reserve(j.size());
  for (size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_boolean()) fail(path, 0, "label " + std::to_string(i) + " is not a boolean");
    truth.push_back(j[i].get<bool>() ? 1 : 0);
  }
  return truth;
}

}  // namespace

CcdKind ccd_kind_from_path(const std::string& path) {
  const fs::path p(path);
  const std::string stem = p.stem().string();
  const auto suffix = [&](const char* s) {  // name ends in s, not as part of a longer word ("coffee")
    const size_t n = stem.size();
    return n >= 2 && stem.compare(n - 2, 2, s) == 0 &&
           (n == 2 || !std::isalpha(static_cast<unsigned char>(stem[n - 3])));
  };
  if (suffix("vf")) return CcdKind::VertexFace;
  if (suffix("ee")) return CcdKind::EdgeEdge;
  for (fs::path d = p.parent_path(); !d.empty() && d.has_filename(); d = d.parent_path()) {
    if (d.filename() == "vertex-face") return CcdKind::VertexFace;
    if (d.filename() == "edge-edge") return CcdKind::EdgeEdge;
  }
  fail(path, 0,
       "cannot tell vertex-face from edge-edge (expected a vertex-face/ or edge-edge/ folder, or a name ending "
       "in vf or ee)");
}

CcdQueryFile read_ccd_query_file(const std::string& path) {
  CcdQueryFile f;
  f.path = path;
  f.kind = ccd_kind_from_path(path);
  std::ifstream in(path);
  if (!in) fail(path, 0, "cannot open");
  std::string text;
  long line = 0, columns = 0, query_line = 0;
  while (std::getline(in, text)) {
    ++line;
    text = trim(text);
    if (text.empty()) continue;
    std::vector<std::string> fields;
    for (size_t b = 0;;) {
      const size_t e = text.find(',', b);
      fields.push_back(trim(text.substr(b, e == std::string::npos ? std::string::npos : e - b)));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    const long n = static_cast<long>(fields.size());
    if (n != 6 && n != 7) fail(path, line, std::to_string(n) + " columns (expected 6, or 7 with the truth)");
    if (columns == 0) columns = n;
    if (n != columns)
      fail(path, line, std::to_string(n) + " columns where earlier rows have " + std::to_string(columns));
    Vec3 x;
    for (int i = 0; i < 3; ++i)
      x[i] = parse_numerator(fields[2 * i], path, line) / parse_denominator(fields[2 * i + 1], path, line);
    const bool first_row = f.rows.size() % 8 == 0;
    if (first_row) query_line = line;
    f.rows.push_back(x);
    if (n == 7) {
      if (fields[6] != "0" && fields[6] != "1") fail(path, line, "truth '" + fields[6] + "' is not 0 or 1");
      const uint8_t t = fields[6] == "1";
      if (first_row) f.truth.push_back(t);
      else if (f.truth.back() != t)
        fail(path, line, "truth differs from the query's first row (line " + std::to_string(query_line) + ")");
    }
  }
  if (in.bad()) fail(path, line, "read error");
  if (f.rows.size() % 8 != 0)
    fail(path, line, "incomplete query: " + std::to_string(f.rows.size() % 8) + " rows of 8 (query starting at line " +
                         std::to_string(query_line) + ")");
  if (columns == 7) {
    f.truth_source = "csv";
  } else if (const std::string j = mma_bool_path(path); !j.empty()) {
    f.truth = read_mma_bool(j, f.size());
    f.truth_source = j;
  }
  return f;
}

std::vector<std::string> find_ccd_query_files(const std::string& dir) {
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a directory");
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".csv") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace weft
