// Houdini's JSON geometry schema (shared/specs/houdini-geo.md): the file is a [key, value, ...] list holding
// counts, the vertex -> point table, attributes per element class and the primitives.
#include "io/houdini_geo.hpp"
#include "io/houdini_bjson.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <system_error>
#include <type_traits>

namespace weft::io {

namespace {

using json = nlohmann::json;

struct StorageName {
  Storage storage;
  const char* name;
};
constexpr StorageName kStorageNames[] = {{Storage::Float16, "fpreal16"}, {Storage::Float32, "fpreal32"},
                                         {Storage::Float64, "fpreal64"}, {Storage::Int8, "int8"},
                                         {Storage::Int16, "int16"},      {Storage::Int32, "int32"},
                                         {Storage::Int64, "int64"},      {Storage::UInt8, "uint8"}};

std::string str(size_t n) { return std::to_string(n); }

// ----------------------------------------------------------------------------------------------- reading

class GeoReader {
 public:
  explicit GeoReader(const std::string& path) : path_(path) {}

  Geometry read(const json& root) {
    Geometry g;
    const Fields top = fields(root, "file");
    const size_t npoints = count(top, "pointcount"), nvertices = count(top, "vertexcount");
    const size_t nprimitives = count(top, "primitivecount");

    const std::vector<int> vertex_point = topology(top, nvertices, npoints);
    if (const json* list = find(top, "primitives")) primitives(*list, nvertices, g.primitives);
    if (g.primitives.size() != nprimitives)
      fail("primitives",
           "the list holds " + str(g.primitives.size()) + " primitives, primitivecount is " + str(nprimitives));

    // Primitives hold file vertex numbers until here; vertex attributes follow them into primitive order.
    std::vector<int> vertex_order;
    for (Primitive& p : g.primitives)
      for (int& v : p.points) {
        vertex_order.push_back(v);
        v = vertex_point[v];
      }

    if (const json* a = find(top, "attributes")) {
      const Fields sections = fields(*a, "attributes");
      attributes(find(sections, "pointattributes"), npoints, "point", g.point_attributes, g.warnings);
      attributes(find(sections, "vertexattributes"), nvertices, "vertex", g.vertex_attributes, g.warnings);
      attributes(find(sections, "primitiveattributes"), nprimitives, "primitive", g.primitive_attributes, g.warnings);
      attributes(find(sections, "globalattributes"), 1, "detail", g.detail_attributes, g.warnings);
    }
    for (auto& [name, attr] : g.vertex_attributes) attr = reordered(attr, vertex_order);
    positions(g, npoints);

    if (const json* list = find(top, "pointgroups")) groups(*list, npoints, "point", g.point_groups, g.warnings);
    if (const json* list = find(top, "primitivegroups"))
      groups(*list, nprimitives, "primitive", g.primitive_groups, g.warnings);
    if (const json* list = find(top, "vertexgroups")) groups(*list, nvertices, "vertex", g.vertex_groups, g.warnings);
    for (auto& [name, members] : g.vertex_groups) {  // into primitive order, as vertex attributes
      std::vector<bool> ordered;
      ordered.reserve(vertex_order.size());
      for (const int v : vertex_order) ordered.push_back(members[size_t(v)]);
      members = std::move(ordered);
    }
    if (const json* groups = find(top, "edgegroups"); groups && groups->is_array() && !groups->empty())
      g.warnings.push_back("edgegroups: " + str(groups->size()) + " groups not read");
    std::map<std::string, size_t> opaque;
    for (const Primitive& p : g.primitives)
      if (p.kind == PrimKind::Other) ++opaque[p.type_name];
    for (const auto& [type, n] : opaque)
      g.warnings.push_back(str(n) + " primitives of type '" + type + "' kept opaque (vertices only)");
    return g;
  }

 private:
  using Fields = std::map<std::string, const json*>;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw FormatError(path_ + ": " + where + ": " + what);
  }

  // Houdini stores most records as flat [key, value, ...] lists; a few (options) as JSON maps.
  Fields fields(const json& v, const std::string& where) const {
    Fields f;
    if (v.is_object()) {
      for (auto it = v.begin(); it != v.end(); ++it) f[it.key()] = &it.value();
      return f;
    }
    if (!v.is_array() || v.size() % 2 != 0) fail(where, "expected a [key, value, ...] list");
    for (size_t i = 0; i < v.size(); i += 2) {
      if (!v[i].is_string()) fail(where, "key " + str(i / 2) + " is not a string");
      f[v[i].get<std::string>()] = &v[i + 1];
    }
    return f;
  }
  // Binary files may use short key names (s_v for startvertex...).
  static const json* find(const Fields& f, const char* key, const char* short_key = nullptr) {
    auto it = f.find(key);
    if (it == f.end() && short_key) it = f.find(short_key);
    return it == f.end() ? nullptr : it->second;
  }
  const json& need(const Fields& f, const std::string& where, const char* key, const char* short_key = nullptr) const {
    if (const json* v = find(f, key, short_key)) return *v;
    fail(where, std::string("missing '") + key + "'");
  }
  const json& array(const json& v, const std::string& where, const std::string& what) const {
    if (!v.is_array()) fail(where, what + " is not an array");
    return v;
  }
  int64_t integer(const json& v, const std::string& where, const std::string& what) const {
    if (v.is_number_integer()) return v.get<int64_t>();
    if (v.is_number_float()) {
      const double d = v.get<double>();
      if (d == std::floor(d) && std::abs(d) < 9.2e18) return int64_t(d);
    }
    fail(where, what + " is not an integer");
  }
  double real(const json& v, const std::string& where, const std::string& what) const {
    if (!v.is_number()) fail(where, what + " is not a number");
    return v.get<double>();
  }
  std::string text(const json& v, const std::string& where, const std::string& what) const {
    if (!v.is_string()) fail(where, what + " is not a string");
    return v.get<std::string>();
  }
  size_t count(const Fields& top, const char* key) const {
    const int64_t n = integer(need(top, "file header", key), "file header", key);
    if (n < 0 || n > INT_MAX) fail("file header", std::string(key) + " " + std::to_string(n) + " is out of range");
    return size_t(n);
  }

