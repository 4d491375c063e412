// focus_math.h (private): the small double-precision plane and 4x4 matrix
// helpers, over vec3.h's vector, shared by the focus files (focus_body, focus_frame, light_matrix,
// compute_focus) and cube_faces.cpp.
// Matrices are column-major (m[col*4 + row]), as in geom/focus.h.
#pragma once
#include <cmath>
#include <cstring>

#include "vec3.h"

namespace geom {
namespace focus {

constexpr double kPi = 3.14159265358979323846;

// The vector is libgeom's one (vec3.h); these add what the focus files need.
using V3 = vec3::Vec3;
using vec3::cross;
using vec3::dot;
using vec3::length;
inline V3 normalize(V3 a) { return vec3::normalize_or(a, V3(0, 0, 0)); }
inline bool finite(V3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
// std::fmax's answer (a NaN argument ignored) without its library call, which
// the compiler does not inline under the project's strict floating point:
// the vertex merges of every clip call it.
inline double max_of(double a, double b) { return a < b || a != a ? b : a; }
inline double max_abs(V3 a) { return max_of(std::fabs(a.x), max_of(std::fabs(a.y), std::fabs(a.z))); }
// Two points the same within eps in every coordinate.
inline bool near_point(V3 a, V3 b, double eps) { return max_abs(a - b) <= eps; }
// A unit vector perpendicular to unit n.
inline V3 any_perpendicular(V3 n) {
  V3 t = std::fabs(n.x) < 0.6 ? V3(1, 0, 0) : std::fabs(n.y) < 0.6 ? V3(0, 1, 0) : V3(0, 0, 1);
  return normalize(cross(n, t));
}

// Half-space n.x + d >= 0 (inside where non-negative).
struct Plane {
  V3 n;
  double d = 0;
  double eval(V3 p) const { return dot(n, p) + d; }
};
inline Plane plane_through(V3 point, V3 normal) { return {normal, -dot(normal, point)}; }

struct M4 {
  double m[16];
  double& at(int row, int col) { return m[col * 4 + row]; }
  double at(int row, int col) const { return m[col * 4 + row]; }
  static M4 identity() {
    M4 r;
    std::memset(r.m, 0, sizeof r.m);
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1;
    return r;
  }
  static M4 zero() {
    M4 r;
    std::memset(r.m, 0, sizeof r.m);
    return r;
  }
  static M4 from(const double* p) {
    M4 r;
    std::memcpy(r.m, p, sizeof r.m);
    return r;
  }
};
inline M4 operator*(const M4& a, const M4& b) {
  M4 r;
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a.at(rr, k) * b.at(k, c);
      r.at(rr, c) = s;
    }
  return r;
}
struct V4 {
  double x, y, z, w;
};
inline V4 mul(const M4& a, double x, double y, double z, double w) {
  return {a.m[0] * x + a.m[4] * y + a.m[8] * z + a.m[12] * w, a.m[1] * x + a.m[5] * y + a.m[9] * z + a.m[13] * w,
          a.m[2] * x + a.m[6] * y + a.m[10] * z + a.m[14] * w, a.m[3] * x + a.m[7] * y + a.m[11] * z + a.m[15] * w};
}
inline V4 mul_point(const M4& a, V3 p) { return mul(a, p.x, p.y, p.z, 1); }
inline bool finite(const M4& a) {
  for (double v : a.m)
    if (!std::isfinite(v)) return false;
  return true;
}
// General inverse (cofactors); false when singular or not finite.
bool invert(const M4& a, M4& out);

// A rigid frame: rows are the axes, `origin` maps to 0. Column-major 4x4.
inline M4 frame(V3 x_axis, V3 y_axis, V3 z_axis, V3 origin) {
  M4 r = M4::identity();
  V3 ax[3] = {x_axis, y_axis, z_axis};
  for (int i = 0; i < 3; ++i) {
    r.at(i, 0) = ax[i].x;
    r.at(i, 1) = ax[i].y;
    r.at(i, 2) = ax[i].z;
    r.at(i, 3) = -dot(ax[i], origin);
  }
  return r;
}

}  // namespace focus
}  // namespace geom
