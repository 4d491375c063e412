// vec3.h (private): libgeom's one double-precision 3-vector, for the
// silhouette stages (topology.cpp, esm_quads.cpp, shadow_volume.cpp) and the
// focus files (focus_math.h builds its planes and matrices on it). Each
// operation is the plain formula, in the order written here, so every stage
// rounds alike.
#pragma once
#include <cmath>

#include "geom/span.h"

namespace geom::vec3 {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  Vec3() = default;
  Vec3(double a, double b, double c) : x(a), y(b), z(c) {}
  explicit Vec3(const double* p) : x(p[0]), y(p[1]), z(p[2]) {}
  double operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(double s, Vec3 a) { return a * s; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
// a / |a|, or `zero` where a is the zero vector.
inline Vec3 normalize_or(Vec3 a, Vec3 zero) {
  const double l = length(a);
  return l > 0 ? a * (1.0 / l) : zero;
}
// From float storage, widened exactly.
inline Vec3 of(const Float3& p) { return {double(p.x), double(p.y), double(p.z)}; }
inline Vec3 of(const float p[3]) { return {double(p[0]), double(p[1]), double(p[2])}; }

}  // namespace geom::vec3
