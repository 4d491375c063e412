// The ray-cast shadow reference (geom/shadow_reference.h) against a closed-form
// answer: a unit box floating over a ground square, where both the visible point
// and the blocking test are slab intersections computed here in double.
//
//   side view          L (point, spot or at infinity)
//                        \
//            +-----+      \        box  [-0.5, 0.5] x [1, 2] x [-0.5, 0.5]
//            |     |
//            +-----+
//   ===========================    ground y = 0, |x|, |z| <= 4
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geom/shadow_reference.h"

namespace {

struct D3 {
  double x, y, z;
};
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return a * (1 / std::sqrt(dot(a, a))); }

const D3 kLo{-0.5, 1, -0.5}, kHi{0.5, 2, 0.5};
const double kGround = 4;

// Slab test: entry parameter and the normal of the entry face, or false.
bool hit_box(D3 o, D3 d, double t0, double t1, double& t, D3& n) {
  double lo[3] = {kLo.x, kLo.y, kLo.z}, hi[3] = {kHi.x, kHi.y, kHi.z}, oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
  int axis = -1;
  double sign = 0;
  for (int k = 0; k < 3; ++k) {
    if (dd[k] == 0) {
      if (oo[k] < lo[k] || oo[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - oo[k]) / dd[k], b = (hi[k] - oo[k]) / dd[k];
    double s = -1;
    if (a > b) std::swap(a, b), s = 1;
    if (a > t0) t0 = a, axis = k, sign = s;
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  t = t0;
  n = {axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0};
  return axis >= 0;
}

void add_scene(std::vector<float>& p, std::vector<uint32_t>& idx) {
  auto quad = [&](D3 a, D3 b, D3 c, D3 d) {
    uint32_t base = uint32_t(p.size() / 3);
    for (D3 v : {a, b, c, d}) p.insert(p.end(), {float(v.x), float(v.y), float(v.z)});
    idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  quad({-kGround, 0, -kGround}, {-kGround, 0, kGround}, {kGround, 0, kGround}, {kGround, 0, -kGround});
  const D3 l = kLo, h = kHi;
  quad({l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z});  // -x
  quad({h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z});  // +x
  quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z});  // -y
  quad({l.x, h.y, l.z}, {l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z});  // +y
  quad({l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, l.y, l.z});  // -z
  quad({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z});  // +z
}

// A point light high above the origin.
geom::Light overhead() {
  geom::Light l;
  l.position[1] = 10;
  return l;
}

uint8_t closed_form(const geom::Camera& c, const geom::Light& light, int x, int y) {
  const D3 eye{c.eye[0], c.eye[1], c.eye[2]};
  const D3 f = unit(D3{c.target[0], c.target[1], c.target[2]} - eye);
  const D3 r = unit(cross(f, {c.up[0], c.up[1], c.up[2]}));
  const D3 u = cross(r, f);
  const double ty = std::tan(c.fovy_deg * M_PI / 360), tx = ty * c.width / c.height;
  const D3 d = f + r * ((2.0 * (x + 0.5) / c.width - 1) * tx) + u * ((1 - 2.0 * (y + 0.5) / c.height) * ty);
  double t = c.far_plane;
  D3 n{0, 0, 0};
  bool hit = hit_box(eye, d, c.near_plane, c.far_plane, t, n);
  if (d.y != 0) {
    const double tg = -eye.y / d.y;
    const D3 g = eye + d * tg;
    if (tg >= c.near_plane && tg <= c.far_plane && (!hit || tg < t) && std::fabs(g.x) <= kGround &&
        std::fabs(g.z) <= kGround)
      hit = true, t = tg, n = {0, eye.y > 0 ? 1.0 : -1.0, 0};
  }
  if (!hit) return 128;
  const D3 P = eye + d * t;
  double h[4];  // homogeneous (geom/scene.h)
  geom::light_homogeneous(light, h);
  const D3 L{h[0], h[1], h[2]};
  const double w = h[3];
  const D3 to_light = L - P * w;
  if (dot(n, to_light) <= 0) return 0;
  if (light.type == geom::LightType::Spot) {
    const D3 axis = unit({light.direction[0], light.direction[1], light.direction[2]});
    if (dot(unit(P - L), axis) < std::cos(light.outer_cone)) return 0;
  }
  double tb;
  D3 nb;
  const D3 o = P + n * 1e-9;
  return hit_box(o, to_light, 0, w != 0 ? 1.0 : 1e30, tb, nb) ? 0 : 255;
}

TEST(ShadowReference, MatchesClosedFormOnRandomLightsAndCameras) {
  std::vector<float> p;
  std::vector<uint32_t> idx;
  add_scene(p, idx);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  size_t shadowed = 0, lit = 0;  // over all trials: the law is not checked on an empty shadow
  for (int trial = 0; trial < 24; ++trial) {
    geom::Camera cam;
    cam.width = 64, cam.height = 48;
    const double a = U(rng) * M_PI;
    cam.eye[0] = float(6 * std::cos(a)), cam.eye[1] = float(3 + 2 * U(rng)), cam.eye[2] = float(6 * std::sin(a));
    cam.target[0] = float(U(rng) * 0.5), cam.target[1] = 0.5f, cam.target[2] = float(U(rng) * 0.5);
    cam.fovy_deg = float(50 + 10 * U(rng));
    const int kind = trial % 3;  // point, spot, directional
    const double h[4] = {float(3 * U(rng)), float(3.5 + U(rng)), float(3 * U(rng)), kind == 2 ? 0.0 : 1.0};
    geom::Light light = geom::light_from_homogeneous(h);
    if (kind == 1) {
      light.type = geom::LightType::Spot;
      for (int k = 0; k < 3; ++k) light.direction[k] = -h[k];
      light.outer_cone = 35 * M_PI / 180;
    }
    const geom::ShadowReference ref =
        geom::shadow_reference(geom::positions_of(p.data(), p.size() / 3), idx.data(), idx.size(), cam, light);
    ASSERT_TRUE(ref.ok) << ref.error;
    size_t certain = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const size_t i = size_t(y) * cam.width + x;
        if (ref.uncertain[i]) continue;
        ++certain;
        shadowed += ref.mask[i] == 0, lit += ref.mask[i] == 255;
        ASSERT_EQ(int(ref.mask[i]), int(closed_form(cam, light, x, y)))
            << "trial " << trial << " pixel " << x << "," << y;
      }
    EXPECT_GT(certain, size_t(cam.width * cam.height / 2));
  }
  EXPECT_GT(shadowed, 1000u);
  EXPECT_GT(lit, 10000u);
}

TEST(ShadowReference, UncertainMarksEveryPixelNextToAnotherValue) {
  std::vector<float> p;
  std::vector<uint32_t> idx;
  add_scene(p, idx);
  geom::Camera cam;
  cam.eye[0] = 3, cam.eye[1] = 5, cam.eye[2] = 6;
  cam.width = 40, cam.height = 30;
  geom::Light light;
  light.position[0] = 1, light.position[1] = 4, light.position[2] = 0.5f;
  const auto ref =
      geom::shadow_reference(geom::positions_of(p.data(), p.size() / 3), idx.data(), idx.size(), cam, light);
  ASSERT_TRUE(ref.ok);
  for (int y = 0; y + 1 < cam.height; ++y)
    for (int x = 0; x + 1 < cam.width; ++x) {
      const size_t i = size_t(y) * cam.width + x;
      for (size_t j : {i + 1, i + cam.width})
        if (ref.mask[i] != ref.mask[j]) {
          EXPECT_TRUE(ref.uncertain[i]);
          EXPECT_TRUE(ref.uncertain[j]);
        }
    }
}

TEST(ShadowReference, EmptySceneIsAllBackground) {
  geom::Camera cam;
  cam.width = 8, cam.height = 6;
  const auto ref = geom::shadow_reference(geom::PositionSpan(), nullptr, 0, cam, overhead());
  ASSERT_TRUE(ref.ok) << ref.error;
  for (uint8_t v : ref.mask) EXPECT_EQ(v, 128);
}

TEST(ShadowReference, RefusesBadInput) {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t bad[3] = {0, 1, 3};
  geom::Camera cam;
  auto r = geom::shadow_reference(geom::positions_of(p, 3), bad, 3, cam, overhead());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("out of range"), std::string::npos) << r.error;
  const float nan_p[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
  const uint32_t good[3] = {0, 1, 2};
  r = geom::shadow_reference(geom::positions_of(nan_p, 3), good, 3, cam, overhead());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("not finite"), std::string::npos) << r.error;
  cam.width = 0;
  r = geom::shadow_reference(geom::positions_of(p, 3), good, 3, cam, overhead());
  EXPECT_FALSE(r.ok);
  cam.width = 8;
  cam.far_plane = cam.near_plane;
  r = geom::shadow_reference(geom::positions_of(p, 3), good, 3, cam, overhead());
  EXPECT_FALSE(r.ok);
}

}  // namespace
