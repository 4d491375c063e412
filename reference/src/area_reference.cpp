// The light fraction under a disc light by ray casting with Embree 3 (see
// geom/area_reference.h): the visible point of each pixel as in
// shadow_reference.cpp, then `samples` stratified shadow rays to the disc.
#include "geom/area_reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "ray_scene.h"

namespace geom {
namespace {

using namespace ray_scene;  // V3, dot, cross, the scene, rays and light (ray_scene.h)

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

}  // namespace

AreaReference area_light_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                   const Camera& camera, const Light& light, double radius, int samples,
                                   uint32_t seed) {
  AreaReference out;
  double position[4];
  light_homogeneous(light, position);
  const int W = camera.width, H = camera.height;
  if (samples < 1 || samples > 65536) return out.error = "area reference: samples out of range (1..65536)", out;
  if (!(radius >= 0) || !std::isfinite(radius) || (position[3] == 0 && radius >= M_PI / 2))
    return out.error = "area reference: light radius out of range", out;
  RayCast cast;
  out.error =
      prepare_ray_cast("area reference", positions, indices, index_count, camera, light, RTC_SCENE_FLAG_NONE, cast);
  if (!out.error.empty()) return out;
  const RayScene& rs = cast.scene;
  const EyeRays& eye = cast.eye;
  const LocalLight& light_local = cast.light;
  const double Lw = light_local.w, offset = cast.offset;
  const V3 L = light_local.L;
  const int grid = std::max(1, int(std::lround(std::sqrt(double(samples)))));
  const int n = grid * grid;  // the stratified count actually cast

  out.width = W, out.height = H;
  out.fraction.assign(size_t(W) * H, -1.0f);
  RTCIntersectContext context;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      V3 P, nrm;
      uint32_t triangle;
      if (!primary_hit(rs, eye, camera, x, y, positions, indices, P, nrm, triangle)) continue;
      float& frac = out.fraction[size_t(y) * W + x];
      frac = 0;
      const V3 to_light = normalize(L - P * Lw);  // towards the light's centre
      if (!(dot(nrm, to_light) > 0)) continue;
      if (light_local.outside_cone(P)) continue;
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
        rtcOccluded1(rs.scene.get(), &context, &ray);
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
