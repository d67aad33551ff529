// OBJ meshes and frame-numbered file names.
#include "io/obj.hpp"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string_view>
#include <system_error>

namespace weft::io {

namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

template <class T>
bool parse(std::string_view s, T& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);  // from_chars takes no plus sign
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

TriMesh read_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::system_error(errno, std::generic_category(), "cannot open " + path);
  TriMesh mesh;
  std::string line;
  size_t number = 0;
  const auto fail = [&](const std::string& what) {
    return FormatError(path + ": line " + std::to_string(number) + ": " + what);
  };
  std::vector<int> face;
  while (std::getline(in, line)) {
    ++number;
    std::string_view text(line);
    text = text.substr(0, text.find('#'));
    const std::vector<std::string_view> words = split(text);
    if (words.empty()) continue;
    if (words[0] == "v") {
      Vec3 p;
      if (words.size() < 4) throw fail("a vertex needs three coordinates");
      for (int c = 0; c < 3; ++c)
        if (!parse(words[size_t(c) + 1], p[c]))
          throw fail("'" + std::string(words[size_t(c) + 1]) + "' is not a number");
      if (mesh.positions.size() == size_t(INT_MAX)) throw fail("too many vertices");
      mesh.positions.push_back(p);
    } else if (words[0] == "f") {
      if (words.size() < 4) throw fail("a face needs at least three vertices");
      face.clear();
      const long defined = long(mesh.positions.size());
      for (size_t k = 1; k < words.size(); ++k) {
        const std::string_view ref = words[k].substr(0, words[k].find('/'));  // the position of v/vt/vn
        long index = 0;
        if (!parse(ref, index) || index == 0) throw fail("'" + std::string(words[k]) + "' is not a vertex reference");
        const long zero_based = index > 0 ? index - 1 : defined + index;  // negative: relative to the end so far
        if (zero_based < 0 || zero_based >= defined)
          throw fail("face vertex " + std::to_string(index) + " is out of range: " + std::to_string(defined) +
                     " vertices are defined before this line");
        face.push_back(int(zero_based));
      }
      for (size_t k = 1; k + 1 < face.size(); ++k) mesh.triangles.push_back({face[0], face[k], face[k + 1]});
    }
  }
  if (in.bad()) throw std::system_error(errno, std::generic_category(), "cannot read " + path);
  return mesh;
}

void write_obj(const TriMesh& mesh, const std::string& path) {
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw FormatError(path + ": vertex " + std::to_string(i) + " is not finite");
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (const int v : mesh.triangles[t])
      if (v < 0 || size_t(v) >= mesh.positions.size())
        throw FormatError(path + ": triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                          ", but there are " + std::to_string(mesh.positions.size()));
  write_file_atomically(path, [&](std::ostream& out) {
    char buf[128];
    for (const Vec3& p : mesh.positions) {
      char* end = buf;
      *end++ = 'v';
      for (int c = 0; c < 3; ++c) {
        *end++ = ' ';
        end = std::to_chars(end, buf + sizeof buf, p[c]).ptr;  // shortest form that reads back exactly
      }
      *end++ = '\n';
      out.write(buf, end - buf);
    }
    for (const auto& t : mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  });
}

std::vector<std::string> expand_frame_pattern(const std::string& pattern, int first, int last) {
  const auto fail = [&](const std::string& what) { return FormatError("frame pattern '" + pattern + "': " + what); };
  if (first > last) throw fail("first frame " + std::to_string(first) + " is after last frame " + std::to_string(last));

  struct Piece {
    std::string text;
    int pad = -1;  // >= 0: the frame number, zero-padded to this width
  };
  std::vector<Piece> pieces(1);
  bool has_frame = false;
  for (size_t i = 0; i < pattern.size();) {
    if (pattern[i] != '$') {
      pieces.back().text += pattern[i++];
      continue;
    }
    const bool braced = i + 1 < pattern.size() && pattern[i + 1] == '{';
    const size_t start = i + (braced ? 2 : 1);
    size_t end = start;
    while (end < pattern.size() && (std::isalnum(static_cast<unsigned char>(pattern[end])) || pattern[end] == '_'))
      ++end;
    const std::string name = pattern.substr(start, end - start);
    if (braced && (end == pattern.size() || pattern[end] != '}')) throw fail("'${' is not closed by '}'");
    int pad = 0;
    if (name.empty() || name[0] != 'F' ||
        (name.size() > 1 && (!parse(std::string_view(name).substr(1), pad) || pad > 32)))
      throw fail("unsupported variable '$" + name + "' (only $F and $F<digits>)");
    pieces.push_back({"", pad});
    pieces.emplace_back();
    has_frame = true;
    i = end + (braced ? 1 : 0);
  }
  if (!has_frame && first != last) throw fail("has no $F, so every frame would get the same name");

  std::vector<std::string> names;
  for (int frame = first;; ++frame) {
    std::string name;
    for (const Piece& p : pieces) {
      if (p.pad < 0) {
        name += p.text;
      } else {
        char buf[48];
        std::snprintf(buf, sizeof buf, "%0*d", p.pad, frame);
        name += buf;
      }
    }
    names.push_back(std::move(name));
    if (frame == last) break;
  }
  return names;
}

}  // namespace weft::io