  std::vector<int> topology(const Fields& top, size_t nvertices, size_t npoints) const {
    std::vector<int> vertex_point;
    const json* t = find(top, "topology");
    const json* ref = t ? find(fields(*t, "topology"), "pointref") : nullptr;
    if (ref) {
      const json& indices = array(need(fields(*ref, "topology"), "topology", "indices"), "topology", "indices");
      vertex_point.reserve(indices.size());
      for (size_t v = 0; v < indices.size(); ++v) {
        const int64_t p = integer(indices[v], "topology", "vertex " + str(v));
        if (p < 0 || size_t(p) >= npoints)
          fail("topology",
               "vertex " + str(v) + " refers to point " + std::to_string(p) + ", but pointcount is " + str(npoints));
        vertex_point.push_back(int(p));
      }
    }
    if (vertex_point.size() != nvertices)
      fail("topology", "holds " + str(vertex_point.size()) + " vertices, vertexcount is " + str(nvertices));
    return vertex_point;
  }

  // ---- attributes

  template <class T>
  T element(const json& v, size_t e, const std::string& where) const {
    if constexpr (std::is_same_v<T, double>)
      return real(v, where, "element " + str(e));
    else
      return integer(v, where, "element " + str(e));
  }

  // The values of `count` tuples of `size`, in any of the three layouts Houdini writes.
  template <class T>
  std::vector<T> values(const Fields& f, size_t count, int size, const std::string& where) const {
    const size_t k = size_t(size);
    std::vector<T> out;
    if (const json* t = find(f, "tuples")) {
      const json& tuples = array(*t, where, "tuples");
      if (tuples.size() != count) fail(where, "has " + str(tuples.size()) + " tuples, expected " + str(count));
      out.resize(count * k);
      for (size_t e = 0; e < count; ++e) {
        const json& tuple = tuples[e];
        if (!tuple.is_array()) {
          if (k != 1) fail(where, "tuple " + str(e) + " is not an array");
          out[e] = element<T>(tuple, e, where);
        } else {
          if (tuple.size() != k)
            fail(where, "tuple " + str(e) + " has " + str(tuple.size()) + " values, expected " + str(k));
          for (size_t c = 0; c < k; ++c) out[e * k + c] = element<T>(tuple[c], e, where);
        }
      }
    } else if (const json* a = find(f, "arrays")) {  // one array per component
      const json& arrays = array(*a, where, "arrays");
      if (arrays.size() != k) fail(where, "has " + str(arrays.size()) + " component arrays, expected " + str(k));
      out.resize(count * k);
      for (size_t c = 0; c < k; ++c) {
        const json& component = array(arrays[c], where, "component array " + str(c));
        if (component.size() != count)
          fail(where,
               "component array " + str(c) + " has " + str(component.size()) + " values, expected " + str(count));
        for (size_t e = 0; e < count; ++e) out[e * k + c] = element<T>(component[e], e, where);
      }
    } else if (const json* r = find(f, "rawpagedata")) {
      out = paged<T>(f, array(*r, where, "rawpagedata"), count, k, where);
    } else {
      fail(where, "holds no tuples, arrays or rawpagedata");
    }
    return out;
  }

  // Pages of `pagesize` elements; within a page each packed subvector (`packing`, default the whole tuple)
  // stores its components element-major, or a single tuple when its constantpageflags entry says so.
  template <class T>
  std::vector<T> paged(const Fields& f, const json& raw, size_t count, size_t k, const std::string& where) const {
    const int64_t pagesize = integer(need(f, where, "pagesize"), where, "pagesize");
    if (pagesize <= 0) fail(where, "pagesize " + std::to_string(pagesize) + " is not positive");
    std::vector<size_t> packing;
    if (const json* p = find(f, "packing")) {
      for (const json& n : array(*p, where, "packing")) {
        const int64_t v = integer(n, where, "packing");
        if (v <= 0) fail(where, "packing holds " + std::to_string(v));
        packing.push_back(size_t(v));
      }
    } else {
      packing.push_back(k);
    }
    size_t packed = 0;
    for (size_t v : packing) packed += v;
    if (packed != k) fail(where, "packing adds up to " + str(packed) + ", the tuple size is " + str(k));
    const json* flags = find(f, "constantpageflags");
    if (flags && (!flags->is_array() || flags->size() > packing.size()))
      fail(where, "constantpageflags does not match the packing");
    const auto constant = [&](size_t subvector, size_t page) {
      if (!flags || subvector >= flags->size()) return false;
      const json& pages = (*flags)[subvector];
      return pages.is_array() && page < pages.size() &&
             (pages[page].is_boolean() ? pages[page].get<bool>() : pages[page] != 0);
    };

    std::vector<T> out(count * k);
    size_t at = 0;
    const size_t ps = size_t(pagesize);
    for (size_t page = 0; page * ps < count; ++page) {
      const size_t first = page * ps, m = std::min(ps, count - first);
      size_t component = 0;
      for (size_t sv = 0; sv < packing.size(); ++sv) {
        const size_t width = packing[sv], stored = constant(sv, page) ? width : m * width;
        if (raw.size() - at < stored)
          fail(where, "rawpagedata holds " + str(raw.size()) + " values, fewer than its pages need");
        for (size_t i = 0; i < m; ++i)
          for (size_t c = 0; c < width; ++c) {
            const size_t src = at + (stored == width ? c : i * width + c);
            out[(first + i) * k + component + c] = element<T>(raw[src], first + i, where);
          }
        at += stored;
        component += width;
      }
    }
    if (at != raw.size()) fail(where, "rawpagedata holds " + str(raw.size()) + " values, its pages need " + str(at));
    return out;
  }

