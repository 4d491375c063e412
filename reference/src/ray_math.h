// reference/src/ray_math.h (private): the double-precision vector math and the
// Embree handle owners that the hard (shadow_reference.cpp) and area-light
// (area_reference.cpp) ray casts share.
#pragma once
#include <embree3/rtcore.h>

#include <cmath>

namespace geom {
namespace ray_math {

struct V3 {
  double x, y, z;
};
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 normalize(V3 a) {
  double l = std::sqrt(dot(a, a));
  return l > 0 ? a * (1 / l) : a;
}
inline V3 v3(const float* p) { return {p[0], p[1], p[2]}; }
inline V3 v3(const double* p) { return {p[0], p[1], p[2]}; }

struct DeviceDeleter {
  void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); }
};

}  // namespace ray_math
}  // namespace geom
