// The pieces both ray-cast references share (reference/src/ray_scene.h).
#include "ray_scene.h"

#include <algorithm>

namespace geom {
namespace ray_scene {
namespace {

template <class T>
bool finite3(const T* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace

std::string check_inputs(const char* who, PositionSpan positions, const uint32_t* indices, size_t index_count,
                         const Camera& camera, const double light[4]) {
  const std::string w = std::string(who) + ": ";
  const int W = camera.width, H = camera.height;
  if (W <= 0 || H <= 0 || W > 16384 || H > 16384)
    return w + "image size " + std::to_string(W) + "x" + std::to_string(H) + " out of range";
  if (!(camera.fovy_deg > 0 && camera.fovy_deg < 180) || !(camera.near_plane > 0) ||
      !(camera.far_plane > camera.near_plane) || !finite3(camera.eye) || !finite3(camera.target) ||
      !finite3(camera.up) || !finite3(light) || !std::isfinite(light[3]))
    return w + "invalid camera or light";
  if (index_count % 3) return w + "index count " + std::to_string(index_count) + " is not a multiple of 3";
  for (size_t i = 0; i < index_count; ++i)
    if (indices[i] >= positions.size())
      return w + "triangle " + std::to_string(i / 3) + " has index " + std::to_string(indices[i]) + " out of range (" +
             std::to_string(positions.size()) + " vertices)";
  for (size_t i = 0; i < positions.size(); ++i) {
    const Float3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return w + "vertex " + std::to_string(i) + " is not finite";
  }
  return "";
}

std::string build_ray_scene(const char* who, PositionSpan positions, const uint32_t* indices, size_t index_count,
                            RTCSceneFlags flags, RayScene& out) {
  const std::string w = std::string(who) + ": ";
  const size_t tri_count = index_count / 3;
  out.device.reset(rtcNewDevice("threads=1"));
  if (!out.device) return w + "Embree device creation failed";
  out.scene.reset(rtcNewScene(out.device.get()));
  rtcSetSceneFlags(out.scene.get(), RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | flags));
  rtcSetSceneBuildQuality(out.scene.get(), RTC_BUILD_QUALITY_HIGH);
  V3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < index_count; ++i) {
    const Float3& p = positions[indices[i]];
    lo = {std::min(lo.x, double(p.x)), std::min(lo.y, double(p.y)), std::min(lo.z, double(p.z))};
    hi = {std::max(hi.x, double(p.x)), std::max(hi.y, double(p.y)), std::max(hi.z, double(p.z))};
  }
  out.centre = tri_count ? (lo + hi) * 0.5 : V3{0, 0, 0};
  out.extent = tri_count ? std::sqrt(dot(hi - lo, hi - lo)) * 0.5 : 1.0;
  if (tri_count) {
    RTCGeometry geometry = rtcNewGeometry(out.device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    float* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), positions.size()));
    uint32_t* ib = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), tri_count));
    if (!vb || !ib) {
      rtcReleaseGeometry(geometry);
      return w + "Embree buffer allocation failed";
    }
    const V3 c = out.centre;
    for (size_t i = 0; i < positions.size(); ++i) {
      const Float3& p = positions[i];
      vb[3 * i] = float(p.x - c.x), vb[3 * i + 1] = float(p.y - c.y), vb[3 * i + 2] = float(p.z - c.z);
    }
    std::copy(indices, indices + index_count, ib);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(out.scene.get(), geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(out.scene.get());
  if (rtcGetDeviceError(out.device.get()) != RTC_ERROR_NONE) return w + "Embree scene build failed";
  return "";
}

EyeRays::EyeRays(const Camera& camera, V3 centre)
    : eye(v3(camera.eye) - centre),
      f(normalize(v3(camera.target) - v3(camera.eye))),
      r(normalize(cross(f, v3(camera.up)))),
      u(cross(r, f)),
      tx(0),
      ty(std::tan(camera.fovy_deg * M_PI / 360.0)) {
  tx = ty * camera.width / camera.height;
}

V3 EyeRays::direction(int x, int y, int width, int height) const {
  const double sx = (2.0 * (x + 0.5) / width - 1.0) * tx, sy = (1.0 - 2.0 * (y + 0.5) / height) * ty;
  return f + r * sx + u * sy;
}

bool primary_hit(const RayScene& rs, const EyeRays& eye, const Camera& camera, int x, int y, PositionSpan positions,
                 const uint32_t* indices, V3& P, V3& n, uint32_t& triangle) {
  const V3 d = eye.direction(x, y, camera.width, camera.height);
  RTCRayHit rh{};
  rh.ray.org_x = float(eye.eye.x), rh.ray.org_y = float(eye.eye.y), rh.ray.org_z = float(eye.eye.z);
  rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
  rh.ray.tnear = camera.near_plane, rh.ray.tfar = camera.far_plane;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(rs.scene.get(), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  triangle = rh.hit.primID;
  const uint32_t* t = indices + 3 * size_t(triangle);
  const Float3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
  const V3 A = V3{a.x, a.y, a.z} - rs.centre, B = V3{b.x, b.y, b.z} - rs.centre, C = V3{c.x, c.y, c.z} - rs.centre;
  const double bu = rh.hit.u, bv = rh.hit.v;
  P = A * (1 - bu - bv) + B * bu + C * bv;
  n = normalize(cross(B - A, C - A));
  if (dot(n, eye.eye - P) < 0) n = n * -1.0;  // the side the camera sees
  return true;
}

LocalLight::LocalLight(const Light& light, const double h[4], V3 centre)
    : w(h[3]),
      L(v3(h) - centre * h[3]),
      spot(light.type == LightType::Spot),
      axis(normalize(v3(light.direction))),
      spot_cos(std::cos(light.outer_cone)) {}

std::string prepare_ray_cast(const char* who, PositionSpan positions, const uint32_t* indices, size_t index_count,
                             const Camera& camera, const Light& light, RTCSceneFlags flags, RayCast& out) {
  double h[4];  // homogeneous (geom/scene.h)
  light_homogeneous(light, h);
  std::string error = check_inputs(who, positions, indices, index_count, camera, h);
  if (error.empty()) error = build_ray_scene(who, positions, indices, index_count, flags, out.scene);
  if (!error.empty()) return error;
  out.eye = EyeRays(camera, out.scene.centre);
  out.light = LocalLight(light, h, out.scene.centre);
  out.offset = 1e-5 * std::max(out.scene.extent, 1e-30);
  return "";
}

}  // namespace ray_scene
}  // namespace geom