  int tuple_size(const Fields& data, const Fields& values, const std::string& where) const {
    const json* s = find(data, "size");
    if (!s) s = find(values, "size");
    const int64_t k = s ? integer(*s, where, "size") : 1;
    if (k < 1 || k > 4096) fail(where, "tuple size " + std::to_string(k) + " is out of range");
    return int(k);
  }

  Attribute numeric(const Fields& data, size_t count, const std::string& where) const {
    const Fields vals = fields(need(data, where, "values"), where);
    const json* s = find(vals, "storage");
    if (!s) s = find(data, "storage");
    if (!s) fail(where, "missing 'storage'");
    const std::string name = text(*s, where, "storage");
    const auto known = std::find_if(std::begin(kStorageNames), std::end(kStorageNames),
                                    [&](const StorageName& n) { return name == n.name; });
    if (known == std::end(kStorageNames)) fail(where, "unknown storage '" + name + "'");
    Attribute a;
    a.storage = known->storage;
    a.size = tuple_size(data, vals, where);
    if (is_int(a.storage)) {
      a.ints = values<int64_t>(vals, count, a.size, where);
      return a;
    }
    a.floats = values<double>(vals, count, a.size, where);
    if (a.storage == Storage::Float32)
      for (double& x : a.floats) x = double(float(x));
    return a;
  }

