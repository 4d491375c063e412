// Exact shadow mask by ray casting with Embree 3 (see geom/shadow_reference.h).
// The per-pixel law is the one of 000/001/004 (a point is in shadow exactly when
// the segment from it to the light is blocked); this file is its reference.
#include "geom/shadow_reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_map>

#include "ray_math.h"

namespace geom {
namespace {

using namespace ray_math;  // V3, dot, cross, the Embree owners (ray_math.h)

template <class T>
bool finite3(const T* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// A shadow ray's context: the filter skips the hits on one object (`skip`) or
// keeps only those (`only`), and records the object of the hit it accepts.
struct ObjectFilter {
  RTCIntersectContext context;
  const uint32_t* objects = nullptr;
  uint32_t skip = kNoObject, only = kNoObject, accepted = kNoObject;
};

void object_filter(const RTCFilterFunctionNArguments* args) {
  const ObjectFilter* f = reinterpret_cast<const ObjectFilter*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t o = f->objects[RTCHitN_primID(args->hit, args->N, i)];
    if ((f->skip != kNoObject && o == f->skip) || (f->only != kNoObject && o != f->only))
      args->valid[i] = 0;
    else
      const_cast<ObjectFilter*>(f)->accepted = o;
  }
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<uint32_t> triangle_components(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                          uint32_t& count) {
  const size_t tris = index_count / 3;
  std::vector<uint32_t> parent(tris);
  std::iota(parent.begin(), parent.end(), 0u);
  // The first triangle seen at each vertex position; later ones join it.
  struct Key {
    uint32_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    size_t operator()(const Key& k) const {
      return (size_t(k.x) * 73856093u) ^ (size_t(k.y) * 19349663u) ^ (size_t(k.z) * 83492791u);
    }
  };
  std::unordered_map<Key, uint32_t, Hash> first;
  first.reserve(index_count);
  for (size_t i = 0; i < tris * 3; ++i) {
    if (indices[i] >= positions.size()) continue;
    const Float3& p = positions[indices[i]];
    Key k;
    const float x = p.x == 0 ? 0.0f : p.x, y = p.y == 0 ? 0.0f : p.y, z = p.z == 0 ? 0.0f : p.z;  // -0 is 0
    std::memcpy(&k.x, &x, 4), std::memcpy(&k.y, &y, 4), std::memcpy(&k.z, &z, 4);
    const auto it = first.emplace(k, uint32_t(i / 3)).first;
    const uint32_t a = find_root(parent, it->second), b = find_root(parent, uint32_t(i / 3));
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<uint32_t> id(tris), dense(tris, kNoObject);
  count = 0;
  for (size_t t = 0; t < tris; ++t) {
    const uint32_t r = find_root(parent, uint32_t(t));
    if (dense[r] == kNoObject) dense[r] = count++;
    id[t] = dense[r];
  }
  return id;
}

ShadowReference shadow_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                 const Camera& camera, const Light& light) {
  return shadow_reference(positions, indices, index_count, camera, light, nullptr);
}

ShadowReference shadow_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                 const Camera& camera, const Light& light, const uint32_t* triangle_objects) {
  ShadowReference out;
  double position[4];  // homogeneous (geom/scene.h)
  light_homogeneous(light, position);
  const int W = camera.width, H = camera.height;
  if (W <= 0 || H <= 0 || W > 16384 || H > 16384) {
    out.error = "shadow reference: image size " + std::to_string(W) + "x" + std::to_string(H) + " out of range";
    return out;
  }
  if (!(camera.fovy_deg > 0 && camera.fovy_deg < 180) || !(camera.near_plane > 0) ||
      !(camera.far_plane > camera.near_plane) || !finite3(camera.eye) || !finite3(camera.target) ||
      !finite3(camera.up) || !finite3(position) || !std::isfinite(position[3])) {
    out.error = "shadow reference: invalid camera or light";
    return out;
  }
  if (index_count % 3) {
    out.error = "shadow reference: index count " + std::to_string(index_count) + " is not a multiple of 3";
    return out;
  }
  const size_t tri_count = index_count / 3;
  for (size_t i = 0; i < index_count; ++i)
    if (indices[i] >= positions.size()) {
      out.error = "shadow reference: triangle " + std::to_string(i / 3) + " has index " + std::to_string(indices[i]) +
                  " out of range (" + std::to_string(positions.size()) + " vertices)";
      return out;
    }
  for (size_t i = 0; i < positions.size(); ++i) {
    const Float3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      out.error = "shadow reference: vertex " + std::to_string(i) + " is not finite";
      return out;
    }
  }

