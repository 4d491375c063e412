// Shadow-map techniques (ssm, pcf, cube, and the focused maps psm, lispsm,
// uniform of geom/focus.h) against the ray-cast reference
// (geom/shadow_reference.h), headless on EGL (llvmpipe without a GPU).
//
// Law: away from true boundaries (the reference's uncertain set), a shadow map
// of adequate size agrees with the exact mask on all but a small fraction of
// pixels: the fraction allowed covers the map's texel-sized staircase and the
// bias near contact, not inverted or missing shadows (which cost tens of percent).
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

// Ground with a few boxes (closed) of different sizes and yaw:
//
//   side view          ____
//            ___      |    |   __
//           |   |     |    |  |__|   <- floating box (its shadow detached)
//   ________|___|_____|____|________ y = 0
geom::Scene blocks_scene() {
  geom::Scene s;
  add_ground(s, 6);
  add_box(s, box_at({-1.5f, 0.6f, 0}, {0.6f, 0.6f, 0.6f}, 20));
  add_box(s, box_at({1.0f, 1.0f, -1.0f}, {0.5f, 1.0f, 0.8f}, -35));
  add_box(s, box_at({1.8f, 1.6f, 1.5f}, {0.3f, 0.3f, 0.3f}, 10));
  return s;
}

geom::Camera default_view() { return camera({4, 5, 8}, {0, 0.5f, 0}, 50, 0.1f, 100, 200, 150); }

struct Case {
  const char* name;
  geom::Light light;
};

std::vector<Case> light_cases() {
  std::vector<Case> cases;
  cases.push_back({"point", point_light({-1.5f, 3.5f, -3.5f})});
  cases.push_back({"point outside the scene box", point_light({-5.0f, 9.0f, -8.0f})});
  geom::Light spot = point_light({-3, 7, 2});
  spot.type = geom::LightType::Spot;
  for (int k = 0; k < 3; ++k) spot.direction[k] = glm::vec3(3, -7, -2)[k];
  spot.outer_cone = 40 * M_PI / 180;
  cases.push_back({"spot", spot});
  geom::Light dir;
  dir = sun({-0.6f, 0.8f, -0.5f});
  cases.push_back({"directional", dir});
  return cases;
}

TEST(GlShadowMaps, MasksAgreeWithTheReferenceAwayFromBoundaries) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = blocks_scene();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (const Case& c : light_cases())
    for (Technique t :
         {Technique::Ssm, Technique::Pcf, Technique::Cube, Technique::Psm, Technique::Lispsm, Technique::Uniform}) {
      if (t == Technique::Cube && directional(c.light)) continue;
      const Comparison cmp = render_and_compare(*state, scene, default_view(), c.light, t, 1024);
      SCOPED_TRACE(std::string(c.name) + " " + render::technique_name(t));
      std::printf("%s %s: %zu certain, %zu wrong (%.3f%%), lit %zu shadowed %zu background %zu\n", c.name,
                  render::technique_name(t), cmp.certain, cmp.wrong, 100 * cmp.error(), cmp.lit, cmp.shadowed,
                  cmp.background);
      EXPECT_GT(cmp.lit, 1000u);
      EXPECT_GT(cmp.shadowed, 1000u);
      EXPECT_LT(cmp.error(), 0.01);
    }
}

}  // namespace
