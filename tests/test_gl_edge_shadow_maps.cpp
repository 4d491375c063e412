// Edge distance (edsm, 001) and extended (esm, 000) shadow maps against the
// simple shadow map at the same map size, on the crossed-pipes scene: both
// reconstruct the silhouette between texels, so their masks are closer to the
// ray-cast reference than the simple map's. Also: they agree with the
// reference away from boundaries as well as a shadow map does.
//
//   top view:   wall  ==================
//                        \      /
//                         \    /        two pipes crossing in front of the
//                          \  /         wall, a light behind the viewer
//                           \/          casting their shadows onto it
//                           /\.
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

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

geom::Camera front_view() {  // the crossing of the pipes' shadows on the wall
  return camera({0.5f, 2.0f, 6.5f}, {0, 1.7f, -2.0f}, 24, 0.1f, 100, 240, 180);
}

std::vector<geom::Light> lights() {
  std::vector<geom::Light> out;
  geom::Light point;
  point = point_light({1.5f, 4.0f, 9.0f});
  out.push_back(point);
  geom::Light spot = point;
  spot = point_light({-1.0f, 5.0f, 8.5f});
  spot.type = geom::LightType::Spot;
  for (int k = 0; k < 3; ++k) spot.direction[k] = glm::vec3(0.5f, -3.0f, -9.0f)[k];
  spot.outer_cone = 25 * M_PI / 180;
  out.push_back(spot);
  geom::Light dir;
  dir = sun({0.3f, 0.5f, 1.0f});
  out.push_back(dir);
  return out;
}

// Summed over a point, a spot and a directional light at each map size.
TEST(GlEdgeShadowMaps, CloserToTheReferenceThanTheSimpleShadowMap) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (int size : {96, 160}) {
    size_t ssm = 0, edsm = 0, esm = 0, shadowed = 0;
    for (const geom::Light& l : lights()) {
      const Comparison s = render_and_compare(*state, scene, front_view(), l, Technique::Ssm, size);
      ssm += s.wrong, shadowed += s.shadowed;
      edsm += render_and_compare(*state, scene, front_view(), l, Technique::Edsm, size).wrong;
      esm += render_and_compare(*state, scene, front_view(), l, Technique::Esm, size).wrong;
    }
    std::printf("map %d: wrong pixels ssm %zu, edsm %zu, esm %zu (reference shadowed %zu)\n", size, ssm, edsm, esm,
                shadowed);
    SCOPED_TRACE("map " + std::to_string(size));
    EXPECT_GT(shadowed, 10000u);
    EXPECT_GT(ssm, 150u) << "the simple shadow map should show its staircase at this size";
    EXPECT_LT(edsm, ssm);
    EXPECT_LT(esm, ssm);
  }
}

TEST(GlEdgeShadowMaps, AgreeWithTheReferenceAtALargeMapSize) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (const geom::Light& l : lights())
    for (Technique t : {Technique::Edsm, Technique::Esm}) {
      const Comparison c = render_and_compare(*state, scene, front_view(), l, t, 1024);
      SCOPED_TRACE(render::technique_name(t));
      EXPECT_LT(c.error(), 0.005) << c.wrong << " of " << c.certain;
    }
}

}  // namespace
