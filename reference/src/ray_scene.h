// reference/src/ray_scene.h (private): what the hard (shadow_reference.cpp) and
// area-light (area_reference.cpp) ray casts share: the double-precision vector
// math, the input checks, the Embree scene in a local frame centred on the
// scene's box (so a scene far from the origin keeps float precision), the
// camera's primary rays and the light in that frame.
#pragma once
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "geom/scene.h"
#include "geom/span.h"

namespace geom {
namespace ray_scene {

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

// The checks both references make of their input: image size, camera, light
// (homogeneous, geom/scene.h), the index count and range, finite vertices.
// "" when all hold, else "WHO: the problem".
std::string check_inputs(const char* who, PositionSpan positions, const uint32_t* indices, size_t index_count,
                         const Camera& camera, const double light[4]);

// The triangles in Embree, in the local frame: local = input - centre; `extent`
// is the box's half diagonal (1 with no triangle), the scale of the shadow
// rays' self-intersection offset.
struct RayScene {
  std::unique_ptr<RTCDeviceTy, DeviceDeleter> device;
  std::unique_ptr<RTCSceneTy, SceneDeleter> scene;
  V3 centre{0, 0, 0};
  double extent = 1.0;
};
// `flags` are added to RTC_SCENE_FLAG_ROBUST. "" on success, else "WHO: ...".
std::string build_ray_scene(const char* who, PositionSpan positions, const uint32_t* indices, size_t index_count,
                            RTCSceneFlags flags, RayScene& out);

// The camera's pixel rays in the local frame: the direction of a pixel has
// view-space depth 1, so the ray parameter is the view depth ([near, far]).
struct EyeRays {
  V3 eye{}, f{}, r{}, u{};
  double tx = 0, ty = 0;
  EyeRays() = default;
  EyeRays(const Camera& camera, V3 centre);
  V3 direction(int x, int y, int width, int height) const;
};

// The visible point of pixel (x, y): false when the ray hits nothing; else the
// point P (local frame), the unit normal n of its triangle on the side the
// camera sees and the triangle.
bool primary_hit(const RayScene& rs, const EyeRays& eye, const Camera& camera, int x, int y, PositionSpan positions,
                 const uint32_t* indices, V3& P, V3& n, uint32_t& triangle);

// The light in the local frame: (L, w) homogeneous (L = position - centre for a
// point, the direction towards the light for w = 0), the spot's cone.
struct LocalLight {
  double w = 0;
  V3 L{};
  bool spot = false;
  V3 axis{};
  double spot_cos = 0;
  LocalLight() = default;
  LocalLight(const Light& light, const double homogeneous[4], V3 centre);
  // A spot light's point P outside its cone (never for other lights).
  bool outside_cone(V3 P) const { return spot && w != 0 && dot(normalize(P - L), axis) < spot_cos; }
};

// Everything a reference casts with: the checked input in Embree, the pixel
// rays, the light in the local frame and the shadow rays' offset (1e-5 of the
// scene's half diagonal).
struct RayCast {
  RayScene scene;
  EyeRays eye;
  LocalLight light;
  double offset = 0;
};
// check_inputs, build_ray_scene (with `flags`), then the rays and the light.
// "" on success, else "WHO: the problem".
std::string prepare_ray_cast(const char* who, PositionSpan positions, const uint32_t* indices, size_t index_count,
                             const Camera& camera, const Light& light, RTCSceneFlags flags, RayCast& out);

}  // namespace ray_scene
}  // namespace geom
