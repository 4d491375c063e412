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

#include "ray_scene.h"

namespace geom {
namespace {

using namespace ray_scene;  // V3, dot, cross, the scene, rays and light (ray_scene.h)

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

// |N.L| below it: a parallel or grazing face, in the uncertain band (the
// shading, shaders/shade.frag, gives it no direct light).
constexpr double kGrazingCos = 1e-4;

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

namespace {

// The object of each triangle: the caller's ids (kNoObject kept free for
// "none"), else the connected components; `count` set to how many there are.
std::vector<uint32_t> object_ids(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                 const uint32_t* triangle_objects, uint32_t& count) {
  if (!triangle_objects) return triangle_components(positions, indices, index_count, count);
  std::vector<uint32_t> objects(triangle_objects, triangle_objects + index_count / 3);
  std::vector<uint32_t> sorted = objects;
  std::sort(sorted.begin(), sorted.end());
  count = uint32_t(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  for (uint32_t& o : objects)
    if (o == kNoObject) o = kNoObject - 1;
  return objects;
}

// The class of a lit-facing point P (normal n) of object `own` inside the
// light's cone: Cast when another object blocks the segment to the light, else
// Self when its own object does, else Lit; `blocker` the blocking object.
ShadowClass trace_to_light(const RayCast& cast, const std::vector<uint32_t>& objects, const V3& P, const V3& n,
                           uint32_t own, uint32_t& blocker) {
  const double Lw = cast.light.w;
  const V3 o = P + n * cast.offset;
  const V3 dir = Lw != 0 ? cast.light.L - o : cast.light.L;
  for (int pass = 0; pass < 2; ++pass) {  // another object blocking (Cast), else the pixel's own (Self)
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
    rtcOccluded1(cast.scene.scene.get(), &f.context, &ray);
    if (ray.tfar == -std::numeric_limits<float>::infinity()) {
      blocker = f.accepted;
      return pass == 0 ? ShadowClass::Cast : ShadowClass::Self;
    }
  }
  return ShadowClass::Lit;
}

// The uncertain band: every pixel next to one of another mask value, and every
// grazing pixel (|N.L| under kGrazingCos).
void mark_uncertain(ShadowReference& out, const std::vector<uint8_t>& grazing) {
  const int W = out.width, H = out.height;
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
}

}  // namespace

ShadowReference shadow_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                 const Camera& camera, const Light& light, const uint32_t* triangle_objects) {
  ShadowReference out;
  const int W = camera.width, H = camera.height;
  RayCast cast;
  out.error = prepare_ray_cast("shadow reference", positions, indices, index_count, camera, light,
                               RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION, cast);
  if (!out.error.empty()) return out;
  const std::vector<uint32_t> objects = object_ids(positions, indices, index_count, triangle_objects, out.object_count);
  out.width = W, out.height = H;
  out.mask.assign(size_t(W) * H, 128);
  out.pixel_class.assign(size_t(W) * H, uint8_t(ShadowClass::None));
  out.object.assign(size_t(W) * H, kNoObject);
  out.blocker.assign(size_t(W) * H, kNoObject);
  std::vector<uint8_t> grazing(size_t(W) * H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      V3 P, n;
      uint32_t triangle;
      if (!primary_hit(cast.scene, cast.eye, camera, x, y, positions, indices, P, n, triangle)) continue;
      const double cos_l = dot(n, normalize(cast.light.L - P * cast.light.w));
      const size_t px = size_t(y) * W + x;
      const uint32_t own = objects[triangle];
      out.object[px] = own;
      out.mask[px] = 0;
      if (std::fabs(cos_l) < kGrazingCos) grazing[px] = 1;
      ShadowClass c;
      if (!(cos_l > 0)) {  // facing away: the object's own terminator
        c = ShadowClass::Self, out.blocker[px] = own;
      } else if (cast.light.outside_cone(P)) {
        c = ShadowClass::Unlit;
      } else {
        c = trace_to_light(cast, objects, P, n, own, out.blocker[px]);
      }
      out.pixel_class[px] = uint8_t(c);
      if (c == ShadowClass::Lit) out.mask[px] = 255;
    }
  mark_uncertain(out, grazing);
  out.ok = true;
  return out;
}

}  // namespace geom
