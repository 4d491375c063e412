// A concave crease is no shadow: an open corner (a floor and two walls meeting
// at right angles, seen from inside) lit from inside the corner, so that every
// face turns to the light and nothing stands between any point and the light.
// The exact answer is "all lit"; a map technique that shadows any pixel
// outside the reference's uncertain band draws acne.
//
//      wall B (z = 0, facing +z)
//      |
//      |   light somewhere up here, x > 0, y > 0, z > 0
//      |
//      +---------- floor (y = 0, facing +y)
//     /
//    wall A (x = 0, facing +x)
//
// At a crease the texel centre nearest to a receiver point may fall on the
// other face, and the receiver's plane carried to that centre passes behind
// it (shaders/depth_plane.frag compares at the texel centre). The law: no
// shadowed pixel at all, for ssm, pcf, the focused maps (uniform, psm,
// lispsm) and the silhouette maps' fallback (edsm, esm-exact), on random
// corners (any size, turned about the vertical), random lights (suns and point
// lights inside the corner's octant, from grazing to overhead: N.L >= 0.05 on
// every face) and random cameras inside the octant, at map sizes 64 to 1024.
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

constexpr int kFrames = 12;
constexpr int kSizes[] = {64, 256, 1024};
constexpr Technique kTechniques[] = {Technique::Ssm,     Technique::Pcf,    Technique::Uniform, Technique::Psm,
                                     Technique::Lispsm,  Technique::Edsm,   Technique::EsmExact};

// The corner of size `s` at the origin turned by `yaw` about +y: the floor
// [0,s] x [0,s], wall A on x = 0 and wall B on z = 0, each of height h, each
// its own caster.
geom::Scene corner(float s, float h, float yaw) {
  geom::Scene scene;
  const glm::mat4 r = glm::rotate(glm::mat4(1), yaw, glm::vec3(0, 1, 0));
  auto p = [&](float x, float y, float z) { return glm::vec3(r * glm::vec4(x, y, z, 1)); };
  add_quad(scene, p(0, 0, 0), p(0, 0, s), p(s, 0, s), p(s, 0, 0));  // floor, +y
  tag_caster(scene, 0, 0);
  add_quad(scene, p(0, 0, 0), p(0, h, 0), p(0, h, s), p(0, 0, s));  // wall A, +x
  tag_caster(scene, 2, 1);
  add_quad(scene, p(0, 0, 0), p(s, 0, 0), p(s, h, 0), p(0, h, 0));  // wall B, +z
  tag_caster(scene, 4, 2);
  return scene;
}

// A unit direction with every component at least `lo` (inside the octant).
glm::vec3 octant_direction(std::mt19937& rng, float lo) {
  std::uniform_real_distribution<float> u(0, 1);
  for (;;) {
    const glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(1e-3f));
    if (d.x >= lo && d.y >= lo && d.z >= lo) return d;
  }
}

struct Case {
  int frame = 0, size = 0;
  Technique technique = Technique::Ssm;
  size_t wrong = 0;
};

// Every frame and size for one kind of light; the cases with a wrong pixel.
std::vector<Case> run(bool point, uint32_t seed, size_t& scored) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<Case> bad;
  scored = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    const float s = std::pow(10.0f, -1.0f + 3.0f * u(rng)), h = s * (0.3f + 0.7f * u(rng));
    const float yaw = 6.2831853f * u(rng);
    const geom::Scene scene = corner(s, h, yaw);
    std::string error;
    auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
    EXPECT_TRUE(state) << error;
    if (!state) return bad;
    const glm::mat4 r = glm::rotate(glm::mat4(1), yaw, glm::vec3(0, 1, 0));
    const glm::vec3 to_light = glm::vec3(r * glm::vec4(octant_direction(rng, 0.05f), 0));
    const geom::Light light =
        point ? point_light(glm::vec3(r * glm::vec4(glm::vec3(s * (1.5f + 3 * u(rng))) * octant_direction(rng, 0.3f), 1)))
              : sun(to_light);
    const glm::vec3 eye = glm::vec3(r * glm::vec4(s * (0.4f + 1.6f * u(rng)) * octant_direction(rng, 0.2f), 1));
    const glm::vec3 target = glm::vec3(r * glm::vec4(s * 0.2f * u(rng), h * 0.2f * u(rng), s * 0.2f * u(rng), 1));
    const geom::Camera view = camera(eye, target, 40 + 30 * u(rng), s * 1e-3f, s * 100, 160, 120);
    for (int size : kSizes)
      for (Technique t : kTechniques) {
        geom::ShadowReference ref;
        geom::PngImage mask;
        const Comparison c = render_and_compare(*state, scene, view, light, t, size, &mask, &ref);
        EXPECT_EQ(c.shadowed, 0u) << "the corner has no shadow";
        scored += c.certain;
        if (c.wrong) bad.push_back({frame, size, t, c.wrong});
      }
  }
  return bad;
}

void check(bool point, uint32_t seed) {
  size_t scored = 0;
  const std::vector<Case> bad = run(point, seed, scored);
  for (const Case& c : bad)
    std::printf("frame %d, map %d: %s shadows %zu pixels of a lit corner\n", c.frame, c.size,
                render::technique_name(c.technique), c.wrong);
  std::printf("%s: %zu scored pixels, %zu cases with acne\n", point ? "point" : "sun", scored, bad.size());
  EXPECT_GT(scored, size_t(kFrames) * std::size(kSizes) * std::size(kTechniques) * 4000) << "the corner must fill the views";
  EXPECT_TRUE(bad.empty()) << bad.size() << " cases shadow a lit concave corner";
}

TEST(GlBiasCrease, SunLitCornerHasNoAcne) {
  ASSERT_NE(context(), nullptr);
  check(false, 21);
}

TEST(GlBiasCrease, PointLitCornerHasNoAcne) {
  ASSERT_NE(context(), nullptr);
  check(true, 22);
}

}  // namespace
