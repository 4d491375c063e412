// A depth bias that holds at every angle and size: a colonnade 200 m deep,
// seen from one end at eye height, lit by a sun from the side. Round pillars
// (16 facets) turn every angle to the light, down to the terminator; at 1024
// texels over 200 m one texel covers about 0.2 m, so a pillar's neighbouring
// facets fall inside the texels of the one being lit. The map techniques test
// the receiver's plane at each texel's centre (shaders/depth_plane.frag), so
// their self-shadowing error (geom/shadow_error.h's self class: terminators
// and the lit pixels next to them) must stay under 0.2% at 1024 and 2048
// texels and fall as the map grows (no size worse than the one before by more
// than 0.02 points, 4096 at most half of 512's), for ssm, pcf, uniform (the
// focused map without a warp), edsm and esm-exact (their fallback is ssm's
// test) and esm (its depth test is ssm's; Bujnak 2004's 0.707-texel dilation
// applies only behind an edge by more than its z-bias).
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

TEST(GlBiasWideDepth, SelfShadowingFallsAsTheMapGrows) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = colonnade();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = camera({0.8f, 1.7f, 2}, {0.2f, 1.5f, -40}, 60, 0.1f, 400, 640, 480);
  const geom::Light light = sun({1, 0.45f, 0.15f});
  const int sizes[] = {512, 1024, 2048, 4096};
  for (Technique t : {Technique::Ssm, Technique::Pcf, Technique::Uniform, Technique::Edsm, Technique::EsmExact,
                      Technique::Esm}) {
    SCOPED_TRACE(render::technique_name(t));
    double self[4], visible[4];
    for (int k = 0; k < 4; ++k) {
      const geom::ShadowError e = score(*state, scene, view, light, t, sizes[k]);
      self[k] = e.error_self, visible[k] = e.error_visible;
      std::printf("%s map %d: error_self %.3f%% (%zu of %zu), error_visible %.3f%%\n", render::technique_name(t),
                  sizes[k], 100 * e.error_self, e.wrong_self, e.self_pixels, 100 * e.error_visible);
      if (k == 0) EXPECT_GT(e.self_pixels, 5000u) << "the view must show the pillars' terminators";
    }
    EXPECT_LT(self[1], 0.002) << "error_self at 1024";
    EXPECT_LT(self[2], 0.002) << "error_self at 2048";
    for (int k = 1; k < 4; ++k) {
      EXPECT_LE(self[k], self[k - 1] + 0.0002) << "error_self grows from " << sizes[k - 1] << " to " << sizes[k];
      EXPECT_LE(visible[k], visible[k - 1] + 0.0002)
          << "error_visible grows from " << sizes[k - 1] << " to " << sizes[k];
    }
    EXPECT_LE(visible[3], visible[0] / 2) << "error_visible at 4096 at most half of 512's";
  }
}

}  // namespace
