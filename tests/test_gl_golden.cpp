// Golden images: every technique on the bundled default scene (data/
// default_scene.gltf), shaded colour at 160 x 120 with its point light and its
// directional light, compared with tests/golden/<technique>_<light>.png.
//
// Tolerance (llvmpipe renders deterministically; the margin absorbs other
// drivers and Mesa versions): at most 1% of the pixels may differ by more than
// 24 levels in some channel, and the mean absolute difference must stay under
// 2 levels. GEOM_UPDATE_GOLDEN=1 rewrites the files instead of comparing.
#include <cstdlib>

#include "geom/import.h"
#include "gl_fixtures.h"

using namespace gltest;

namespace {

struct Light {
  const char* name;
  geom::Light setup;
};

// The scene's own point and directional lights, as the scene declares them.
std::vector<Light> golden_lights(const geom::Scene& scene) {
  std::vector<Light> out;
  for (const geom::Light& l : scene.lights) {
    if (l.type == geom::LightType::Directional) out.push_back({"directional", l});
    if (l.type == geom::LightType::Point) out.push_back({"point", l});
  }
  return out;
}

TEST(GlGolden, EveryTechniqueOnTheDefaultScene) {
  ASSERT_NE(context(), nullptr);
  const std::string path = std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf";
  geom::ImportResult imported = geom::import_file(path);
  ASSERT_TRUE(imported.ok) << imported.error;
  const std::vector<Light> lights = golden_lights(imported.scene);
  ASSERT_EQ(lights.size(), 2u) << "the default scene declares a point and a directional light";
  std::string error;
  auto state = render::create_state(imported.scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 160, 120);
  const bool update = std::getenv("GEOM_UPDATE_GOLDEN") != nullptr;
  for (const Light& light : lights)
    for (render::Technique t : render::available_techniques()) {
      if (t == render::Technique::Cube && directional(light.setup)) continue;
      render::FrameSettings fs;
      fs.technique = t;
      fs.shadow_map_size = 512;
      float bounds[4];
      render::scene_bounds(*state, bounds);
      if (render::technique_is_soft(t))  // a disc light: 4% of the scene's radius, 0.02 rad for the sun
        fs.light_radius = directional(light.setup) ? 0.02f : 0.04f * bounds[3];
      geom::PngImage image;
      std::vector<render::PassTime> times;
      ASSERT_TRUE(render::render(*state, view, light.setup, fs, image, times, error)) << error;
      const std::string golden =
          std::string(GEOM_SOURCE_DIR) + "/tests/golden/" + render::technique_name(t) + "_" + light.name + ".png";
      SCOPED_TRACE(golden);
      if (update) {
        ASSERT_TRUE(geom::write_png(golden, image, error)) << error;
        continue;
      }
      geom::PngImage expected;
      ASSERT_TRUE(geom::read_png(golden, expected, error, 3)) << error;
      ASSERT_EQ(expected.width, image.width);
      ASSERT_EQ(expected.height, image.height);
      size_t far_off = 0;
      double sum = 0;
      for (size_t i = 0; i < image.pixels.size(); i += 3) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
          const int d = std::abs(int(image.pixels[i + c]) - int(expected.pixels[i + c]));
          worst = std::max(worst, d);
          sum += d;
        }
        far_off += worst > 24;
      }
      const size_t pixels = image.pixels.size() / 3;
      EXPECT_LE(far_off, pixels / 100) << far_off << " pixels differ by more than 24 levels";
      EXPECT_LT(sum / double(image.pixels.size()), 2.0);
    }
}

}  // namespace

namespace {

// The techniques against the ray-cast reference on the default scene, under
// its point light and its directional light (the sun): shadow volumes exact,
// the 1024-texel maps within 0.2% of the certain pixels.
TEST(GlGolden, DefaultSceneMasksAgreeWithTheReference) {
  ASSERT_NE(context(), nullptr);
  geom::ImportResult imported = geom::import_file(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
  ASSERT_TRUE(imported.ok) << imported.error;
  std::string error;
  auto state = render::create_state(imported.scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 200, 150);
  for (const Light& light : golden_lights(imported.scene))
    for (render::Technique t : {render::Technique::Ssm, render::Technique::Pcf, render::Technique::Psm,
                                render::Technique::Lispsm, render::Technique::Uniform, render::Technique::Edsm,
                                render::Technique::Esm, render::Technique::Sssm, render::Technique::Sv}) {
      const Comparison c = render_and_compare(*state, imported.scene, view, light.setup, t, 1024);
      SCOPED_TRACE(std::string(light.name) + " " + render::technique_name(t));
      EXPECT_GT(c.shadowed, 100u);
      if (t == render::Technique::Sv)
        EXPECT_EQ(c.wrong, 0u);
      else
        EXPECT_LT(c.error(), 0.002) << c.wrong << " of " << c.certain;  // a few texel-staircase pixels
    }
}

}  // namespace
