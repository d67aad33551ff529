#include "io/procedural.hpp"

#include <cmath>

namespace weft::io {

Mesh grid(int nu, int nv, Vec3 origin, Vec3 du, Vec3 dv) {
  Mesh m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) m.x.push_back(origin + (real(i) / nu) * du + (real(j) / nv) * dv);
  auto id = [nu](int i, int j) { return j * (nu + 1) + i; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) { m.tris.push_back({a, b, c}); m.tris.push_back({a, c, d}); }
      else { m.tris.push_back({a, b, d}); m.tris.push_back({b, c, d}); }
    }
  return m;
}

Mesh uv_sphere(Vec3 centre, real radius, int rings, int segments) {
  Mesh m;
  m.x.push_back(centre + Vec3{0, radius, 0});
  for (int r = 1; r < rings; ++r) {
    const real th = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const real ph = 2 * pi * s / segments;
      m.x.push_back(centre + radius * Vec3{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)});
    }
  }
  m.x.push_back(centre - Vec3{0, radius, 0});
  const int south = int(m.x.size()) - 1;
  auto id = [segments](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) m.tris.push_back({0, id(1, s + 1), id(1, s)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.tris.push_back({id(r, s), id(r, s + 1), id(r + 1, s + 1)});
      m.tris.push_back({id(r, s), id(r + 1, s + 1), id(r + 1, s)});
    }
  for (int s = 0; s < segments; ++s) m.tris.push_back({south, id(rings - 1, s), id(rings - 1, s + 1)});
  return m;
}

Mesh box(Vec3 lo, Vec3 hi) {
  Mesh m;
  for (int k = 0; k < 8; ++k) m.x.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  const int q[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : q) { m.tris.push_back({f[0], f[1], f[2]}); m.tris.push_back({f[0], f[2], f[3]}); }
  return m;
}

Mesh tube(real y0, real y1, int rings, int segments, real r0, real r1) {
  Mesh m;
  for (int j = 0; j <= rings; ++j) {
    const real t = real(j) / rings, r = r0 + t * (r1 - r0), y = y0 + t * (y1 - y0);
    for (int s = 0; s < segments; ++s) {
      const real ph = 2 * pi * s / segments;
      m.x.push_back({r * std::cos(ph), y, r * std::sin(ph)});
    }
  }
  auto id = [segments](int j, int s) { return j * segments + (s % segments); };
  for (int j = 0; j < rings; ++j)
    for (int s = 0; s < segments; ++s) {
      m.tris.push_back({id(j, s), id(j + 1, s), id(j + 1, s + 1)});
      m.tris.push_back({id(j, s), id(j + 1, s + 1), id(j, s + 1)});
    }
  return m;
}

Mesh capsule(Vec3 a, Vec3 b, real radius, int rings, int segments) {
  // A sphere split at its equator, halves moved to a and b, with the seam rings joined.
  const Vec3 axis = normalized(b - a);
  const Vec3 helper = std::fabs(axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 e1 = normalized(cross(axis, helper)), e2 = cross(e1, axis);  // (e1, axis, e2) right-handed: a rotation keeps the faces outward
  if (rings % 2) ++rings;
  Mesh m = uv_sphere({0, 0, 0}, radius, rings, segments);
  for (Vec3& p : m.x) {
    const Vec3 local = p.x * e1 + p.z * e2 + p.y * axis;  // sphere's y becomes the capsule axis
    p = (p.y >= 0 ? b : a) + local;
  }
  // The equator ring belongs to the upper half; add a ring copy for the lower half and a band between.
  const int eq = rings / 2, first = 1 + (eq - 1) * segments;
  const int added = int(m.x.size());
  for (int s = 0; s < segments; ++s) m.x.push_back(m.x[first + s] - (b - a));
  for (auto& t : m.tris) {
    // Triangles below the equator that use equator vertices now use the copies.
    int below = 0;
    for (int k = 0; k < 3; ++k) below += (t[k] > first + segments - 1 && t[k] < added) ? 1 : 0;
    if (below)
      for (int k = 0; k < 3; ++k)
        if (t[k] >= first && t[k] < first + segments) t[k] = added + (t[k] - first);
  }
  for (int s = 0; s < segments; ++s) {
    const int u0 = first + s, u1 = first + (s + 1) % segments, l0 = added + s, l1 = added + (s + 1) % segments;
    m.tris.push_back({u0, u1, l1});
    m.tris.push_back({u0, l1, l0});
  }
  return m;
}

void append(Mesh& to, const Mesh& m) {
  const int off = int(to.x.size());
  to.x.insert(to.x.end(), m.x.begin(), m.x.end());
  for (const auto& t : m.tris) to.tris.push_back({t[0] + off, t[1] + off, t[2] + off});
}

}  // namespace weft::io
