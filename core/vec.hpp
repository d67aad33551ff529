// 3-vectors and 3x3 matrices for kernels; only + - * / and sqrt.
#pragma once
#include "core/real.hpp"

namespace weft {

struct Vec3 {
  real x = 0, y = 0, z = 0;
  KOKKOS_INLINE_FUNCTION real operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  KOKKOS_INLINE_FUNCTION real& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

KOKKOS_INLINE_FUNCTION Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
KOKKOS_INLINE_FUNCTION Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
KOKKOS_INLINE_FUNCTION Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
KOKKOS_INLINE_FUNCTION Vec3 operator*(real s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
KOKKOS_INLINE_FUNCTION Vec3 operator*(Vec3 a, real s) { return {a.x * s, a.y * s, a.z * s}; }
KOKKOS_INLINE_FUNCTION Vec3 operator/(Vec3 a, real s) { return {a.x / s, a.y / s, a.z / s}; }
KOKKOS_INLINE_FUNCTION Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
KOKKOS_INLINE_FUNCTION Vec3& operator-=(Vec3& a, Vec3 b) { return a = a - b; }
KOKKOS_INLINE_FUNCTION bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

KOKKOS_INLINE_FUNCTION real dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
KOKKOS_INLINE_FUNCTION Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
KOKKOS_INLINE_FUNCTION real norm2(Vec3 a) { return dot(a, a); }
KOKKOS_INLINE_FUNCTION real norm(Vec3 a) { return sqrt_(dot(a, a)); }
// Unit vector, or zero for a zero vector.
KOKKOS_INLINE_FUNCTION Vec3 normalized(Vec3 a) {
  const real n = norm(a);
  return n > 0 ? a / n : Vec3{};
}
KOKKOS_INLINE_FUNCTION Vec3 vmin(Vec3 a, Vec3 b) { return {min_(a.x, b.x), min_(a.y, b.y), min_(a.z, b.z)}; }
KOKKOS_INLINE_FUNCTION Vec3 vmax(Vec3 a, Vec3 b) { return {max_(a.x, b.x), max_(a.y, b.y), max_(a.z, b.z)}; }
KOKKOS_INLINE_FUNCTION bool isfinite_(Vec3 a) { return isfinite_(a.x) && isfinite_(a.y) && isfinite_(a.z); }

// Row-major 3x3 matrix.
struct Mat3 {
  real m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  KOKKOS_INLINE_FUNCTION static Mat3 identity() {
    Mat3 r;
    r.m[0][0] = r.m[1][1] = r.m[2][2] = 1;
    return r;
  }
  KOKKOS_INLINE_FUNCTION static Mat3 from_cols(Vec3 a, Vec3 b, Vec3 c) {
    Mat3 r;
    for (int i = 0; i < 3; ++i) { r.m[i][0] = a[i]; r.m[i][1] = b[i]; r.m[i][2] = c[i]; }
    return r;
  }
  KOKKOS_INLINE_FUNCTION Vec3 col(int j) const { return {m[0][j], m[1][j], m[2][j]}; }
  KOKKOS_INLINE_FUNCTION Vec3 row(int i) const { return {m[i][0], m[i][1], m[i][2]}; }
};

KOKKOS_INLINE_FUNCTION Vec3 operator*(const Mat3& a, Vec3 v) { return {dot(a.row(0), v), dot(a.row(1), v), dot(a.row(2), v)}; }
KOKKOS_INLINE_FUNCTION Mat3 operator*(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 operator+(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[i][j] + b.m[i][j];
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 operator*(real s, const Mat3& a) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = s * a.m[i][j];
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 transpose(const Mat3& a) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[j][i];
  return r;
}
KOKKOS_INLINE_FUNCTION real det(const Mat3& a) { return dot(a.col(0), cross(a.col(1), a.col(2))); }
// Inverse by the adjugate; the caller checks det != 0.
KOKKOS_INLINE_FUNCTION Mat3 inverse(const Mat3& a) {
  const Vec3 c0 = a.col(0), c1 = a.col(1), c2 = a.col(2);
  const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
  const real d = dot(c0, r0);
  Mat3 r;
  for (int j = 0; j < 3; ++j) { r.m[0][j] = r0[j] / d; r.m[1][j] = r1[j] / d; r.m[2][j] = r2[j] / d; }
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 outer(Vec3 a, Vec3 b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a[i] * b[j];
  return r;
}

}  // namespace weft
