// The projection a frame drew (render::drawn_projection), for a point light
// among the receivers: the bundled scene under its own light, seen from the
// default view, where one frustum cannot cover what the light must see.
//
// Laws:
//   - ssm and pcf draw six faces and say so ("6 faces");
//   - psm, lispsm and uniform draw six faces, each focused by the method (or
//     by uniform where it cannot warp), and say which ("6 faces: lispsm x5");
//   - cube says "cube map";
//   - no technique's mask equals another's while their projections differ
//     in name: a figure is never another technique's under a different label
//     (ssm, psm, lispsm and uniform were drawn as the cube map, with cube's
//     identical figures);
//   - each agrees with the ray-cast reference on all but a small fraction of
//     the certain pixels.
#include <map>

#include "geom/import.h"
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

struct Drawn {
  std::string projection;
  geom::PngImage mask;
  Comparison c;
};

TEST(GlProjection, PointLightAmongTheReceiversDrawsAndNamesSixFaces) {
  ASSERT_NE(context(), nullptr);
  geom::ImportResult imported = geom::import_file(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
  ASSERT_TRUE(imported.ok) << imported.error;
  const geom::Scene& scene = imported.scene;
  const geom::Light light = geom::light_from_scene(scene.lights);
  ASSERT_EQ(geom::LightType::Point, light.type);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 160, 120);
  const Technique all[] = {Technique::Ssm, Technique::Pcf,     Technique::Psm,
                           Technique::Lispsm, Technique::Uniform, Technique::Cube};
  std::map<Technique, Drawn> drawn;
  for (Technique t : all) {
    Drawn& d = drawn[t];
    d.c = render_and_compare(*state, scene, view, light, t, 512, &d.mask);
    d.projection = render::drawn_projection(*state);
    std::printf("%-8s %-32s %zu of %zu certain pixels wrong\n", render::technique_name(t), d.projection.c_str(),
                d.c.wrong, d.c.certain);
    EXPECT_LT(d.c.error(), 0.005) << render::technique_name(t);
    EXPECT_EQ(std::string::npos, d.projection.find(',')) << "a CSV field as it is";
  }
  EXPECT_EQ("6 faces", drawn[Technique::Ssm].projection.substr(0, 7));
  EXPECT_EQ("6 faces", drawn[Technique::Pcf].projection.substr(0, 7));
  EXPECT_EQ("cube map", drawn[Technique::Cube].projection);
  for (Technique t : {Technique::Psm, Technique::Lispsm, Technique::Uniform}) {
    const std::string& p = drawn[t].projection;
    SCOPED_TRACE(render::technique_name(t));
    EXPECT_EQ("6 faces: ", p.substr(0, 9));
    // Every face says its method: the requested one, or uniform where it cannot warp.
    EXPECT_TRUE(p.find(render::technique_name(t)) != std::string::npos || p.find("uniform") != std::string::npos) << p;
  }
  // Different projections, different figures: no mask is another's under a different name.
  for (Technique a : all)
    for (Technique b : all) {
      if (a >= b || drawn[a].projection == drawn[b].projection) continue;
      EXPECT_NE(drawn[a].mask.pixels, drawn[b].mask.pixels)
          << render::technique_name(a) << " (" << drawn[a].projection << ") draws exactly what "
          << render::technique_name(b) << " (" << drawn[b].projection << ") draws";
    }
}

// A directional light and a far point light: one map each, named as drawn.
TEST(GlProjection, OneMapIsNamedAsDrawn) {
  ASSERT_NE(context(), nullptr);
  geom::Scene scene;
  add_ground(scene, 4);
  add_box(scene, box_at({0, 1, 0}, {0.5f, 1, 0.5f}));
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = camera({5, 4, 6}, {0, 0.5f, 0}, 50, 0.1f, 100, 160, 120);
  for (const geom::Light& light : {sun({0.4f, 1, 0.3f}), point_light({3, 12, 2})}) {
    for (Technique t : {Technique::Ssm, Technique::Psm, Technique::Lispsm, Technique::Uniform}) {
      render_and_compare(*state, scene, view, light, t, 256);
      const std::string p = render::drawn_projection(*state);
      SCOPED_TRACE(std::string(render::technique_name(t)) + ": " + p);
      if (t == Technique::Ssm) {
        EXPECT_EQ("fitted frustum", p);
      } else {
        const std::string name = render::technique_name(t);
        EXPECT_TRUE(p.rfind(name, 0) == 0 || p.rfind("uniform (fallback: ", 0) == 0);
      }
    }
  }
  render_and_compare(*state, scene, view, sun({0.4f, 1, 0.3f}), Technique::Sv, 0);
  EXPECT_EQ("shadow volumes", render::drawn_projection(*state));
}

}  // namespace
