// Houdini geometry built in code, as Vellum hands it over: simulation cloths and their constraint geometry,
// for the topics that read and write .geo / .bgeo (io_geo_writeback, io_vellum_import, cli_import_export).
#pragma once
#include "io/houdini_geo.hpp"
#include "tests/io_checks_fixture.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace weft::test {

// Rounded to float. Through a volatile: GCC 12 -O3 drops the rounding of double(float(x)) when its SLP
// vectorizer packs two of them (as in a braced list of f32 calls).
inline double f32(double x) {
  volatile float f = float(x);
  return f;
}

inline std::vector<bool> flags(std::initializer_list<int> v) {
  std::vector<bool> out;
  for (const int x : v) out.push_back(x != 0);
  return out;
}

// A Vellum-style cloth as Houdini hands it over: a 4 x 3 grid 0.25 m apart at y = 1 (point j*4+i at
// (0.25 i, 1, 0.25 j)), six quads, UVs on vertices, an extra float and an int point attribute, a point and a
// primitive group, a primitive string and detail attributes (the frame range among them); no v.
inline io::Geometry cloth() {
  io::Geometry g;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) g.points.push_back({0.25 * i, 1, 0.25 * j});
  std::vector<double> uv;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      io::Primitive p;
      const int a = j * 4 + i;
      p.points = {a, a + 1, a + 5, a + 4};
      for (const int q : p.points) uv.insert(uv.end(), {f32(g.points[q].x / 0.75), f32(g.points[q].z / 0.5), 0});
      g.primitives.push_back(p);
    }
  g.vertex_attributes["uv"] = io::float_attribute(3, uv);
  std::vector<double> mask;
  for (int p = 0; p < 12; ++p) mask.push_back(f32(0.1 * p));
  g.point_attributes["clothmask"] = io::float_attribute(1, mask);
  g.point_attributes["stopped"] = io::int_attribute(1, {1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0});
  g.point_groups["pinned"] = flags({1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0});
  g.primitive_groups["front"] = flags({1, 1, 1, 0, 0, 0});
  g.primitive_attributes["name"] = io::string_attribute(1, {"shirt", "shirt", "shirt", "sleeve", "sleeve", "sleeve"});
  g.detail_attributes["framestart"] = io::int_attribute(1, {1});
  g.detail_attributes["frameend"] = io::int_attribute(1, {4});
  g.detail_attributes["asset"] = io::string_attribute(1, {"shirt_v3"});
  return g;
}

// The constraint geometry the Vellum Constraints node would write for it: a distance constraint per edge.
inline io::Geometry distance_constraints(const io::Geometry& sim) {
  io::Geometry c;
  c.points = sim.points;
  std::vector<std::string> type;
  std::vector<double> stiffness, rest;
  const auto edge = [&](int a, int b) {
    io::Primitive p;
    p.kind = io::PrimKind::Polyline;
    p.points = {a, b};
    c.primitives.push_back(p);
    type.push_back("distance");
    stiffness.push_back(1e4);
    rest.push_back(0.25);
  };
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      if (i < 3) edge(j * 4 + i, j * 4 + i + 1);
      if (j < 2) edge(j * 4 + i, j * 4 + i + 4);
    }
  c.primitive_attributes["type"] = io::string_attribute(1, type);
  c.primitive_attributes["stiffness"] = io::float_attribute(1, stiffness);
  c.primitive_attributes["restlength"] = io::float_attribute(1, rest);
  return c;
}

// Everything of `original` but P and the point attribute v is in `frame`, unchanged.
inline void expect_same_but_p_and_v(const io::Geometry& original, const io::Geometry& frame) {
  ASSERT_EQ(frame.points.size(), original.points.size());
  EXPECT_EQ(frame.position_storage, original.position_storage);
  ASSERT_EQ(frame.primitives.size(), original.primitives.size());
  for (size_t i = 0; i < original.primitives.size(); ++i) {
    EXPECT_EQ(frame.primitives[i].kind, original.primitives[i].kind) << "primitive " << i;
    EXPECT_EQ(frame.primitives[i].points, original.primitives[i].points) << "primitive " << i;
  }
  io::AttributeMap points = frame.point_attributes, original_points = original.point_attributes;
  points.erase("v");
  original_points.erase("v");
  expect_same_attributes(original_points, points, "point");
  expect_same_attributes(original.vertex_attributes, frame.vertex_attributes, "vertex");
  expect_same_attributes(original.primitive_attributes, frame.primitive_attributes, "primitive");
  expect_same_attributes(original.detail_attributes, frame.detail_attributes, "detail");
  EXPECT_EQ(frame.point_groups, original.point_groups);
  EXPECT_EQ(frame.vertex_groups, original.vertex_groups);
  EXPECT_EQ(frame.primitive_groups, original.primitive_groups);
}