  Attribute strings(const Fields& data, size_t count, const std::string& where) const {
    std::vector<std::string> table;
    for (const json& s : array(need(data, where, "strings"), where, "strings"))
      table.push_back(text(s, where, "a string"));
    const Fields idx = fields(need(data, where, "indices"), where);
    Attribute a;
    a.storage = Storage::String;
    a.size = tuple_size(data, idx, where);
    const std::vector<int64_t> ids = values<int64_t>(idx, count, a.size, where);
    a.strings.reserve(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] >= int64_t(table.size()))
        fail(where, "element " + str(i / size_t(a.size)) + " uses string " + std::to_string(ids[i]) +
                        ", the table holds " + str(table.size()));
      a.strings.push_back(ids[i] < 0 ? std::string() : table[size_t(ids[i])]);  // -1: no string
    }
    return a;
  }

  void attributes(const json* list, size_t count, const std::string& cls, AttributeMap& out,
                  std::vector<std::string>& warnings) const {
    if (!list) return;
    const json& entries = array(*list, cls + " attributes", "the list");
    for (size_t i = 0; i < entries.size(); ++i) {
      std::string where = cls + " attribute " + str(i);
      const json& entry = entries[i];
      if (!entry.is_array() || entry.size() != 2) fail(where, "expected [definition, values]");
      const Fields def = fields(entry[0], where);
      const std::string name = text(need(def, where, "name"), where, "name");
      where = cls + " attribute '" + name + "'";
      const std::string type = text(need(def, where, "type"), where, "type");
      const Fields data = fields(entry[1], where);
      Attribute a;
      if (type == "numeric") {
        a = numeric(data, count, where);
      } else if (type == "string") {
        a = strings(data, count, where);
      } else {
        warnings.push_back(where + ": type '" + type + "' is not supported; skipped");
        continue;
      }
      if (const json* options = find(def, "options"); options && options->is_object()) {
        const auto t = options->find("type");
        if (t != options->end() && t->is_object() && t->contains("value") && (*t)["value"].is_string())
          a.qualifier = (*t)["value"].get<std::string>();
      }
      out[name] = std::move(a);
    }
  }

  // ---- groups

  bool flag(const json& v, const std::string& where) const {
    return v.is_boolean() ? v.get<bool>() : integer(v, where, "a membership flag") != 0;
  }

  // [[name], [selection, [unordered, [boolRLE | i8, [...]]]]], or an ordered list of element numbers.
  void groups(const json& list, size_t count, const std::string& cls, GroupMap& out,
              std::vector<std::string>& warnings) const {
    const std::string elements = cls == "vertex" ? "vertices" : cls + "s";
    const json& entries = array(list, cls + " groups", "the list");
    for (size_t i = 0; i < entries.size(); ++i) {
      std::string where = cls + " group " + str(i);
      const json& entry = entries[i];
      if (!entry.is_array() || entry.size() != 2) fail(where, "expected [definition, selection]");
      const std::string name = text(need(fields(entry[0], where), where, "name"), where, "name");
      where = cls + " group '" + name + "'";
      const Fields selection = fields(need(fields(entry[1], where), where, "selection"), where);
      std::vector<bool> members(count, false);
      if (const json* unordered = find(selection, "unordered")) {
        const Fields encoding = fields(*unordered, where);
        if (const json* r = find(encoding, "boolRLE")) {  // (count, value) pairs
          const json& runs = array(*r, where, "boolRLE");
          if (runs.size() % 2 != 0) fail(where, "boolRLE is not a list of (count, value) pairs");
          size_t at = 0;
          for (size_t k = 0; k < runs.size(); k += 2) {
            const int64_t n = integer(runs[k], where, "a boolRLE count");
            if (n < 0 || uint64_t(n) > count - at)
              fail(where, "boolRLE describes more than the " + str(count) + " " + elements);
            std::fill_n(members.begin() + std::ptrdiff_t(at), size_t(n), flag(runs[k + 1], where));
            at += size_t(n);
          }
          if (at != count) fail(where, "boolRLE describes " + str(at) + " " + elements + ", there are " + str(count));
        } else if (const json* b = find(encoding, "i8")) {  // one flag per element
          const json& bits = array(*b, where, "i8");
          if (bits.size() != count)
            fail(where, "i8 holds " + str(bits.size()) + " flags, there are " + str(count) + " " + elements);
          for (size_t k = 0; k < count; ++k) members[k] = flag(bits[k], where);
        } else {
          fail(where, "unordered selection in an unknown encoding (expected boolRLE or i8)");
        }
      } else if (const json* ordered = find(selection, "ordered")) {
        for (const json& x : array(*ordered, where, "ordered")) {
          const int64_t e = integer(x, where, "an element number");
          if (e < 0 || uint64_t(e) >= count)
            fail(where, "element " + std::to_string(e) + " is out of range, there are " + str(count) + " " + elements);
          members[size_t(e)] = true;
        }
        warnings.push_back(where + ": ordered; read as plain membership (its order is not kept)");
      } else {
        fail(where, "the selection is neither unordered nor ordered");
      }
      out[name] = std::move(members);
    }
  }

  static Attribute reordered(const Attribute& a, const std::vector<int>& order) {
    Attribute r = a;
    const size_t k = size_t(a.size);
    r.floats.clear();
    r.ints.clear();
    r.strings.clear();
    for (int v : order)
      for (size_t c = 0; c < k; ++c) {
        const size_t i = size_t(v) * k + c;
        if (is_float(a.storage))
          r.floats.push_back(a.floats[i]);
        else if (is_int(a.storage))
          r.ints.push_back(a.ints[i]);
        else
          r.strings.push_back(a.strings[i]);
      }
    return r;
  }

  void positions(Geometry& g, size_t npoints) const {
    const auto it = g.point_attributes.find("P");
    if (it == g.point_attributes.end()) {
      if (npoints > 0) fail("point attribute 'P'", "missing: the file has no positions");
      return;
    }
    const Attribute& P = it->second;
    if (!is_float(P.storage)) fail("point attribute 'P'", "is not a float attribute");
    if (P.size != 3 && P.size != 4)  // 4: homogeneous positions of very old files
      fail("point attribute 'P'", "has tuple size " + std::to_string(P.size) + ", expected 3");
    g.points.resize(npoints);
    for (size_t p = 0; p < npoints; ++p) g.points[p] = {P.number(p, 0), P.number(p, 1), P.number(p, 2)};
    g.position_storage = P.storage;
    g.point_attributes.erase(it);
  }

  // ---- primitives (holding file vertex numbers)

  std::vector<int> vertex_list(const json& v, size_t nvertices, const std::string& where) const {
    std::vector<int> list;
    const auto add = [&](const json& x) {
      const int64_t n = integer(x, where, "a vertex");
      if (n < 0 || size_t(n) >= nvertices)
        fail(where, "vertex " + std::to_string(n) + " is out of range, vertexcount is " + str(nvertices));
      list.push_back(int(n));
    };
    if (v.is_array()) {
      for (const json& x : v) add(x);
    } else {
      add(v);
    }
    return list;
  }

  Primitive single(const std::string& type, const Fields& f, size_t nvertices, const std::string& where) const {
    Primitive p;
    if (type == "Poly") {
      const json* closed = find(f, "closed");
      if (closed && !closed->is_boolean()) fail(where, "'closed' is not a bool");
      p.kind = !closed || closed->get<bool>() ? PrimKind::Polygon : PrimKind::Polyline;
      p.points = vertex_list(need(f, where, "vertex"), nvertices, where);
    } else if (type == "Sphere") {
      p.kind = PrimKind::Sphere;
      p.points = vertex_list(need(f, where, "vertex"), nvertices, where);
      if (p.points.size() != 1) fail(where, "a Sphere has one vertex, this one " + str(p.points.size()));
      if (const json* t = find(f, "transform")) {
        const json& m = array(*t, where, "transform");
        if (m.size() != 9) fail(where, "transform has " + str(m.size()) + " values, expected 9");
        for (size_t i = 0; i < 9; ++i) p.transform[i] = real(m[i], where, "transform");
      }
    } else {
      const json* v = find(f, "vertex");
      if (!v)
        fail(where, "type '" + type + "' has no vertex list this reader understands" +
                        (type.rfind("Packed", 0) == 0 ? "; unpack it in Houdini first" : ""));
      p.kind = PrimKind::Other;
      p.type_name = type;
      p.points = vertex_list(*v, nvertices, where);
    }
    return p;
  }

  // Houdini 18+ runs: consecutive vertices from startvertex, counts per primitive plain or run-length coded.
  void polygon_run(const std::string& type, const Fields& f, size_t nvertices, std::vector<Primitive>& out) const {
    const std::string where = "primitive " + str(out.size());
    Primitive proto;
    if (type == "Polygon_run" || type == "p_r") {
      proto.kind = PrimKind::Polygon;
    } else if (type == "PolygonCurve_run" || type == "c_r") {
      proto.kind = PrimKind::Polyline;
    } else {
      proto.kind = PrimKind::Other;
      proto.type_name = type == "t_r" ? "Tetrahedron" : type.substr(0, type.size() - 4);
    }
    const int64_t start = integer(need(f, where, "startvertex", "s_v"), where, "startvertex");
    const int64_t n = integer(need(f, where, "nprimitives", "n_p"), where, "nprimitives");
    if (n < 0 || size_t(n) > nvertices + 1) fail(where, "nprimitives " + std::to_string(n) + " is out of range");
    std::vector<int64_t> counts;
    if (const json* rle = find(f, "nvertices_rle", "r_v")) {
      const json& pairs = array(*rle, where, "nvertices_rle");
      if (pairs.size() % 2 != 0) fail(where, "nvertices_rle is not a list of (count, repeat) pairs");
      for (size_t i = 0; i < pairs.size(); i += 2) {
        const int64_t c = integer(pairs[i], where, "nvertices_rle"),
                      repeat = integer(pairs[i + 1], where, "nvertices_rle");
        if (repeat < 0 || counts.size() + size_t(repeat) > size_t(n))
          fail(where, "nvertices_rle describes more than nprimitives " + std::to_string(n) + " primitives");
        counts.insert(counts.end(), size_t(repeat), c);
      }
    } else if (const json* nv = find(f, "nvertices", "n_v")) {
      for (const json& c : array(*nv, where, "nvertices")) counts.push_back(integer(c, where, "nvertices"));
    } else if (proto.type_name == "Tetrahedron") {
      counts.assign(size_t(n), 4);
    } else {
      fail(where, "run of type '" + type + "' has no vertex counts");
    }
    if (counts.size() != size_t(n))
      fail(where, "nprimitives is " + std::to_string(n) + " but the vertex counts describe " + str(counts.size()));
    int64_t v = start;
    for (const int64_t c : counts) {
      const std::string at = "primitive " + str(out.size());
      if (c < 0 || v < 0 || size_t(v + c) > nvertices)
        fail(at, "vertices " + std::to_string(v) + " to " + std::to_string(v + c - 1) +
                     " are out of range, vertexcount is " + str(nvertices));
      Primitive p = proto;
      for (int64_t i = 0; i < c; ++i) p.points.push_back(int(v++));
      out.push_back(std::move(p));
    }
  }

  // The older run form: fields shared by the run, then one list of the varying fields per primitive.
  void generic_run(const Fields& def, const json& data, size_t nvertices, std::vector<Primitive>& out) const {
    const std::string where = "primitive " + str(out.size());
    const std::string runtype = text(need(def, where, "runtype"), where, "runtype");
    const json& varying = array(need(def, where, "varyingfields"), where, "varyingfields");
    const json* uniform_fields = find(def, "uniformfields");
    const Fields uniform = uniform_fields ? fields(*uniform_fields, where) : Fields{};
    for (const json& item : array(data, where, "the run")) {
      const std::string at = "primitive " + str(out.size());
      if (!item.is_array() || item.size() != varying.size())
        fail(at, "expected " + str(varying.size()) + " varying fields");
      Fields f = uniform;
      for (size_t i = 0; i < varying.size(); ++i) f[text(varying[i], at, "a varying field name")] = &item[i];
      out.push_back(single(runtype, f, nvertices, at));
    }
  }

  void primitives(const json& list, size_t nvertices, std::vector<Primitive>& out) const {
    for (const json& entry : array(list, "primitives", "the list")) {
      const std::string where = "primitive " + str(out.size());
      if (!entry.is_array() || entry.size() != 2) fail(where, "expected [definition, data]");
      const Fields def = fields(entry[0], where);
      const std::string type = text(need(def, where, "type"), where, "type");
      if (type == "run") {
        generic_run(def, entry[1], nvertices, out);
      } else if (type.size() > 4 && type.compare(type.size() - 4, 4, "_run") == 0) {
        polygon_run(type, fields(entry[1], where), nvertices, out);
      } else if (type == "p_r" || type == "c_r" || type == "t_r") {
        polygon_run(type, fields(entry[1], where), nvertices, out);
      } else {
        out.push_back(single(type, fields(entry[1], where), nvertices, where));
      }
    }
  }

  std::string path_;
};

