// Houdini geometry: the model Vellum assets need (points, primitives, attributes on every element class, groups),
// reading .geo (JSON text) and .bgeo (binary JSON) files, writing both, and triangulation for the solver.
#pragma once
#include "io/trimesh.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace weft::io {

// How a file stores an attribute's values; String values are indices into a string table in the file.
enum class Storage { Float16, Float32, Float64, Int8, Int16, Int32, Int64, UInt8, String };

bool is_float(Storage s);
bool is_int(Storage s);

// One attribute: a tuple of `size` components per element, element-major (element e, component c at
// [e * size + c]) in the vector that matches the storage. Float32 values read from text are rounded to
// float, so a .geo and a .bgeo of the same geometry read identically.
struct Attribute {
  Storage storage = Storage::Float32;
  int size = 1;
  std::string qualifier;  // Houdini's type info ("point", "vector", "normal", "color"...), or empty
  std::vector<double> floats;
  std::vector<int64_t> ints;
  std::vector<std::string> strings;

  size_t count() const;                                    // elements held
  double number(size_t element, int component = 0) const;  // a float or int component
};

Attribute float_attribute(int size, std::vector<double> values, Storage storage = Storage::Float32);
Attribute int_attribute(int size, std::vector<int64_t> values, Storage storage = Storage::Int32);
Attribute string_attribute(int size, std::vector<std::string> values);

using AttributeMap = std::map<std::string, Attribute>;

enum class PrimKind { Polygon, Polyline, Sphere, Other };

struct Primitive {
  PrimKind kind = PrimKind::Polygon;
  std::vector<int> points;  // the point of each vertex, in vertex order
  std::string type_name;    // Houdini's type name of an Other primitive ("Part", "Tetrahedron", ...)
  std::array<double, 9> transform{1, 0, 0, 0, 1, 0, 0, 0, 1};  // Sphere: 3x3 shape about its point
};

// Named groups: whether each element belongs, one entry per element (point, vertex or primitive).
using GroupMap = std::map<std::string, std::vector<bool>>;

// Vertices are numbered through the primitives in order; vertex attributes and groups hold one element per
// vertex in that order.
struct Geometry {
  std::vector<Vec3> points;                     // P
  Storage position_storage = Storage::Float32;  // how P is stored in files
  AttributeMap point_attributes;                // all but P
  AttributeMap vertex_attributes;
  std::vector<Primitive> primitives;
  AttributeMap primitive_attributes;
  AttributeMap detail_attributes;     // one element
  GroupMap point_groups, vertex_groups, primitive_groups;  // ordered groups read as plain membership
  std::vector<std::string> warnings;  // what reading skipped or kept opaque; never written

  size_t vertex_count() const;
};

// Reads a .geo or .bgeo file, told apart by content. Malformed files throw FormatError naming the file and
// the element (line or byte offset, attribute, primitive, vertex or point); unreadable ones std::system_error.
Geometry read_geo(const std::string& path);

// Writes ASCII .geo / binary .bgeo that Houdini loads, atomically. Geometry the format cannot hold (an Other
// primitive, an index, attribute or group size that does not match, a non-finite value) throws FormatError
// first; check_writable throws the same error without writing (`path` only names the file in the message).
void write_geo(const Geometry& geometry, const std::string& path);
void write_bgeo(const Geometry& geometry, const std::string& path);
void check_writable(const Geometry& geometry, const std::string& path);

// Closed polygons fanned into triangles, turned counter-clockwise (Houdini's polygons run clockwise seen
// from the front), with the primitive each came from so results can be written back per primitive.
struct Triangulation {
  TriMesh mesh;  // every point of the geometry
  std::vector<int> primitive;
};
Triangulation triangulate(const Geometry& geometry);
TriMesh to_trimesh(const Geometry& geometry);

// A cloth frame: the mesh's triangles as closed polygons in Houdini's winding, positions as P.
Geometry from_trimesh(const TriMesh& mesh);

}  // namespace weft::io
