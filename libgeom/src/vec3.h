// vec3.h (private): the double-precision 3-vector of the silhouette stages
// (topology.cpp, esm_quads.cpp, shadow_volume.cpp). Each operation is the
// plain formula, in the order written here, so every stage rounds alike.
#pragma once
#include <cmath>

#include "geom/span.h"

namespace geom::vec3 {

struct Vec3 {
  double x, y, z;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
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
