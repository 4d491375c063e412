// The extended shadow maps of seed 000 (esm, the paper's lookup) and esm-exact
// (its quads drawn with a depth-resolved priority, the boundary on the true
// edge; render/src/esm.cpp) against the simple shadow map at the same map
// size, scored by class against the ray-cast reference (geom/shadow_error.h).
//
//  - a jenga tower under an oblique sun: every block shadows the block below
//    it across gaps of a fraction of a texel, the case where the paper's
//    0.707-texel dilation fills the gaps (with the dilation's z-bias at 2e-3
//    of window depth instead of 2e-2 esm got 320 / 615 cast-class pixels
//    wrong against ssm's 347 / 114 at 128 / 256, and this test failed);
//  - a point light inside the scene's bounds (six cube faces with their edge
//    maps): the crossed pipes' shadows on the wall and the ground.
#include "geom/shadow_error.h"
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

// Twelve levels of three blocks, each block its own object (so one block's
// shadow on the block below is cast-class), 0.002 apart vertically.
geom::Scene jenga_tower() {
  geom::Scene s;
  add_ground(s, 4);
  tag_caster(s, 0, 0);
  uint32_t id = 1;
  for (int level = 0; level < 12; ++level)
    for (int k = 0; k < 3; ++k) {
      const size_t first = s.sources.size();
      const float off = 0.52f * float(k - 1), y = 0.15f + 0.3f * float(level);
      const bool turn = level % 2;
      add_box(s, box_at(turn ? glm::vec3(off, y, 0) : glm::vec3(0, y, off),
                        turn ? glm::vec3(0.25f, 0.149f, 0.78f) : glm::vec3(0.78f, 0.149f, 0.25f)));
      tag_caster(s, first, id++);
    }
  return s;
}

geom::Scene crossed_pipes() {
  geom::Scene s;
  add_ground(s, 4);
  tag_caster(s, 0, 0);
  size_t first = s.sources.size();
  add_quad(s, {-4, 0, -2}, {4, 0, -2}, {4, 4, -2}, {-4, 4, -2});  // wall facing +z
  tag_caster(s, first, 1);
  first = s.sources.size();
  add_pipe(s, {-2.5f, 0.4f, -0.5f}, {2.5f, 3.2f, -0.3f}, 0.18f, 16);
  tag_caster(s, first, 2);
  first = s.sources.size();
  add_pipe(s, {-2.5f, 3.0f, -0.2f}, {2.5f, 0.5f, -0.6f}, 0.14f, 16);
  tag_caster(s, first, 3);
  return s;
}

// Issue 18's goal for ESM, esm@N error_cast <= ssm@N / 3, met by esm-exact on
// the tower; the paper's esm at least beats ssm there.
TEST(GlEsm, JengaBlocksShadowingTheBlockBelow) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = jenga_tower();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Light light = sun({0.5f, 1.0f, 0.3f});
  const geom::Camera view = camera({3.5f, 3.0f, 4.5f}, {0, 1.8f, 0}, 45, 0.1f, 100, 240, 180);
  for (int size : {128, 256}) {
    const geom::ShadowError s = score(*state, scene, view, light, Technique::Ssm, size);
    const geom::ShadowError e = score(*state, scene, view, light, Technique::Esm, size);
    const geom::ShadowError x = score(*state, scene, view, light, Technique::EsmExact, size);
    std::printf("jenga tower, map %d: wrong cast-class pixels ssm %zu, esm %zu, esm-exact %zu (of %zu); visible %zu %zu %zu\n",
                size, s.wrong_cast, e.wrong_cast, x.wrong_cast, s.cast_pixels, s.wrong_visible, e.wrong_visible, x.wrong_visible);
    SCOPED_TRACE("map " + std::to_string(size));
    EXPECT_GT(s.cast_pixels, 3000u);
    EXPECT_GT(s.wrong_cast, 100u) << "the simple shadow map should miss the blocks' thin shadows at this size";
    EXPECT_LE(x.wrong_cast * 3, s.wrong_cast);
    EXPECT_LT(e.wrong_cast, s.wrong_cast);
  }
}

// A point light inside the scene's bounds, drawn as six faces: both beat ssm
// (the cube technique) on the cast class at two map sizes, esm-exact by 3x.
TEST(GlEsm, PointLightInsideTheScene) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Light light = point_light({0.8f, 3.6f, 1.5f});  // the box is [-4, 4] x [0, 4] x [-4, 4]
  const geom::Camera view = camera({-1.5f, 2.2f, 6.0f}, {0, 1.4f, -1.0f}, 50, 0.1f, 100, 240, 180);
  for (int size : {40, 64}) {
    const geom::ShadowError s = score(*state, scene, view, light, Technique::Ssm, size);
    const geom::ShadowError e = score(*state, scene, view, light, Technique::Esm, size);
    const geom::ShadowError x = score(*state, scene, view, light, Technique::EsmExact, size);
    std::printf("point light inside, map %d: wrong cast-class pixels ssm %zu, esm %zu, esm-exact %zu (of %zu)\n", size,
                s.wrong_cast, e.wrong_cast, x.wrong_cast, s.cast_pixels);
    SCOPED_TRACE("map " + std::to_string(size));
    EXPECT_GT(s.cast_pixels, 3000u);
    EXPECT_GT(s.wrong_cast, 50u) << "the simple shadow map should show its staircase at this size";
    EXPECT_LT(e.wrong_cast, s.wrong_cast);
    EXPECT_LE(x.wrong_cast * 3, s.wrong_cast);
  }
}

}  // namespace
