// PLY meshes: a text header declares elements (a count and a list of scalar or list properties); the body
// holds every element's instances in header order, as whitespace-separated text or packed binary.
#include "io/ply.hpp"

#include <cerrno>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <system_error>

namespace weft::io {

namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_scalar_type(std::string_view name, Scalar& t) {
  struct Name {
    std::string_view a, b;
    Scalar t;
  };
  static constexpr Name names[] = {
      {"char", "int8", Scalar::Int8},     {"uchar", "uint8", Scalar::UInt8},       {"short", "int16", Scalar::Int16},
      {"ushort", "uint16", Scalar::UInt16}, {"int", "int32", Scalar::Int32},       {"uint", "uint32", Scalar::UInt32},
      {"float", "float32", Scalar::Float32}, {"double", "float64", Scalar::Float64}};
  for (const Name& n : names)
    if (name == n.a || name == n.b) {
      t = n.t;
      return true;
    }
  return false;
}

size_t width(Scalar t) {
  switch (t) {
    case Scalar::Int8: case Scalar::UInt8: return 1;
    case Scalar::Int16: case Scalar::UInt16: return 2;
    case Scalar::Int32: case Scalar::UInt32: case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 0;
}

bool is_float(Scalar t) { return t == Scalar::Float32 || t == Scalar::Float64; }

// What the reader does with a property's values.
enum class Role { Skip, X, Y, Z, FaceIndices };

struct Property {
  std::string name;
  bool list = false;
  Scalar count_type = Scalar::UInt8;  // lists only
  Scalar type = Scalar::Float32;
  Role role = Role::Skip;
};

struct Element {
  std::string name;
  long count = 0;
  std::vector<Property> properties;
};

// Where a value sits, for error messages (built only when one is thrown).
struct Place {
  const Element& element;
  long index;
  const Property& property;
};

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

template <class T>
bool parse_number(std::string_view s, T& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);  // from_chars takes no plus sign
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool in_range(long long v, Scalar t) {
  switch (t) {
    case Scalar::Int8: return v >= INT8_MIN && v <= INT8_MAX;
    case Scalar::UInt8: return v >= 0 && v <= UINT8_MAX;
    case Scalar::Int16: return v >= INT16_MIN && v <= INT16_MAX;
    case Scalar::UInt16: return v >= 0 && v <= UINT16_MAX;
    case Scalar::Int32: return v >= INT32_MIN && v <= INT32_MAX;
    case Scalar::UInt32: return v >= 0 && v <= UINT32_MAX;
    default: return true;
  }
}

// The body's values, one at a time, in either encoding.
class Body {
 public:
  Body(std::string_view data, bool binary, const std::string& path) : data_(data), binary_(binary), path_(path) {}

  FormatError error(const Place& at, const std::string& what) const {
    return FormatError(path_ + ": element '" + at.element.name + "' " + std::to_string(at.index) + ", property '" +
                       at.property.name + "': " + what);
  }

  // An integer-typed value (list counts and indices).
  long long integer(Scalar t, const Place& at) {
    if (binary_) return static_cast<long long>(raw(t, at));
    const std::string_view word = token(at);
    long long v = 0;
    if (!parse_number(word, v) || !in_range(v, t)) throw error(at, "'" + std::string(word) + "' is not a valid integer of its type");
    return v;
  }

  // Any value, as a double (float properties hold float values, in text too).
  double scalar(Scalar t, const Place& at) {
    if (!is_float(t)) return static_cast<double>(integer(t, at));
    if (binary_) return raw(t, at);
    const std::string_view word = token(at);
    double v = 0;
    if (!parse_number(word, v)) throw error(at, "'" + std::string(word) + "' is not a number");
    return t == Scalar::Float32 ? static_cast<double>(static_cast<float>(v)) : v;
  }

  // Anything left after the last element means the header's counts are wrong.
  void finish() const {
    size_t p = pos_;
    if (!binary_)
      while (p < data_.size() && std::strchr(" \t\r\n", data_[p]) != nullptr) ++p;
    if (p < data_.size())
      throw FormatError(path_ + ": " + std::to_string(data_.size() - p) + " bytes of data after the last element");
  }

 private:
  std::string_view token(const Place& at) {
    while (pos_ < data_.size() && std::strchr(" \t\r\n", data_[pos_]) != nullptr) ++pos_;
    const size_t start = pos_;
    while (pos_ < data_.size() && std::strchr(" \t\r\n", data_[pos_]) == nullptr) ++pos_;
    if (pos_ == start) throw error(at, "the data ends early");
    return data_.substr(start, pos_ - start);
  }

  // A little-endian value, assembled byte by byte (independent of the host's byte order).
  double raw(Scalar t, const Place& at) {
    const size_t w = width(t);
    if (data_.size() - pos_ < w) throw error(at, "the data ends early");
    uint64_t u = 0;
    for (size_t i = 0; i < w; ++i) u |= uint64_t(static_cast<unsigned char>(data_[pos_ + i])) << (8 * i);
    pos_ += w;
    switch (t) {
      case Scalar::Int8: return static_cast<int8_t>(u);
      case Scalar::UInt8: return static_cast<uint8_t>(u);
      case Scalar::Int16: return static_cast<int16_t>(u);
      case Scalar::UInt16: return static_cast<uint16_t>(u);
      case Scalar::Int32: return static_cast<int32_t>(u);
      case Scalar::UInt32: return static_cast<uint32_t>(u);
      case Scalar::Float32: {
        const uint32_t u32 = static_cast<uint32_t>(u);
        float f;
        std::memcpy(&f, &u32, 4);
        return f;
      }
      case Scalar::Float64: {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
      }
    }
    return 0;
  }

  std::string_view data_;
  bool binary_;
  const std::string& path_;
  size_t pos_ = 0;
};

}  // namespace

TriMesh read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::system_error(errno, std::generic_category(), "cannot open " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::system_error(errno, std::generic_category(), "cannot read " + path);

  // Header: one declaration a line, up to end_header.
  std::vector<Element> elements;
  bool binary = false, have_format = false, ended = false;
  size_t pos = 0, line_number = 0;
  while (!ended) {
    if (pos >= bytes.size()) throw FormatError(path + ": the header has no end_header line");
    const size_t eol = bytes.find('\n', pos);
    std::string_view line(bytes.data() + pos, (eol == std::string::npos ? bytes.size() : eol) - pos);
    pos = eol == std::string::npos ? bytes.size() : eol + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const auto fail = [&](const std::string& what) {
      return FormatError(path + ": header line " + std::to_string(line_number) + ": " + what);
    };
    if (line_number == 1) {
      if (line != "ply") throw FormatError(path + ": not a PLY file (no 'ply' line first)");
      continue;
    }
    const std::vector<std::string_view> w = split(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() != 3 || w[2] != "1.0") throw fail("expected 'format <encoding> 1.0'");
      if (w[1] == "binary_big_endian") throw fail("binary big-endian PLY is not supported");
      if (w[1] != "ascii" && w[1] != "binary_little_endian") throw fail("unknown format '" + std::string(w[1]) + "'");
      binary = w[1] == "binary_little_endian";
      have_format = true;
    } else if (w[0] == "element") {
      Element e;
      if (w.size() != 3 || !parse_number(w[2], e.count) || e.count < 0) throw fail("expected 'element <name> <count>'");
      e.name = std::string(w[1]);
      elements.push_back(std::move(e));
    } else if (w[0] == "property") {
      if (elements.empty()) throw fail("a property before any element");
      Property p;
      const bool list = w.size() == 5 && w[1] == "list";
      if (list ? !parse_scalar_type(w[2], p.count_type) || !parse_scalar_type(w[3], p.type)
               : w.size() != 3 || !parse_scalar_type(w[1], p.type))
        throw fail("expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
      if (list && is_float(p.count_type)) throw fail("a list count must have an integer type");
      p.list = list;
      p.name = std::string(w.back());
      elements.back().properties.push_back(std::move(p));
    } else if (w[0] == "end_header") {
      ended = true;
    } else {
      throw fail("unknown keyword '" + std::string(w[0]) + "'");
    }
  }
  if (!have_format) throw FormatError(path + ": the header has no format line");

  // The properties the mesh is made of.
  Element* vertex = nullptr;
  Element* face = nullptr;
  for (Element& e : elements) {
    if ((e.name == "vertex" && vertex) || (e.name == "face" && face))
      throw FormatError(path + ": element '" + e.name + "' is declared twice");
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  if (!vertex) throw FormatError(path + ": no 'vertex' element");
  if (vertex->count > INT_MAX) throw FormatError(path + ": element 'vertex': too many vertices");
  // Every vertex and face takes at least a byte, so a count beyond the file's size is not allocated.
  for (const Element* e : {vertex, face})
    if (e && e->count > long(bytes.size() - pos))
      throw FormatError(path + ": element '" + e->name + "': " + std::to_string(e->count) + " instances cannot fit in " +
                        std::to_string(bytes.size() - pos) + " bytes of data");
  for (const char* axis : {"x", "y", "z"}) {
    Property* found = nullptr;
    for (Property& p : vertex->properties)
      if (p.name == axis) found = &p;
    if (!found || found->list) throw FormatError(path + ": element 'vertex' has no scalar property '" + axis + "'");
    found->role = axis[0] == 'x' ? Role::X : (axis[0] == 'y' ? Role::Y : Role::Z);
  }
  if (face) {
    Property* found = nullptr;
    for (Property& p : face->properties)
      if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) found = &p;
    if (!found) throw FormatError(path + ": element 'face' has no list property 'vertex_indices'");
    if (is_float(found->type)) throw FormatError(path + ": element 'face': vertex indices must have an integer type");
    found->role = Role::FaceIndices;
  }

  // Body: every element in header order.
  TriMesh mesh;
  mesh.positions.resize(static_cast<size_t>(vertex->count));
  if (face) mesh.triangles.resize(static_cast<size_t>(face->count));
  Body body(std::string_view(bytes).substr(pos), binary, path);
  for (const Element& e : elements) {
    for (long k = 0; k < e.count; ++k) {
      for (const Property& p : e.properties) {
        const Place at{e, k, p};
        if (!p.list) {
          const double v = body.scalar(p.type, at);
          if (p.role == Role::X) mesh.positions[size_t(k)].x = v;
          if (p.role == Role::Y) mesh.positions[size_t(k)].y = v;
          if (p.role == Role::Z) mesh.positions[size_t(k)].z = v;
          continue;
        }
        const long long n = body.integer(p.count_type, at);
        if (n < 0) throw body.error(at, "negative list length " + std::to_string(n));
        if (p.role != Role::FaceIndices) {
          for (long long i = 0; i < n; ++i) body.scalar(p.type, at);
          continue;
        }
        if (n != 3) throw body.error(at, "a face of " + std::to_string(n) + " vertices; only triangles are supported");
        for (int c = 0; c < 3; ++c) {
          const long long v = body.integer(p.type, at);
          if (v < 0 || v >= vertex->count)
            throw body.error(at, "vertex index " + std::to_string(v) + " is out of range (" +
                                     std::to_string(vertex->count) + " vertices)");
          mesh.triangles[size_t(k)][size_t(c)] = static_cast<int>(v);
        }
      }
    }
  }
  body.finish();
  return mesh;
}

}  // namespace weft::io
