// Shadow silhouette maps (sssm; Sen, Cammarano and Hanrahan 2003): for a
// straight-edged occluder (a random triangle held flat above a ground, lit
// from above (the camera between them, looking down) by a directional or a point light) the reconstructed shadow
// boundary lies within one texel of the true one: every pixel whose shadow
// state differs from the ray-cast reference is within one shadow-map texel
// (plus one pixel) of the occluder's projected outline, and sssm gets far fewer
// pixels wrong than the simple shadow map of the same size (the boundary is
// rebuilt between texels, not snapped to them). The default scene's block
// tower (a receiver's own outline on its face) is checked for sssm beside edsm
// in test_gl_edge_shadow_maps.cpp.
#include <algorithm>

#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

constexpr int kImage = 160;   // pixels per side
constexpr int kMap = 32;      // shadow-map texels per side
constexpr float kEye = 2.5f;  // the camera's height, under the plate (at 3): it sees the ground's [-2.5, 2.5] square

// The ground point of pixel (x, y) of the top-down camera (eye at (0, kEye, 0), 90 degrees, up -z).
glm::vec2 ground_of(const geom::Camera& c, int x, int y) {
  const double t = std::tan(c.fovy_deg * M_PI / 360.0) * c.eye[1];
  return glm::vec2(float((2.0 * (x + 0.5) / c.width - 1.0) * t), float((2.0 * (y + 0.5) / c.height - 1.0) * t));
}

float segment_distance(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

struct Case {
  geom::Scene scene;
  geom::Light light;
  glm::vec2 outline[3];  // the triangle's shadow on the ground (x, z)
};

Case random_case(std::mt19937& rng, bool point) {
  std::uniform_real_distribution<float> u(-1, 1);
  Case c;
  add_ground(c.scene, 4);
  tag_caster(c.scene, 0, 0);
  // A triangle of 1.2 to 2 around a centre near the origin, angles over 25 degrees.
  glm::vec3 v[3];
  for (;;) {
    const glm::vec2 centre(0.6f * u(rng), 0.6f * u(rng));
    const float phase = 3.14159f * u(rng);
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const float a = phase + 2.094f * float(k) + 0.6f * u(rng), r = 1.6f + 0.4f * u(rng);
      v[k] = glm::vec3(centre.x + r * std::cos(a), 3.0f, centre.y + r * std::sin(a));
    }
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 e1 = glm::normalize(v[(k + 1) % 3] - v[k]), e2 = glm::normalize(v[(k + 2) % 3] - v[k]);
      ok = ok && glm::dot(e1, e2) < std::cos(glm::radians(25.0f));
    }
    if (ok) break;
  }
  const size_t first = c.scene.sources.size();
  add_triangle(c.scene, v[0], v[1], v[2]);
  add_triangle(c.scene, v[0], v[2], v[1]);  // two-sided: the plate closed on itself
  tag_caster(c.scene, first, 1);
  const glm::vec3 L = point ? glm::vec3(0.8f * u(rng), 9.0f + u(rng), 0.8f * u(rng))
                            : glm::normalize(glm::vec3(0.25f * u(rng), 1.0f, 0.25f * u(rng)));
  c.light = point ? point_light(L) : sun(L);
  for (int k = 0; k < 3; ++k) {
    const glm::vec3 g = point ? L + (v[k] - L) * (L.y / (L.y - v[k].y)) : v[k] - L * (v[k].y / L.y);
    c.outline[k] = glm::vec2(g.x, g.z);
  }
  return c;
}

TEST(GlSssm, BoundaryWithinATexelOfAStraightEdgedOccluder) {
  ASSERT_NE(context(), nullptr);
  std::mt19937 rng(16);
  size_t sssm_wrong = 0, ssm_wrong = 0;
  for (int i = 0; i < 8; ++i) {
    const bool point = i % 2;
    Case c = random_case(rng, point);
    SCOPED_TRACE("case " + std::to_string(i) + (point ? " (point light)" : " (directional light)"));
    std::string error;
    auto state = render::create_state(c.scene, GEOM_SHADER_DIR, error);
    ASSERT_TRUE(state) << error;
    geom::Camera view = camera({0, kEye, 0}, {0, 0, 0}, 90, 0.1f, 100, kImage, kImage);
    set3(view.up, {0, 0, -1});
    // The texel's footprint on the ground of the scene-wide frustum: the map spans the
    // scene's bounding sphere (orthographic) or its angle (point light, seen from about
    // 9 above the ground). sssm draws the frustum fitted to what the camera sees
    // (light_fit.cpp), no wider: its texels are at most this large.
    float bounds[4];
    render::scene_bounds(*state, bounds);
    float texel = 2 * bounds[3] / kMap;
    if (point) {
      const glm::vec3 L(float(c.light.position[0]), float(c.light.position[1]), float(c.light.position[2]));
      const float d = glm::length(glm::vec3(bounds[0], bounds[1], bounds[2]) - L);
      texel = 2 * std::tan(std::asin(std::min(1.0f, bounds[3] / d)) * 1.02f) * L.y / kMap;
    }
    const float pixel = 2 * kEye / kImage;
    geom::PngImage mask;
    const Comparison s = render_and_compare(*state, c.scene, view, c.light, Technique::Sssm, kMap, &mask);
    ssm_wrong += render_and_compare(*state, c.scene, view, c.light, Technique::Ssm, kMap).wrong;
    geom::ShadowReference ref =
        geom::shadow_reference(geom::positions_of(c.scene.positions.data(), c.scene.vertex_count()),
                               c.scene.indices.data(), c.scene.indices.size(), view, c.light);
    ASSERT_TRUE(ref.ok) << ref.error;
    EXPECT_GT(s.shadowed, 2000u);
    float worst = 0;
    size_t wrong = 0;
    for (int y = 0; y < kImage; ++y)
      for (int x = 0; x < kImage; ++x) {
        const size_t k = size_t(y) * kImage + x;
        if (mask.pixels[k] == ref.mask[k] || ref.mask[k] == 128) continue;
        const glm::vec2 p = ground_of(view, x, y);
        float d = 1e30f;
        for (int e = 0; e < 3; ++e) d = std::min(d, segment_distance(p, c.outline[e], c.outline[(e + 1) % 3]));
        worst = std::max(worst, d), ++wrong;
      }
    sssm_wrong += wrong;
    EXPECT_LE(worst, texel + pixel) << wrong << " wrong pixels; texel " << texel << ", pixel " << pixel;
  }
  std::printf("wrong pixels over 8 cases at map %d: sssm %zu, ssm %zu\n", kMap, sssm_wrong, ssm_wrong);
  EXPECT_GT(ssm_wrong, 1000u) << "the simple map should show its staircase at this size";
  EXPECT_LT(sssm_wrong * 4, ssm_wrong);
}

}  // namespace