// The Vellum import's sim geometry: 3 x 3 points 0.5 m apart in the plane y = 1 (point j*3+i at (0.5 i, 1,
// 0.5 j)), four quads, Vellum's point attributes (mass, pscale, stopped, ...) and a v.
inline io::Geometry cloth_sim() {
  io::Geometry g;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) g.points.push_back({0.5 * i, 1, 0.5 * j});
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      io::Primitive p;
      const int a = j * 3 + i;
      p.points = {a, a + 1, a + 4, a + 3};
      g.primitives.push_back(p);
    }
  g.point_attributes["mass"] = io::float_attribute(1, {0, 0.25, 0.25, 0.25, 0.5, 0.25, 0.25, 0.25, 0.25});
  g.point_attributes["pscale"] = io::float_attribute(1, {0.01, 0.01, 0.01, 0.01, 0.02, 0.01, 0.01, 0.01, 0.01});
  g.point_attributes["stopped"] = io::int_attribute(1, {0, 0, 1, 0, 0, 0, 0, 0, 3});
  g.point_attributes["layer"] = io::int_attribute(1, {0, 0, 0, 0, 2, 0, 0, 0, 0});
  g.point_attributes["friction"] = io::float_attribute(1, {1, 1, 1, 1, 0.5, 1, 1, 1, 1});
  g.point_attributes["dynamicfriction"] = io::float_attribute(1, {1, 1, 1, 1, 0.25, 1, 1, 1, 1});
  g.point_attributes["pintoanimation"] = io::int_attribute(1, {0, 0, 0, 0, 0, 0, 1, 0, 0});
  std::vector<double> v(27, 0.0);
  v[4 * 3 + 1] = -2;
  g.point_attributes["v"] = io::float_attribute(3, v);
  return g;
}

// One constraint primitive per add(); attributes filled with Vellum's defaults where not given.
struct ConstraintGeo {
  io::Geometry g;
  std::vector<std::string> type, target_path;
  std::vector<double> stiffness, compress, damping, restlength, restvector, target_uv;
  std::vector<int64_t> target_prim, target_pt;

  explicit ConstraintGeo(const io::Geometry& sim) { g.points = sim.points; }
  ConstraintGeo& add(const std::string& t, std::vector<int> points, double k, double rest = 0,
                     std::array<double, 4> rv = {0, 0, 0, 0}, double ck = -1, double d = 0,
                     io::PrimKind kind = io::PrimKind::Polyline) {
    io::Primitive p;
    p.kind = kind;
    p.points = std::move(points);
    g.primitives.push_back(p);
    type.push_back(t);
    stiffness.push_back(k);
    compress.push_back(ck);
    damping.push_back(d);
    restlength.push_back(rest);
    restvector.insert(restvector.end(), rv.begin(), rv.end());
    target_path.push_back("");
    target_prim.push_back(-1);
    target_pt.push_back(-1);
    target_uv.insert(target_uv.end(), {0, 0, 0});
    return *this;
  }
  ConstraintGeo& attach(int point, const std::string& path, int prim, double u, double v, int pt = -1) {
    add("attach", {point}, 1e6, 0, {0, 0, 0, 0}, -1, 0, io::PrimKind::Sphere);
    target_path.back() = path;
    target_prim.back() = prim;
    target_pt.back() = pt;
    target_uv.resize(target_uv.size() - 3);
    target_uv.insert(target_uv.end(), {u, v, 0});
    return *this;
  }
  std::string write(const std::string& path) {
    auto& a = g.primitive_attributes;
    a["type"] = io::string_attribute(1, type);
    a["stiffness"] = io::float_attribute(1, stiffness);
    a["compressstiffness"] = io::float_attribute(1, compress);
    a["dampingratio"] = io::float_attribute(1, damping);
    a["restlength"] = io::float_attribute(1, restlength);
    a["restvector"] = io::float_attribute(4, restvector);
    a["target_path"] = io::string_attribute(1, target_path);
    a["target_prim"] = io::int_attribute(1, target_prim);
    a["target_pt"] = io::int_attribute(1, target_pt);
    a["target_uv"] = io::float_attribute(3, target_uv);
    io::write_geo(g, path);
    return path;
  }
};

}  // namespace weft::test
