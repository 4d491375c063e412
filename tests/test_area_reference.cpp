// The area-light reference (geom/area_reference.h): the light fraction under a
// disc light by stratified ray casting.
//  - radius 0 is the hard reference: the fraction is exactly geom/shadow_reference.h's
//    mask (1 lit, 0 shadow, -1 no geometry) on every pixel of random scenes;
//  - a straight edge: a large plate's edge above the ground casts a penumbra whose
//    fraction at every ground pixel matches the disc's analytic share (the chord
//    cut by the plane through the pixel's point and the edge), for random
//    heights, light positions and radii;
//  - bad input is refused with an error.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geom/area_reference.h"
#include "geom/shadow_reference.h"

namespace {

struct Mesh {
  std::vector<float> p;
  std::vector<uint32_t> i;
  void quad(const float a[3], const float b[3], const float c[3], const float d[3]) {
    const uint32_t base = uint32_t(p.size() / 3);
    for (const float* v : {a, b, c, d}) p.insert(p.end(), {v[0], v[1], v[2]});
    i.insert(i.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  geom::PositionSpan span() const { return geom::positions_of(p.data(), p.size() / 3); }
};

geom::Camera top_down(double x, double size, int pixels) {
  geom::Camera c;
  c.eye[0] = x, c.eye[1] = 10, c.eye[2] = 0;
  c.target[0] = x, c.target[1] = 0, c.target[2] = 0;
  c.up[0] = 0, c.up[1] = 0, c.up[2] = -1;
  c.fovy_deg = 2 * std::atan(size / 10) * 180 / M_PI;
  c.near_plane = 1, c.far_plane = 100;
  c.width = c.height = pixels;
  return c;
}

geom::Light point(double x, double y, double z) {
  const double h[4] = {x, y, z, 1};
  return geom::light_from_homogeneous(h);
}

TEST(AreaReference, RadiusZeroIsTheHardReference) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  for (int k = 0; k < 6; ++k) {
    Mesh m;
    const float g[4][3] = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}};
    m.quad(g[0], g[1], g[2], g[3]);
    for (int b = 0; b < 4; ++b) {  // random floating squares
      const float cx = 2 * u(rng), cz = 2 * u(rng), y = 1.5f + u(rng), s = 0.3f + 0.2f * u(rng);
      const float q[4][3] = {{cx - s, y, cz - s}, {cx - s, y, cz + s}, {cx + s, y, cz + s}, {cx + s, y, cz - s}};
      m.quad(q[0], q[1], q[2], q[3]);
    }
    const geom::Camera cam = top_down(0, 3, 48);
    const geom::Light l = point(u(rng), 5 + u(rng), u(rng));
    const geom::ShadowReference hard = geom::shadow_reference(m.span(), m.i.data(), m.i.size(), cam, l);
    const geom::AreaReference soft = geom::area_light_reference(m.span(), m.i.data(), m.i.size(), cam, l, 0, 4);
    ASSERT_TRUE(hard.ok && soft.ok) << hard.error << soft.error;
    for (size_t i = 0; i < hard.mask.size(); ++i) {
      const float want = hard.mask[i] == 128 ? -1.0f : hard.mask[i] == 255 ? 1.0f : 0.0f;
      ASSERT_EQ(soft.fraction[i], want) << "pixel " << i;
    }
  }
}

TEST(AreaReference, StraightEdgeMatchesTheDiscsShare) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 5; ++k) {
    const double e = 0.5 * (u(rng) - 0.5), ho = 0.8 + 0.6 * u(rng), hl = 3.5 + u(rng), lx = e - 3 - u(rng);
    const double R = 0.2 + 0.4 * u(rng);
    Mesh m;
    const float g[4][3] = {{-6, 0, -6}, {-6, 0, 6}, {6, 0, 6}, {6, 0, -6}};
    m.quad(g[0], g[1], g[2], g[3]);
    const float fe = float(e), fh = float(ho);
    const float plate[4][3] = {{-20, fh, -20}, {-20, fh, 20}, {fe, fh, 20}, {fe, fh, -20}};
    m.quad(plate[0], plate[1], plate[2], plate[3]);
    const double shadow_x = lx + (e - lx) * hl / (hl - ho);  // the centre's shadow edge on the ground
    const geom::Camera cam = top_down(shadow_x, 0.5, 40);
    const geom::Light l = point(lx, hl, 0);
    const geom::AreaReference ref = geom::area_light_reference(m.span(), m.i.data(), m.i.size(), cam, l, R, 256, k);
    ASSERT_TRUE(ref.ok) << ref.error;
    double worst = 0, lo = 1, hi = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        // The ground point of the pixel; the plane through it and the edge (along z).
        const double t = std::tan(cam.fovy_deg * M_PI / 360) * 10;
        const double P[3] = {shadow_x + (2.0 * (x + 0.5) / cam.width - 1) * t, 0,
                             (2.0 * (y + 0.5) / cam.height - 1) * t};
        const double EP[3] = {e - P[0], ho, 0};  // P -> the edge at P's z
        double n[3] = {EP[1], -EP[0], 0};        // cross(z, EP) up to sign: perpendicular to both
        const double nl = std::hypot(n[0], n[1]);
        n[0] /= nl, n[1] /= nl;
        if ((e + 1 - P[0]) * n[0] + ho * n[1] < 0) n[0] = -n[0], n[1] = -n[1];  // positive: the lit side
        const double LP[3] = {lx - P[0], hl, -P[2]};
        const double dl = std::sqrt(LP[0] * LP[0] + LP[1] * LP[1] + LP[2] * LP[2]);
        const double delta = LP[0] * n[0] + LP[1] * n[1];
        const double nw = delta / dl;
        const double uu = std::clamp(delta / (R * std::sqrt(1 - nw * nw)), -1.0, 1.0);
        const double want = (std::acos(-uu) + uu * std::sqrt(1 - uu * uu)) / M_PI;
        const float got = ref.fraction[size_t(y) * cam.width + x];
        ASSERT_GE(got, 0.0f);
        worst = std::max(worst, std::fabs(got - want));
        lo = std::min(lo, double(got)), hi = std::max(hi, double(got));
      }
    EXPECT_LT(worst, 0.03) << "case " << k;
    EXPECT_LT(lo, 0.05) << "the view should reach the umbra";
    EXPECT_GT(hi, 0.95) << "the view should reach the fully lit ground";
  }
}

TEST(AreaReference, RefusesBadInput) {
  Mesh m;
  const float g[4][3] = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}};
  m.quad(g[0], g[1], g[2], g[3]);
  const geom::Camera cam = top_down(0, 3, 8);
  const geom::Light l = point(0, 5, 0);
  EXPECT_FALSE(geom::area_light_reference(m.span(), m.i.data(), m.i.size(), cam, l, -1, 4).ok);
  EXPECT_FALSE(geom::area_light_reference(m.span(), m.i.data(), m.i.size(), cam, l, 0.1, 0).ok);
  geom::Light sun = l;
  sun.type = geom::LightType::Directional;
  EXPECT_FALSE(geom::area_light_reference(m.span(), m.i.data(), m.i.size(), cam, sun, 2.0, 4).ok);
  std::vector<uint32_t> bad = {0, 1, 9};
  EXPECT_FALSE(geom::area_light_reference(m.span(), bad.data(), bad.size(), cam, l, 0.1, 4).ok);
}

}  // namespace