  std::vector<uint32_t> objects;
  if (triangle_objects) {
    objects.assign(triangle_objects, triangle_objects + tri_count);
    std::vector<uint32_t> sorted = objects;
    std::sort(sorted.begin(), sorted.end());
    out.object_count = uint32_t(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
    for (uint32_t& o : objects)  // kNoObject must stay free for "none"
      if (o == kNoObject) o = kNoObject - 1;
  } else {
    objects = triangle_components(positions, indices, index_count, out.object_count);
  }

  std::unique_ptr<RTCDeviceTy, DeviceDeleter> device(rtcNewDevice("threads=1"));
  if (!device) {
    out.error = "shadow reference: Embree device creation failed";
    return out;
  }
  std::unique_ptr<RTCSceneTy, SceneDeleter> scene(rtcNewScene(device.get()));
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);
  // Rays are cast in a local frame centred on the scene's box, so that a scene
  // far from the origin keeps float precision; `extent` (its half diagonal)
  // scales the self-intersection offset of shadow rays.
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
      out.error = "shadow reference: Embree buffer allocation failed";
      return out;
    }
    for (size_t i = 0; i < positions.size(); ++i) {
      const Float3& p = positions[i];
      vb[3 * i] = float(p.x - centre.x), vb[3 * i + 1] = float(p.y - centre.y), vb[3 * i + 2] = float(p.z - centre.z);
    }
    for (size_t i = 0; i < index_count; ++i) ib[i] = indices[i];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene.get(), geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene.get());
  if (rtcGetDeviceError(device.get()) != RTC_ERROR_NONE) {
    out.error = "shadow reference: Embree scene build failed";
    return out;
  }

  // Camera basis: forward f, right r, true up u; the ray direction of a pixel has
  // view-space depth 1, so the ray parameter is the view depth ([near, far]).
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

  out.width = W, out.height = H;
  out.mask.assign(size_t(W) * H, 128);
  out.pixel_class.assign(size_t(W) * H, uint8_t(ShadowClass::None));
  out.object.assign(size_t(W) * H, kNoObject);
  out.blocker.assign(size_t(W) * H, kNoObject);
  std::vector<uint8_t> grazing(size_t(W) * H, 0);
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
      const double bu = rh.hit.u, bv = rh.hit.v;
      const V3 P = A * (1 - bu - bv) + B * bu + C * bv;
      V3 n = normalize(cross(B - A, C - A));
      if (dot(n, eye - P) < 0) n = n * -1.0;  // the side the camera sees
      const V3 to_light = L - P * Lw;
      const double cos_l = dot(n, normalize(to_light));
      const size_t px = size_t(y) * W + x;
      uint8_t& m = out.mask[px];
      const uint32_t own = objects[rh.hit.primID];
      out.object[px] = own;
      m = 0;
      if (std::fabs(cos_l) < 1e-4) grazing[px] = 1;
      if (!(cos_l > 0)) {  // facing away: the object's own terminator
        out.pixel_class[px] = uint8_t(ShadowClass::Self), out.blocker[px] = own;
        continue;
      }
      if (spot && Lw != 0 && dot(normalize(P - L), spot_axis) < spot_cos) {
        out.pixel_class[px] = uint8_t(ShadowClass::Unlit);
        continue;
      }
      const V3 o = P + n * offset;
      const V3 dir = Lw != 0 ? L - o : L;
      // Two queries: another object blocking (Cast), else the pixel's own (Self).
      for (int pass = 0; pass < 2; ++pass) {
        RTCRay ray{};
        ray.org_x = float(o.x), ray.org_y = float(o.y), ray.org_z = float(o.z);
        ray.dir_x = float(dir.x), ray.dir_y = float(dir.y), ray.dir_z = float(dir.z);
        ray.tnear = 0;
        ray.tfar = Lw != 0 ? 1.0f - 1e-4f : std::numeric_limits<float>::infinity();  // the light itself is no blocker
        ray.mask = 0xffffffffu;
        ObjectFilter f;
        rtcInitIntersectContext(&f.context);
        f.context.filter = object_filter;
        f.objects = objects.data();
        (pass == 0 ? f.skip : f.only) = own;
        rtcOccluded1(scene.get(), &f.context, &ray);
        if (ray.tfar == -std::numeric_limits<float>::infinity()) {
          out.pixel_class[px] = uint8_t(pass == 0 ? ShadowClass::Cast : ShadowClass::Self);
          out.blocker[px] = f.accepted;
          break;
        }
      }
      if (out.pixel_class[px] == uint8_t(ShadowClass::None)) out.pixel_class[px] = uint8_t(ShadowClass::Lit), m = 255;
    }

  out.uncertain.assign(size_t(W) * H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const uint8_t v = out.mask[size_t(y) * W + x];
      bool near = grazing[size_t(y) * W + x] != 0;
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && yy >= 0 && xx < W && yy < H && out.mask[size_t(yy) * W + xx] != v) near = true;
        }
      out.uncertain[size_t(y) * W + x] = near;
    }
  out.ok = true;
  return out;
}

}  // namespace geom
