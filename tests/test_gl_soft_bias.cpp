// The soft techniques' depth test at every angle and size: the colonnade of
// gl_fixtures.h (200 m deep, round pillars of 16 facets) under a sun from the
// side with an angular radius of 0.02 rad, seen from one end. pcf-soft tests
// every tap, and edsm-soft and esm-soft their hard answers (a texel without an
// edge, a receiver in front of the edges), by the receiver's plane at each
// texel's centre (shaders/depth_plane.frag), as the hard maps do, and
// pcf-soft's kernel is as wide as the penumbra along each axis of its map, so
//  - their hard state (lit where the fraction exceeds 0.5) has at most 0.2%
//    of the self class wrong (geom/shadow_error.h: terminators and the lit
//    pixels next to them) at 1024 and 2048 texels, and the self error does
//    not grow with the map by more than 0.02 points;
//  - their light-fraction error against the area-light reference
//    (geom/area_reference.h) does not grow with the map by more than 0.1
//    points, and at 4096 is at most half of 512's.
#include "geom/area_reference.h"
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

TEST(GlSoftBias, SoftMapsDoNotShadowTheirOwnLitFaces) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = colonnade();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const int w = 320, h = 240;
  const geom::Camera view = camera({0.8f, 1.7f, 2}, {0.2f, 1.5f, -40}, 60, 0.1f, 400, w, h);
  const geom::Light light = sun({1, 0.45f, 0.15f});
  const float radius = 0.02f;
  const auto positions = geom::positions_of(scene.positions.data(), scene.vertex_count());
  const geom::ShadowReference hard =
      geom::shadow_reference(positions, scene.indices.data(), scene.indices.size(), view, light);
  ASSERT_TRUE(hard.ok) << hard.error;
  const geom::AreaReference area =
      geom::area_light_reference(positions, scene.indices.data(), scene.indices.size(), view, light, radius, 32);
  ASSERT_TRUE(area.ok) << area.error;
  const int sizes[] = {512, 1024, 2048, 4096};
  for (Technique t : {Technique::PcfSoft, Technique::EdsmSoft, Technique::EsmSoft}) {
    SCOPED_TRACE(render::technique_name(t));
    double self[4], fraction[4];
    for (int k = 0; k < 4; ++k) {
      render::FrameSettings fs;
      fs.technique = t;
      fs.output = render::Output::Fraction;
      fs.shadow_map_size = sizes[k];
      fs.light_radius = radius;
      geom::PngImage img;
      std::vector<render::PassTime> times;
      ASSERT_TRUE(render::render(*state, view, light, fs, img, times, error)) << error;
      fraction[k] = geom::mean_fraction_error(img.pixels, area);
      if (const char* dir = std::getenv("GEOM_GL_TEST_DUMP")) {  // debugging aid: the fraction and the reference
        geom::PngImage r = img;
        for (size_t i = 0; i < r.pixels.size(); ++i)
          r.pixels[i] = area.fraction[i] < 0 ? 128 : uint8_t(std::lround(255 * area.fraction[i]));
        const std::string base = std::string(dir) + "/" + render::technique_name(t) + "_" + std::to_string(sizes[k]);
        geom::write_png(base + ".png", img, error);
        geom::write_png(base + "_ref.png", r, error);
      }
      for (uint8_t& v : img.pixels) v = v == 128 ? 128 : v > 128 ? 255 : 0;  // shade.frag's mask: lit above 0.5
      const geom::ShadowError e = geom::shadow_error(img.pixels, hard);
      self[k] = e.error_self;
      std::printf("%s map %d: error_self %.3f%% (%zu of %zu), light-fraction error %.4f\n", render::technique_name(t),
                  sizes[k], 100 * e.error_self, e.wrong_self, e.self_pixels, fraction[k]);
      if (k == 0) EXPECT_GT(e.self_pixels, 1500u) << "the view must show the pillars' terminators";
    }
    EXPECT_LT(self[1], 0.002) << "error_self at 1024";
    EXPECT_LT(self[2], 0.002) << "error_self at 2048";
    for (int k = 1; k < 4; ++k) {
      EXPECT_LE(self[k], self[k - 1] + 0.0002) << "error_self grows from " << sizes[k - 1] << " to " << sizes[k];
      EXPECT_LE(fraction[k], fraction[k - 1] + 0.001)
          << "the light-fraction error grows from " << sizes[k - 1] << " to " << sizes[k];
    }
    EXPECT_LE(fraction[3], fraction[0] / 2) << "the light-fraction error at 4096 at most half of 512's";
  }
}

}  // namespace
