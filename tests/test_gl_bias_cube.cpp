// The cube map's depth bias falls as the map grows (Gerasimov 2004's
// omnidirectional map, render/src/cube.cpp), on two of geombench's frames: a
// rippled sphere's terminator (below), and the near-plane frame: the
// bundled scene seen from 8 units with the camera's near plane 6 units out, so
// that it cuts the crossed pipes open and shows their inner walls. A pipe's
// wall seen from inside is shadowed by the pipe's own near side; close to the
// pipe's terminator (as the light sees it) the two are a thin wedge apart,
// thinner than any fixed share of the distance. A multiplicative bias (a fixed
// 3% of the squared distance, Gerasimov 2004, Sect. 12.3.7) lights that wedge
// at every size, so its error stayed near 0.15-0.19% of the visible pixels from
// 512 to 4096 texels and rose with the map; a slope-scaled bias in the light's
// own distance (shaders/cube_distance.frag) shrinks with the texel.
// The law (the size law for every map technique): error_visible at
// 4096 at most half of 512's, no size worse than the one before by more than
// 0.02 points; and error_self falls the same way.
#include "gl_fixtures.h"

using namespace gltest;

namespace {

// The rippled sphere's terminator under a point light: the ripples' crests
// shadow their troughs at grazing incidence, gaps thinner than a fixed share
// of the distance. error_self halves as the map doubles from 1024 to 4096
// (a multiplicative bias stopped falling at 2048: 0.152 / 0.084 / 0.085%) and
// stays under 0.2% at 1024.
TEST(GlBiasCube, RippledTerminatorErrorFallsAsTheMapGrows) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = rippled_sphere(500);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 640, 480);
  const geom::Light light = point_light({2, 4, 1.5f});
  const int sizes[] = {1024, 2048, 4096};
  double self[3];
  for (int k = 0; k < 3; ++k) {
    const geom::ShadowError e = score(*state, scene, view, light, render::Technique::Cube, sizes[k]);
    self[k] = e.error_self;
    std::printf("rippled sphere, cube map %d: error_self %.3f%% (%zu of %zu)\n", sizes[k], 100 * e.error_self,
                e.wrong_self, e.self_pixels);
    if (k == 0) EXPECT_GT(e.self_pixels, 50000u) << "the view must show the sphere's terminator";
  }
  EXPECT_LT(self[0], 0.002) << "error_self at 1024";
  for (int k = 1; k < 3; ++k) EXPECT_LE(self[k], self[k - 1] * 0.6) << "error_self halves from " << sizes[k - 1];
}

class GlBiasCubeDefault : public DefaultSceneTest {};

TEST_F(GlBiasCubeDefault, ErrorFallsAsTheMapGrowsOnTheNearPlaneFrame) {
  const geom::Camera view = camera({6, 3, 5}, {2.5f, 1.2f, -1}, 45, 6, 100, 640, 480);
  const geom::Light light = geom::light_from_scene(scene.lights);
  ASSERT_NE(light.type, geom::LightType::Directional) << "the cube map needs the scene's point light";
  const int sizes[] = {512, 1024, 2048, 4096};
  double self[4], visible[4];
  for (int k = 0; k < 4; ++k) {
    const geom::ShadowError e = score(*state, scene, view, light, render::Technique::Cube, sizes[k]);
    self[k] = e.error_self, visible[k] = e.error_visible;
    std::printf("cube map %d: error_self %.3f%% (%zu of %zu), error_visible %.3f%% (%zu of %zu)\n", sizes[k],
                100 * e.error_self, e.wrong_self, e.self_pixels, 100 * e.error_visible, e.wrong_visible,
                e.visible_pixels);
    if (k == 0) EXPECT_GT(e.self_pixels, 20000u) << "the view must show the pipes' inner walls";
  }
  for (int k = 1; k < 4; ++k) {
    EXPECT_LE(visible[k], visible[k - 1] + 0.0002) << "error_visible grows from " << sizes[k - 1] << " to " << sizes[k];
    EXPECT_LE(self[k], self[k - 1] + 0.0002) << "error_self grows from " << sizes[k - 1] << " to " << sizes[k];
  }
  EXPECT_LE(visible[3], visible[0] / 2) << "error_visible at 4096 at most half of 512's";
  EXPECT_LE(self[3], self[0] / 2) << "error_self at 4096 at most half of 512's";
  EXPECT_LT(self[2], 0.002) << "error_self at 2048";
}

}  // namespace
