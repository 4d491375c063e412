// edsm-soft behind round occluders: geombench's crossed pipes in front of a
// wall (Bujnak 2004's test scene) under a disc light of 4% of the scene's
// radius, drawn on the six faces of a point light among its receivers. A
// pipe's front stands in front of its own silhouette, so the umbra half of
// each penumbra lies over the pipe in the light's map; the edge quads there
// must keep their distance (shaders/edsm_soft_edges.frag judges an edge's
// visibility where the edge lies). The laws (Kenzel 2013, Sect. 6: soft
// shadow boundaries from the edge distance alone):
//  - edsm-soft's light-fraction error against the area-light reference
//    (geom/area_reference.h) does not grow with the map (no step up by more
//    than 0.001 + 5%, geombench's soft size law) from 512 to 4096 texels;
//  - at every size it is below pcf-soft's (PCSS, Fernando 2005), the baseline
//    of the same light frames.
// On geombench's rippled sphere (its terminator a band of tiny self-shadows
// that no map resolves), edsm-soft's and esm-soft's light fractions are closer
// to the area reference than the hard edsm's and esm's own masks: where the
// edges cannot decide, the footprint's bilinear comparison stands, not one
// texel's.
// And pcf-soft's reach bounded in map widths at every size (render/src/soft.cpp
// map_reach): on geombench's colonnade under a point light behind and above
// the camera (penumbrae wider than the reach) its light-fraction error does
// not step up from 256 to 512 to 1024 texels.
#include "geom/area_reference.h"
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

geom::Scene crossed_pipes() {
  geom::Scene s;
  add_quad(s, {-4, 0, -3}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -3});
  add_quad(s, {-4, 0, -2}, {4, 0, -2}, {4, 4, -2}, {-4, 4, -2});
  add_pipe(s, {-3, 0.5f, 0}, {3, 3.5f, -0.6f}, 0.12f, 24);
  add_pipe(s, {-3, 3.5f, -0.3f}, {3, 0.5f, 0.3f}, 0.12f, 24);
  return s;
}

TEST(GlSoftRoundOccluder, EdgeDistancePenumbraHoldsAsTheMapGrows) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = camera({-2.5f, 2.5f, 6}, {0, 1.8f, -1}, 60, 0.1f, 50, 320, 240);
  const geom::Light light = point_light({0.5f, 3, 5});
  float bounds[4];
  render::scene_bounds(*state, bounds);
  const float radius = 0.04f * bounds[3];
  const auto positions = geom::positions_of(scene.positions.data(), scene.vertex_count());
  const geom::AreaReference area =
      geom::area_light_reference(positions, scene.indices.data(), scene.indices.size(), view, light, radius, 64);
  ASSERT_TRUE(area.ok) << area.error;
  const int sizes[] = {512, 1024, 2048, 4096};
  double fraction[2][4];
  const Technique techniques[] = {Technique::EdsmSoft, Technique::PcfSoft};
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 4; ++k) {
      render::FrameSettings fs;
      fs.technique = techniques[t];
      fs.output = render::Output::Fraction;
      fs.shadow_map_size = sizes[k];
      fs.light_radius = radius;
      geom::PngImage img;
      std::vector<render::PassTime> times;
      ASSERT_TRUE(render::render(*state, view, light, fs, img, times, error)) << error;
      fraction[t][k] = geom::mean_fraction_error(img.pixels, area);
      std::printf("%s map %d (%s): light-fraction error %.5f\n", render::technique_name(techniques[t]), sizes[k],
                  render::drawn_projection(*state).c_str(), fraction[t][k]);
    }
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE("map " + std::to_string(sizes[k]));
    if (k > 0) EXPECT_LE(fraction[0][k], fraction[0][k - 1] * 1.05 + 0.001) << "edsm-soft's error grows with the map";
    EXPECT_LT(fraction[0][k], fraction[1][k]) << "edsm-soft's error not below pcf-soft's";
  }
}

TEST(GlSoftRoundOccluder, PcfSoftReachIsTheSameShareOfTheMapAtEverySize) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = colonnade();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = camera({0.8f, 1.7f, 2}, {0.2f, 1.5f, -40}, 60, 0.1f, 400, 320, 240);
  const geom::Light light = point_light({1.5f, 6, 9});
  float bounds[4];
  render::scene_bounds(*state, bounds);
  const float radius = 0.04f * bounds[3];
  const auto positions = geom::positions_of(scene.positions.data(), scene.vertex_count());
  const geom::AreaReference area =
      geom::area_light_reference(positions, scene.indices.data(), scene.indices.size(), view, light, radius, 64);
  ASSERT_TRUE(area.ok) << area.error;
  const int sizes[] = {256, 512, 1024};
  double fraction[3];
  for (int k = 0; k < 3; ++k) {
    render::FrameSettings fs;
    fs.technique = Technique::PcfSoft;
    fs.output = render::Output::Fraction;
    fs.shadow_map_size = sizes[k];
    fs.light_radius = radius;
    geom::PngImage img;
    std::vector<render::PassTime> times;
    ASSERT_TRUE(render::render(*state, view, light, fs, img, times, error)) << error;
    fraction[k] = geom::mean_fraction_error(img.pixels, area);
    std::printf("pcf-soft map %d (%s): light-fraction error %.5f\n", sizes[k], render::drawn_projection(*state).c_str(),
                fraction[k]);
    if (k > 0)
      EXPECT_LE(fraction[k], fraction[k - 1] * 1.05 + 0.001)
          << "pcf-soft's error grows from " << sizes[k - 1] << " to " << sizes[k];
  }
}

TEST(GlSoftRoundOccluder, SoftEdgeMapsCloserThanTheirHardAnswerOnARippledSphere) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = rippled_sphere(250);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 320, 240);
  const geom::Light light = point_light({2, 4, 1.5f});
  float bounds[4];
  render::scene_bounds(*state, bounds);
  const float radius = 0.04f * bounds[3];
  const auto positions = geom::positions_of(scene.positions.data(), scene.vertex_count());
  const geom::AreaReference area =
      geom::area_light_reference(positions, scene.indices.data(), scene.indices.size(), view, light, radius, 64);
  ASSERT_TRUE(area.ok) << area.error;
  const Technique pairs[2][2] = {{Technique::Edsm, Technique::EdsmSoft}, {Technique::Esm, Technique::EsmSoft}};
  for (const auto& pair : pairs)
    for (int size : {512, 1024}) {
      double fraction[2];
      for (int k = 0; k < 2; ++k) {
        render::FrameSettings fs;
        fs.technique = pair[k];
        fs.output = k ? render::Output::Fraction : render::Output::Mask;
        fs.shadow_map_size = size;
        fs.light_radius = radius;
        geom::PngImage img;
        std::vector<render::PassTime> times;
        ASSERT_TRUE(render::render(*state, view, light, fs, img, times, error)) << error;
        fraction[k] = geom::mean_fraction_error(img.pixels, area);
        std::printf("%s map %d (%s): light-fraction error %.5f\n", render::technique_name(fs.technique), size,
                    render::drawn_projection(*state).c_str(), fraction[k]);
      }
      EXPECT_LT(fraction[1], fraction[0])
          << render::technique_name(pair[1]) << " no closer than " << render::technique_name(pair[0]) << " at " << size;
    }
}

}  // namespace