// Why `bytes` cannot be JSON geometry text, or empty when they may be.
std::string describe_start(const std::string& bytes) {
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && bytes[first] == '[') return {};
  if (bytes.size() >= 2 && uint8_t(bytes[0]) == 0x1f && uint8_t(bytes[1]) == 0x8b)
    return "gzip-compressed; save it uncompressed as .geo or .bgeo";
  if (bytes.compare(0, 9, "PGEOMETRY") == 0) return "the classic (pre-Houdini 12) format; save it from a newer Houdini";
  if (!bytes.empty() && uint8_t(bytes[0]) == 0x7f) return "byte 1: 0x7f without the binary JSON magic 'NSJb'";
  return "not Houdini JSON geometry (expected '[' or the binary magic 0x7f 'NSJb'; .bgeo.sc is not supported)";
}

// ----------------------------------------------------------------------------------------------- writing

const char* storage_name(Storage s) {
  if (s == Storage::Float16) return "fpreal32";  // halves widen losslessly; no half encoder needed
  for (const StorageName& n : kStorageNames)
    if (n.storage == s) return n.name;
  return "int32";  // string indices
}

JsonWriter::Packing packing(Storage s) {
  switch (s) {
    case Storage::Float64:
      return JsonWriter::Packing::Real64;
    case Storage::Int8:
      return JsonWriter::Packing::Int8;
    case Storage::Int16:
      return JsonWriter::Packing::Int16;
    case Storage::Int64:
      return JsonWriter::Packing::Int64;
    case Storage::UInt8:
      return JsonWriter::Packing::UInt8;
    case Storage::Int32:
    case Storage::String:
      return JsonWriter::Packing::Int32;
    default:
      return JsonWriter::Packing::Real32;
  }
}

