// Shadow-map techniques (ssm, pcf, cube, and the focused maps psm, lispsm,
// uniform of geom/focus.h) against the ray-cast reference
// (geom/shadow_reference.h), headless on EGL (llvmpipe without a GPU).
//
// Law: away from true boundaries (the reference's uncertain set), a shadow map
// of adequate size agrees with the exact mask on all but a small fraction of
// pixels: the fraction allowed covers the map's texel-sized staircase and the
// bias near contact, not inverted or missing shadows (which cost tens of percent).
#include "test_gl_common.h"

using namespace gltest;
using viewer::Technique;

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

viewer::View default_view() {
  viewer::View v;
  v.eye = {4, 5, 8};
  v.target = {0, 0.5f, 0};
  v.fovy_deg = 50;
  v.near_plane = 0.1f;
  v.far_plane = 100;
  v.width = 200, v.height = 150;
  return v;
}

viewer::LightSetup point_light(glm::vec3 p) {
  viewer::LightSetup l;
  l.position = glm::vec4(p, 1);
  return l;
}

struct Case {
  const char* name;
  viewer::LightSetup light;
};

std::vector<Case> light_cases() {
  std::vector<Case> cases;
  cases.push_back({"point", point_light({-1.5f, 3.5f, -3.5f})});
  cases.push_back({"point outside the scene box", point_light({-5.0f, 9.0f, -8.0f})});
  viewer::LightSetup spot = point_light({-3, 7, 2});
  spot.spot = true;
  spot.spot_direction = glm::vec3(3, -7, -2);
  spot.spot_angle_deg = 40;
  cases.push_back({"spot", spot});
  viewer::LightSetup dir;
  dir.position = glm::vec4(-0.6f, 0.8f, -0.5f, 0);
  cases.push_back({"directional", dir});
  return cases;
}

TEST(GlShadowMaps, MasksAgreeWithTheReferenceAwayFromBoundaries) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = blocks_scene();
  std::string error;
  auto state = viewer::create_state(scene, GEOMVIEW_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (const Case& c : light_cases())
    for (Technique t : {Technique::Ssm, Technique::Pcf, Technique::Cube, Technique::Psm, Technique::Lispsm,
                        Technique::Uniform}) {
      if (t == Technique::Cube && c.light.position.w == 0) continue;
      const Comparison cmp = render_and_compare(*state, scene, default_view(), c.light, t, 1024);
      SCOPED_TRACE(std::string(c.name) + " " + viewer::technique_name(t));
      std::printf("%s %s: %zu certain, %zu wrong (%.3f%%), lit %zu shadowed %zu background %zu\n", c.name,
                  viewer::technique_name(t), cmp.certain, cmp.wrong, 100 * cmp.error(), cmp.lit, cmp.shadowed,
                  cmp.background);
      EXPECT_GT(cmp.lit, 1000u);
      EXPECT_GT(cmp.shadowed, 1000u);
      EXPECT_LT(cmp.error(), 0.01);
    }
}

}  // namespace
