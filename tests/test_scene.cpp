// geom/scene.h: the one light and the one camera of the project, and their
// conversions: the homogeneous light the shaders take (and back), the light a
// scene is shown with, and a camera's gluLookAt + gluPerspective matrices.
// Laws over random lights and cameras, the awkward ones included (lights far
// from the origin, unnormalized directions, grazing up vectors, an infinite
// far plane).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geom/scene.h"

namespace {

// Column-major 4x4 times (x, y, z, w).
void transform(const double m[16], const double p[4], double out[4]) {
  for (int r = 0; r < 4; ++r) out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * p[3];
}

double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

TEST(Scene, HomogeneousLightRoundTrips) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> scale(-6, 6);  // 1e-6 .. 1e6 from the origin
  for (int trial = 0; trial < 2000; ++trial) {
    geom::Light l;
    l.type = geom::LightType(trial % 3);
    const double s = std::pow(10.0, scale(rng));
    for (int k = 0; k < 3; ++k) l.position[k] = u(rng) * s, l.direction[k] = u(rng) * (trial % 7 + 1);
    double h[4];
    geom::light_homogeneous(l, h);
    const geom::Light back = geom::light_from_homogeneous(h);
    if (l.type == geom::LightType::Directional) {
      // w = 0 and (x, y, z) points towards the light: against where it travels.
      EXPECT_EQ(h[3], 0);
      EXPECT_LT(dot3(h, l.direction), 0);
      EXPECT_EQ(back.type, geom::LightType::Directional);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(back.direction[k], l.direction[k]);
    } else {
      // Point and spot: the position with w = 1; back as a point light at it.
      EXPECT_EQ(h[3], 1);
      EXPECT_EQ(back.type, geom::LightType::Point);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(h[k], l.position[k]);
        EXPECT_EQ(back.position[k], l.position[k]);
      }
    }
  }
  // Any w != 0 is a point at (x, y, z) / w.
  const double h[4] = {2, -4, 6, 2};
  const geom::Light p = geom::light_from_homogeneous(h);
  EXPECT_EQ(p.type, geom::LightType::Point);
  EXPECT_DOUBLE_EQ(p.position[0], 1);
  EXPECT_DOUBLE_EQ(p.position[1], -2);
  EXPECT_DOUBLE_EQ(p.position[2], 3);
}

TEST(Scene, LightFromSceneIsTheFirstElseFromAbove) {
  std::vector<geom::Light> lights(2);
  lights[0].name = "first", lights[1].name = "second";
  EXPECT_EQ(geom::light_from_scene(lights).name, "first");
  const geom::Light d = geom::light_from_scene({});
  EXPECT_EQ(d.type, geom::LightType::Directional);
  EXPECT_LT(d.direction[1], 0);  // travels downwards
}

TEST(Scene, LookAtMapsTheFrustumToClipSpace) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const double s = std::pow(10.0, 4 * u(rng));
    double eye[3], target[3], up[3];
    for (int k = 0; k < 3; ++k) eye[k] = u(rng) * s, target[k] = eye[k] + u(rng), up[k] = u(rng);
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    const double fl = std::sqrt(dot3(f, f)), ul = std::sqrt(dot3(up, up));
    if (fl < 1e-3 || ul < 1e-3 || std::fabs(dot3(f, up)) > 0.99 * fl * ul) continue;  // degenerate: see below
    for (double& c : f) c /= fl;
    const double fovy = 5 + 170 * (u(rng) * 0.5 + 0.5), aspect = std::pow(2.0, 2 * u(rng));
    const double n = 0.01 + (u(rng) + 1), far = trial % 10 == 0 ? INFINITY : n * (2 + 1000 * (u(rng) + 1));
    const geom::CameraMatrices cam = geom::camera_look_at(eye, target, up, fovy, aspect, n, far);
    // The eye goes to the view origin; the target onto -z at its distance.
    const double e4[4] = {eye[0], eye[1], eye[2], 1}, t4[4] = {target[0], target[1], target[2], 1};
    double ev[4], tv[4];
    transform(cam.view, e4, ev), transform(cam.view, t4, tv);
    const double tol = 1e-9 * (s + 1);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ev[k], 0, tol) << trial;
    EXPECT_NEAR(tv[0], 0, tol);
    EXPECT_NEAR(tv[1], 0, tol);
    EXPECT_NEAR(tv[2], -fl, tol);
    // The up vector lands in the view's y-z plane, on the +y side.
    const double up4[4] = {up[0], up[1], up[2], 0};
    double uv[4];
    transform(cam.view, up4, uv);
    EXPECT_NEAR(uv[0], 0, 1e-9 * ul);
    EXPECT_GT(uv[1], 0);
    // Points on the near and far planes go to depth -1 and +1 (w > 0); the
    // frustum's corners to x, y = +-1.
    const double ty = std::tan(fovy * M_PI / 360), tx = ty * aspect;
    const double depths[2] = {n, std::isinf(far) ? 1e300 : far};
    for (int d = 0; d < 2; ++d)
      for (int corner = 0; corner < 4; ++corner) {
        const double z = depths[d], sx = corner & 1 ? 1 : -1, sy = corner & 2 ? 1 : -1;
        const double p[4] = {sx * tx * z, sy * ty * z, -z, 1};
        double c[4];
        transform(cam.projection, p, c);
        ASSERT_GT(c[3], 0);
        EXPECT_NEAR(c[0] / c[3], sx, 1e-9);
        EXPECT_NEAR(c[1] / c[3], sy, 1e-9);
        EXPECT_NEAR(c[2] / c[3], d == 0 ? -1 : 1, 1e-6) << "fovy " << fovy << " near " << n << " far " << far;
      }
    ++checked;
  }
  EXPECT_GT(checked, 900);
}

TEST(Scene, DegenerateCamerasAreMarkedNotHidden) {
  const double eye[3] = {1, 2, 3}, up[3] = {0, 1, 0}, along_up[3] = {1, 5, 3};
  EXPECT_TRUE(std::isnan(geom::camera_look_at(eye, eye, up, 60, 1, 0.1, 10).projection[0]));       // eye == target
  EXPECT_TRUE(std::isnan(geom::camera_look_at(eye, along_up, up, 60, 1, 0.1, 10).projection[0]));  // up along view
  const double target[3] = {0, 0, 0};
  EXPECT_TRUE(std::isnan(geom::camera_look_at(eye, target, up, 0, 1, 0.1, 10).projection[0]));
  EXPECT_TRUE(std::isnan(geom::camera_look_at(eye, target, up, 180, 1, 0.1, 10).projection[0]));
  EXPECT_TRUE(std::isnan(geom::camera_look_at(eye, target, up, 60, 0, 0.1, 10).projection[0]));
  EXPECT_FALSE(std::isnan(geom::camera_look_at(eye, target, up, 60, 1, 0.1, 10).projection[0]));
}

TEST(Scene, EngineMatricesAreTakenAsTheyAre) {
  float view[16], proj[16];
  for (int i = 0; i < 16; ++i) view[i] = 0.1f * i - 0.7f, proj[i] = 1.0f / (i + 1);
  const geom::CameraMatrices cam = geom::camera_from_matrices(view, proj);
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(cam.view[i], double(view[i]));
    EXPECT_EQ(cam.projection[i], double(proj[i]));
  }
}

}  // namespace