bool fits(int64_t v, Storage s) {
  switch (s) {
    case Storage::Int8:
      return v >= INT8_MIN && v <= INT8_MAX;
    case Storage::Int16:
      return v >= INT16_MIN && v <= INT16_MAX;
    case Storage::Int32:
      return v >= INT32_MIN && v <= INT32_MAX;
    case Storage::UInt8:
      return v >= 0 && v <= UINT8_MAX;
    default:
      return true;
  }
}

class GeoWriter {
 public:
  GeoWriter(const Geometry& g, const std::string& path) : g_(g), path_(path) {}

  // Everything the file could not hold is refused before the file is opened.
  void validate() const {
    if (!is_float(g_.position_storage)) fail("point attribute 'P'", "position_storage is not a float storage");
    for (size_t p = 0; p < g_.points.size(); ++p)
      if (!std::isfinite(g_.points[p].x) || !std::isfinite(g_.points[p].y) || !std::isfinite(g_.points[p].z))
        fail("point " + str(p), "P is not finite");
    for (size_t i = 0; i < g_.primitives.size(); ++i) {
      const Primitive& p = g_.primitives[i];
      const std::string where = "primitive " + str(i);
      if (p.kind == PrimKind::Other)
        fail(where, "type '" + p.type_name + "' cannot be written (only polygons, polylines and spheres)");
      if (p.points.empty() || (p.kind == PrimKind::Sphere && p.points.size() != 1))
        fail(where, "has " + str(p.points.size()) + " vertices");
      for (const int pt : p.points)
        if (pt < 0 || size_t(pt) >= g_.points.size())
          fail(where, "refers to point " + std::to_string(pt) + ", but there are " + str(g_.points.size()) + " points");
    }
    if (g_.point_attributes.count("P")) fail("point attribute 'P'", "positions belong in Geometry::points");
    check(g_.point_attributes, g_.points.size(), "point");
    check(g_.vertex_attributes, g_.vertex_count(), "vertex");
    check(g_.primitive_attributes, g_.primitives.size(), "primitive");
    check(g_.detail_attributes, 1, "detail");
    check_groups(g_.point_groups, g_.points.size(), "point");
    check_groups(g_.vertex_groups, g_.vertex_count(), "vertex");
    check_groups(g_.primitive_groups, g_.primitives.size(), "primitive");
  }

  void emit(JsonWriter& w) const {
    w.begin_array();
    key(w, "fileversion");
    w.string("20.5.0");
    key(w, "hasindex");
    w.boolean(false);
    key(w, "pointcount");
    w.integer(int64_t(g_.points.size()));
    key(w, "vertexcount");
    w.integer(int64_t(g_.vertex_count()));
    key(w, "primitivecount");
    w.integer(int64_t(g_.primitives.size()));

    std::vector<int64_t> vertex_point;
    for (const Primitive& p : g_.primitives) vertex_point.insert(vertex_point.end(), p.points.begin(), p.points.end());
    key(w, "topology");
    w.begin_array();
    key(w, "pointref");
    w.begin_array();
    key(w, "indices");
    w.numbers(vertex_point.data(), vertex_point.size(), JsonWriter::Packing::Int32);
    w.end_array();
    w.end_array();

    key(w, "attributes");
    w.begin_array();
    section(w, "vertexattributes", g_.vertex_attributes);
    AttributeMap points = g_.point_attributes;
    Attribute& P = points["P"];
    P.storage = g_.position_storage;
    P.size = 3;
    P.qualifier = "point";
    for (const Vec3& x : g_.points) P.floats.insert(P.floats.end(), {x.x, x.y, x.z});
    section(w, "pointattributes", points);
    section(w, "primitiveattributes", g_.primitive_attributes);
    section(w, "globalattributes", g_.detail_attributes);
    w.end_array();

    key(w, "primitives");
    w.begin_array();
    size_t vertex = 0;
    for (size_t i = 0; i < g_.primitives.size();) {
      const Primitive& p = g_.primitives[i];
      if (p.kind == PrimKind::Sphere) {
        sphere(w, p, vertex++);
        ++i;
        continue;
      }
      size_t end = i;  // a run of primitives of one kind
      while (end < g_.primitives.size() && g_.primitives[end].kind == p.kind) ++end;
      vertex += run(w, i, end, vertex);
      i = end;
    }
    w.end_array();
    groups(w, "pointgroups", g_.point_groups);
    groups(w, "primitivegroups", g_.primitive_groups);
    groups(w, "vertexgroups", g_.vertex_groups);
    w.end_array();
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw FormatError(path_ + ": " + where + ": " + what);
  }

