// The light fraction under a disc light by ray casting with Embree 3 (see
// geom/area_reference.h): the visible point of each pixel as in
// shadow_reference.cpp, then `samples` stratified shadow rays to the disc.
#include "geom/area_reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "ray_math.h"

namespace geom {
namespace {

using namespace ray_math;  // V3, dot, cross, the Embree owners (ray_math.h)

// PCG32 (O'Neill): the jitter of one pixel.
struct Pcg {
  uint64_t state;
  explicit Pcg(uint64_t seed) : state(seed * 6364136223846793005ULL + 1442695040888963407ULL) { next(); }
  uint32_t next() {
    const uint64_t old = state;
    state = old * 6364136223846793005ULL + 1442695040888963407ULL;
    const uint32_t x = uint32_t(((old >> 18u) ^ old) >> 27u), r = uint32_t(old >> 59u);
    return (x >> r) | (x << ((32 - r) & 31));
  }
  double uniform() { return (next() >> 8) * (1.0 / 16777216.0); }
};

// Shirley and Chiu's concentric map of the square [0, 1]^2 onto the unit disc.
void concentric(double u, double v, double& a, double& b) {
  const double x = 2 * u - 1, y = 2 * v - 1;
  if (x == 0 && y == 0) return void(a = b = 0);
  double r, phi;
  if (std::fabs(x) > std::fabs(y))
    r = x, phi = M_PI / 4 * (y / x);
  else
    r = y, phi = M_PI / 2 - M_PI / 4 * (x / y);
  a = r * std::cos(phi), b = r * std::sin(phi);
}

template <class T>
bool finite3(const T* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace

AreaReference area_light_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                   const Camera& camera, const Light& light, double radius, int samples,
                                   uint32_t seed) {
  AreaReference out;
  double position[4];
  light_homogeneous(light, position);
  const int W = camera.width, H = camera.height;
  if (W <= 0 || H <= 0 || W > 16384 || H > 16384) return out.error = "area reference: image size out of range", out;
  if (samples < 1 || samples > 65536) return out.error = "area reference: samples out of range (1..65536)", out;
  if (!(radius >= 0) || !std::isfinite(radius) || (position[3] == 0 && radius >= M_PI / 2))
    return out.error = "area reference: light radius out of range", out;
  if (!(camera.fovy_deg > 0 && camera.fovy_deg < 180) || !(camera.near_plane > 0) ||
      !(camera.far_plane > camera.near_plane) || !finite3(camera.eye) || !finite3(camera.target) ||
      !finite3(camera.up) || !finite3(position) || !std::isfinite(position[3]))
    return out.error = "area reference: invalid camera or light", out;
  if (index_count % 3) return out.error = "area reference: index count is not a multiple of 3", out;
  for (size_t i = 0; i < index_count; ++i)
    if (indices[i] >= positions.size()) return out.error = "area reference: an index is out of range", out;
  for (size_t i = 0; i < positions.size(); ++i)
    if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
      return out.error = "area reference: a vertex is not finite", out;
  const size_t tri_count = index_count / 3;

  std::unique_ptr<RTCDeviceTy, DeviceDeleter> device(rtcNewDevice("threads=1"));
  if (!device) return out.error = "area reference: Embree device creation failed", out;
  std::unique_ptr<RTCSceneTy, SceneDeleter> scene(rtcNewScene(device.get()));
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);
  V3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < index_count; ++i) {
    const Float3& p = positions[indices[i]];
    lo = {std::min(lo.x, double(p.x)), std::min(lo.y, double(p.y)), std::min(lo.z, double(p.z))};
    hi = {std::max(hi.x, double(p.x)), std::max(hi.y, double(p.y)), std::max(hi.z, double(p.z))};
  }
  const V3 centre = tri_count ? (lo + hi) * 0.5 : V3{0, 0, 0};
  const double extent = tri_count ? std::sqrt(dot(hi - lo, hi - lo)) * 0.5 : 1.0;
  if (tri_count) {
    RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    float* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), positions.size()));
    uint32_t* ib = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), tri_count));
    if (!vb || !ib) {
      rtcReleaseGeometry(geometry);
      return out.error = "area reference: Embree buffer allocation failed", out;
    }
    for (size_t i = 0; i < positions.size(); ++i) {
      const Float3& p = positions[i];
      vb[3 * i] = float(p.x - centre.x), vb[3 * i + 1] = float(p.y - centre.y), vb[3 * i + 2] = float(p.z - centre.z);
    }
    std::copy(indices, indices + index_count, ib);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene.get(), geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene.get());
  if (rtcGetDeviceError(device.get()) != RTC_ERROR_NONE) return out.error = "area reference: Embree failed", out;

  const V3 eye = v3(camera.eye) - centre;
  const V3 f = normalize(v3(camera.target) - v3(camera.eye));
  const V3 r = normalize(cross(f, v3(camera.up)));
  const V3 u = cross(r, f);
  const double ty = std::tan(camera.fovy_deg * M_PI / 360.0), tx = ty * W / H;
  const double Lw = position[3];
  const V3 L = v3(position) - centre * Lw;
  const bool spot = light.type == LightType::Spot;
  const V3 spot_axis = normalize(v3(light.direction));
  const double spot_cos = std::cos(light.outer_cone);
  const double offset = 1e-5 * std::max(extent, 1e-30);
  const int grid = std::max(1, int(std::lround(std::sqrt(double(samples)))));
  const int n = grid * grid;  // the stratified count actually cast

  out.width = W, out.height = H;
  out.fraction.assign(size_t(W) * H, -1.0f);
  RTCIntersectContext context;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double sx = (2.0 * (x + 0.5) / W - 1.0) * tx, sy = (1.0 - 2.0 * (y + 0.5) / H) * ty;
      const V3 d = f + r * sx + u * sy;
      RTCRayHit rh{};
      rh.ray.org_x = float(eye.x), rh.ray.org_y = float(eye.y), rh.ray.org_z = float(eye.z);
      rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
      rh.ray.tnear = camera.near_plane, rh.ray.tfar = camera.far_plane;
      rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcInitIntersectContext(&context);
      rtcIntersect1(scene.get(), &context, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      const uint32_t* t = indices + 3 * size_t(rh.hit.primID);
      const Float3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
      const V3 A = V3{a.x, a.y, a.z} - centre, B = V3{b.x, b.y, b.z} - centre, C = V3{c.x, c.y, c.z} - centre;
      const V3 P = A * (1 - rh.hit.u - rh.hit.v) + B * rh.hit.u + C * rh.hit.v;
      V3 nrm = normalize(cross(B - A, C - A));
      if (dot(nrm, eye - P) < 0) nrm = nrm * -1.0;
      float& frac = out.fraction[size_t(y) * W + x];
      frac = 0;
      const V3 to_light = normalize(L - P * Lw);  // towards the light's centre
      if (!(dot(nrm, to_light) > 0)) continue;
      if (spot && Lw != 0 && dot(normalize(P - L), spot_axis) < spot_cos) continue;
      // The disc's axes, perpendicular to the direction to its centre.
      const V3 e1 = normalize(cross(to_light, std::fabs(to_light.y) < 0.9 ? V3{0, 1, 0} : V3{1, 0, 0}));
      const V3 e2 = cross(to_light, e1);
      const double disc = Lw != 0 ? radius : std::tan(radius);
      const V3 o = P + nrm * offset;
      Pcg rng(uint64_t(seed) * 0x9E3779B97F4A7C15ULL + uint64_t(y) * 16777259ULL + uint64_t(x));
      int lit = 0;
      for (int k = 0; k < n; ++k) {
        double da, db;
        concentric((k % grid + rng.uniform()) / grid, (k / grid + rng.uniform()) / grid, da, db);
        const V3 dir = Lw != 0 ? (L + (e1 * da + e2 * db) * disc) - o : to_light + (e1 * da + e2 * db) * disc;
        RTCRay ray{};
        ray.org_x = float(o.x), ray.org_y = float(o.y), ray.org_z = float(o.z);
        ray.dir_x = float(dir.x), ray.dir_y = float(dir.y), ray.dir_z = float(dir.z);
        ray.tnear = 0;
        ray.tfar = Lw != 0 ? 1.0f - 1e-4f : std::numeric_limits<float>::infinity();
        ray.mask = 0xffffffffu;
        rtcInitIntersectContext(&context);
        rtcOccluded1(scene.get(), &context, &ray);
        lit += ray.tfar != -std::numeric_limits<float>::infinity();
      }
      frac = float(lit) / float(n);
    }
  out.ok = true;
  return out;
}

double mean_fraction_error(const std::vector<uint8_t>& rendered, const AreaReference& ref, size_t* pixels) {
  if (rendered.size() != ref.fraction.size()) return -1;
  double sum = 0;
  size_t count = 0;
  for (size_t i = 0; i < rendered.size(); ++i) {
    if (ref.fraction[i] < 0) continue;
    sum += std::fabs(rendered[i] / 255.0 - double(ref.fraction[i])), ++count;
  }
  if (pixels) *pixels = count;
  return count ? sum / double(count) : 0.0;
}

}  // namespace geom