  static bool identifier(const std::string& name) {
    return !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
           std::all_of(name.begin(), name.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  }

  void check_groups(const GroupMap& groups, size_t count, const std::string& cls) const {
    for (const auto& [name, members] : groups) {
      const std::string where = cls + " group '" + name + "'";
      if (!identifier(name)) fail(where, "is not a valid group name");
      if (members.size() != count)
        fail(where, "holds " + str(members.size()) + " flags, expected " + str(count) + " (one per " + cls + ")");
    }
  }

  void check(const AttributeMap& attrs, size_t count, const std::string& cls) const {
    for (const auto& [name, a] : attrs) {
      const std::string where = cls + " attribute '" + name + "'";
      if (!identifier(name)) fail(where, "is not a valid attribute name");
      if (a.size < 1) fail(where, "tuple size " + std::to_string(a.size) + " is not positive");
      const size_t held = is_float(a.storage) ? a.floats.size() : is_int(a.storage) ? a.ints.size() : a.strings.size();
      if (held != count * size_t(a.size))
        fail(where, "holds " + str(held) + " values, expected " + str(count) + " " + cls + (count == 1 ? "" : "s") +
                        " x " + std::to_string(a.size));
      for (size_t i = 0; i < a.floats.size() && is_float(a.storage); ++i)
        if (!std::isfinite(a.floats[i])) fail(where, "element " + str(i / size_t(a.size)) + " is not finite");
      for (size_t i = 0; i < a.ints.size() && is_int(a.storage); ++i)
        if (!fits(a.ints[i], a.storage))
          fail(where, "element " + str(i / size_t(a.size)) + " holds " + std::to_string(a.ints[i]) + ", beyond " +
                          storage_name(a.storage));
    }
  }

  static void key(JsonWriter& w, const char* k) { w.string(k); }

  // Text files keep Houdini's readable layouts; binary ones one flat page run (default packing, no
  // constant pages), as Houdini writes them.
  template <class T>
  static void layout(JsonWriter& w, const std::vector<T>& v, int size, JsonWriter::Packing p) {
    if (w.format() == JsonWriter::Format::Binary) {
      key(w, "pagesize");
      w.integer(1024);
      key(w, "rawpagedata");
      w.numbers(v.data(), v.size(), p);
    } else if (size == 1) {
      key(w, "arrays");
      w.begin_array();
      w.numbers(v.data(), v.size(), p);
      w.end_array();
    } else {
      key(w, "tuples");
      w.begin_array();
      for (size_t i = 0; i < v.size(); i += size_t(size)) w.numbers(v.data() + i, size_t(size), p);
      w.end_array();
    }
  }

  static void attribute(JsonWriter& w, const std::string& name, const Attribute& a) {
    const bool text = a.storage == Storage::String;
    w.begin_array();
    w.begin_array();
    for (const char* k : {"scope", "public", "type", text ? "string" : "numeric", "name"}) w.string(k);
    w.string(name);
    key(w, "options");
    w.begin_map();
    if (!a.qualifier.empty()) {
      key(w, "type");
      w.begin_map();
      for (const char* k : {"type", "string", "value"}) w.string(k);
      w.string(a.qualifier);
      w.end_map();
    }
    w.end_map();
    w.end_array();

    w.begin_array();
    key(w, "size");
    w.integer(a.size);
    key(w, "storage");
    w.string(storage_name(a.storage));
    if (text) {
      std::vector<std::string> table;
      std::map<std::string, int64_t> index;
      std::vector<int64_t> ids;
      for (const std::string& s : a.strings) {
        if (s.empty()) {
          ids.push_back(-1);  // Houdini's "no string"
          continue;
        }
        const auto [it, added] = index.emplace(s, int64_t(table.size()));
        if (added) table.push_back(s);
        ids.push_back(it->second);
      }
      key(w, "strings");
      w.begin_array();
      for (const std::string& s : table) w.string(s);
      w.end_array();
      key(w, "indices");
      w.begin_array();
      key(w, "size");
      w.integer(a.size);
      key(w, "storage");
      w.string("int32");
      layout(w, ids, a.size, JsonWriter::Packing::Int32);
      w.end_array();
    } else {
      key(w, "values");
      w.begin_array();
      key(w, "size");
      w.integer(a.size);
      key(w, "storage");
      w.string(storage_name(a.storage));
      if (is_float(a.storage))
        layout(w, a.floats, a.size, packing(a.storage));
      else
        layout(w, a.ints, a.size, packing(a.storage));
      w.end_array();
    }
    w.end_array();
    w.end_array();
  }

  static void section(JsonWriter& w, const char* name, const AttributeMap& attrs) {
    if (attrs.empty()) return;
    key(w, name);
    w.begin_array();
    for (const auto& [n, a] : attrs) attribute(w, n, a);
    w.end_array();
  }

  // As Houdini writes them: the name, then the membership run-length coded as (count, value) pairs.
  static void groups(JsonWriter& w, const char* name, const GroupMap& groups) {
    if (groups.empty()) return;
    key(w, name);
    w.begin_array();
    for (const auto& [n, members] : groups) {
      w.begin_array();
      w.begin_array();
      key(w, "name");
      w.string(n);
      w.end_array();
      w.begin_array();
      key(w, "selection");
      w.begin_array();
      key(w, "unordered");
      w.begin_array();
      key(w, "boolRLE");
      w.begin_array();
      for (size_t i = 0; i < members.size();) {
        size_t j = i;
        while (j < members.size() && members[j] == members[i]) ++j;
        w.integer(int64_t(j - i));
        w.boolean(members[i]);
        i = j;
      }
      w.end_array();
      w.end_array();
      w.end_array();
      w.end_array();
      w.end_array();
    }
    w.end_array();
  }

  static void sphere(JsonWriter& w, const Primitive& p, size_t vertex) {
    w.begin_array();
    w.begin_array();
    key(w, "type");
    w.string("Sphere");
    w.end_array();
    w.begin_array();
    key(w, "vertex");
    w.integer(int64_t(vertex));
    key(w, "transform");
    w.numbers(p.transform.data(), 9, JsonWriter::Packing::Real64);
    w.end_array();
    w.end_array();
  }

  // Primitives [begin, end) of one kind as a Polygon_run / PolygonCurve_run; returns the vertices used.
  size_t run(JsonWriter& w, size_t begin, size_t end, size_t start) const {
    std::vector<int64_t> rle;  // (vertex count, repeat) pairs
    size_t vertices = 0;
    for (size_t i = begin; i < end; ++i) {
      const int64_t n = int64_t(g_.primitives[i].points.size());
      vertices += size_t(n);
      if (!rle.empty() && rle[rle.size() - 2] == n)
        ++rle.back();
      else
        rle.insert(rle.end(), {n, 1});
    }
    w.begin_array();
    w.begin_array();
    key(w, "type");
    w.string(g_.primitives[begin].kind == PrimKind::Polygon ? "Polygon_run" : "PolygonCurve_run");
    w.end_array();
    w.begin_array();
    key(w, "startvertex");
    w.integer(int64_t(start));
    key(w, "nprimitives");
    w.integer(int64_t(end - begin));
    key(w, "nvertices_rle");
    w.numbers(rle.data(), rle.size(), JsonWriter::Packing::Int32);
    w.end_array();
    w.end_array();
    return vertices;
  }

  const Geometry& g_;
  const std::string& path_;
};

void write(const Geometry& g, const std::string& path, JsonWriter::Format format) {
  const GeoWriter writer(g, path);
  writer.validate();
  write_file_atomically(path, [&](std::ostream& out) {
    JsonWriter w(out, format);
    writer.emit(w);
  });
}

}  // namespace

bool is_float(Storage s) { return s == Storage::Float16 || s == Storage::Float32 || s == Storage::Float64; }
bool is_int(Storage s) { return s != Storage::String && !is_float(s); }

size_t Attribute::count() const {
  const size_t held = is_float(storage) ? floats.size() : is_int(storage) ? ints.size() : strings.size();
  return size > 0 ? held / size_t(size) : 0;
}

double Attribute::number(size_t element, int component) const {
  const size_t i = element * size_t(size) + size_t(component);
  return is_float(storage) ? floats.at(i) : double(ints.at(i));
}

Attribute float_attribute(int size, std::vector<double> values, Storage storage) {
  Attribute a;
  a.storage = storage;
  a.size = size;
  a.floats = std::move(values);
  return a;
}

Attribute int_attribute(int size, std::vector<int64_t> values, Storage storage) {
  Attribute a;
  a.storage = storage;
  a.size = size;
  a.ints = std::move(values);
  return a;
}

Attribute string_attribute(int size, std::vector<std::string> values) {
  Attribute a;
  a.storage = Storage::String;
  a.size = size;
  a.strings = std::move(values);
  return a;
}

size_t Geometry::vertex_count() const {
  size_t n = 0;
  for (const Primitive& p : primitives) n += p.points.size();
  return n;
}

Geometry read_geo(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::system_error(errno, std::generic_category(), "cannot open " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::system_error(errno, std::generic_category(), "cannot read " + path);
  json root;
  if (is_binary_json(bytes)) {
    root = decode_binary_json(bytes, path);
  } else if (const std::string problem = describe_start(bytes); !problem.empty()) {
    throw FormatError(path + ": " + problem);
  } else {
    try {
      root = json::parse(bytes);
    } catch (const json::parse_error& e) {
      const std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line L, column C: ..."
      const size_t tag = what.find("] ");
      throw FormatError(path + ": " + (tag == std::string::npos ? what : what.substr(tag + 2)));
    }
  }
  return GeoReader(path).read(root);
}

void check_writable(const Geometry& geometry, const std::string& path) { GeoWriter(geometry, path).validate(); }

void write_geo(const Geometry& geometry, const std::string& path) { write(geometry, path, JsonWriter::Format::Text); }
void write_bgeo(const Geometry& geometry, const std::string& path) {
  write(geometry, path, JsonWriter::Format::Binary);
}

Triangulation triangulate(const Geometry& geometry) {
  Triangulation t;
  t.mesh.positions = geometry.points;
  for (size_t i = 0; i < geometry.primitives.size(); ++i) {
    const Primitive& p = geometry.primitives[i];
    if (p.kind != PrimKind::Polygon) continue;
    // Fan from the first vertex; (0, k+1, k) reverses Houdini's clockwise order.
    for (size_t k = 1; k + 1 < p.points.size(); ++k) {
      t.mesh.triangles.push_back({p.points[0], p.points[k + 1], p.points[k]});
      t.primitive.push_back(int(i));
    }
  }
  return t;
}

TriMesh to_trimesh(const Geometry& geometry) { return triangulate(geometry).mesh; }

Geometry from_trimesh(const TriMesh& mesh) {
  Geometry g;
  g.points = mesh.positions;
  g.primitives.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    Primitive p;
    p.points = {t[0], t[2], t[1]};  // counter-clockwise to Houdini's clockwise
    g.primitives.push_back(std::move(p));
  }
  return g;
}

}  // namespace weft::io
