// Edge distance (edsm, Kenzel 2013) and extended (esm, Bujnak 2004) shadow maps against the
// simple shadow map at the same map size, on the crossed-pipes scene: both
// reconstruct the silhouette between texels, so their masks are closer to the
// ray-cast reference than the simple map's. Also: they agree with the
// reference away from boundaries as well as a shadow map does; and on a jenga
// tower and the default scene's block tower, Kenzel 2013's Sect. 5.2 cases (with
// esm-exact's and sssm's bounds beside edsm's).
//
//   top view:   wall  ==================
//                        \      /
//                         \    /        two pipes crossing in front of the
//                          \  /         wall, a light behind the viewer
//                           \/          casting their shadows onto it
//                           /\.
#include "geom/import.h"
#include "geom/shadow_error.h"
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

// Summed over a point, a spot and a directional light at each map size: wrong
// pixels of the cast-shadow class (the pipes' shadows on the wall and ground).
// esm-exact, not esm: the paper's esm dilates the shadow by 0.707 texel, which
// at 64-96 texels over the scene is more than the simple map's staircase.
TEST(GlEdgeShadowMaps, CloserToTheReferenceThanTheSimpleShadowMap) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (int size : {64, 96}) {
    size_t ssm = 0, edsm = 0, esm = 0, cast = 0;
    for (const geom::Light& l : lights()) {
      const geom::ShadowError s = score(*state, scene, front_view(), l, Technique::Ssm, size);
      ssm += s.wrong_cast, cast += s.cast_pixels;
      edsm += score(*state, scene, front_view(), l, Technique::Edsm, size).wrong_cast;
      esm += score(*state, scene, front_view(), l, Technique::EsmExact, size).wrong_cast;
    }
    std::printf("map %d: wrong cast-class pixels ssm %zu, edsm %zu, esm-exact %zu (of %zu)\n", size, ssm, edsm, esm,
                cast);
    SCOPED_TRACE("map " + std::to_string(size));
    EXPECT_GT(cast, 10000u);
    EXPECT_GT(ssm, 100u) << "the simple shadow map should show its staircase at this size";
    // A fifth, not less: where its edges cannot decide (Kenzel 2013, Sect.
    // 5.2), edsm makes exactly ssm's test, so that it is never worse than ssm.
    EXPECT_LE(edsm * 5, ssm) << "edsm within a fifth of the simple map's cast-class error";
    EXPECT_LT(esm, ssm);
  }
}

// A point light inside the scene's bounds, whose receivers
// need more than one frustum: esm and edsm drawn as six cube faces with their
// edge maps, against the cube technique (Gerasimov 2004's cube map with its 4-tap
// filter and its slope-scaled bias) at two map sizes: edsm beats it tenfold on
// the cast-shadow class, esm and esm-exact are no worse, and neither silhouette
// map is worse than ssm, which draws six fitted faces of its own
// (render/src/light_fit.cpp). (Measured: cube 136 and 38 wrong cast-class
// pixels at 40 and 64 texels, edsm 6 and 0, esm-exact 94 and 35.)
TEST(GlEdgeShadowMaps, PointLightInsideTheSceneAsCubeFaces) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Light light = point_light({0.8f, 3.6f, 1.5f});  // the box is [-4, 4] x [0, 4] x [-4, 4]
  const geom::Camera view = camera({-1.5f, 2.2f, 6.0f}, {0, 1.4f, -1.0f}, 50, 0.1f, 100, 240, 180);
  for (int size : {40, 64}) {
    const geom::ShadowError s = score(*state, scene, view, light, Technique::Cube, size);
    const geom::ShadowError d = score(*state, scene, view, light, Technique::Edsm, size);
    const geom::ShadowError e = score(*state, scene, view, light, Technique::Esm, size);
    const geom::ShadowError x = score(*state, scene, view, light, Technique::EsmExact, size);
    const geom::ShadowError m = score(*state, scene, view, light, Technique::Ssm, size);
    std::printf(
        "point light inside, map %d: wrong cast-class pixels cube %zu, edsm %zu, esm %zu, esm-exact %zu, ssm %zu (of "
        "%zu); wrong visible pixels ssm %zu, edsm %zu, esm-exact %zu\n",
        size, s.wrong_cast, d.wrong_cast, e.wrong_cast, x.wrong_cast, m.wrong_cast, s.cast_pixels, m.wrong_visible,
        d.wrong_visible, x.wrong_visible);
    SCOPED_TRACE("map " + std::to_string(size));
    EXPECT_GT(s.cast_pixels, 3000u);
    EXPECT_GT(s.wrong_cast, 20u) << "the cube map should show its staircase at this size";
    EXPECT_LE(d.wrong_cast * 10, s.wrong_cast) << "edsm within a tenth of the simple map's (Kenzel 2013, Sect. 5.2)";
    EXPECT_LT(e.wrong_cast, s.wrong_cast);
    EXPECT_LE(x.wrong_cast, s.wrong_cast) << "esm-exact no worse than the cube map";
    // Never worse than ssm's six fitted faces (their fallback is ssm's test).
    EXPECT_LE(d.wrong_visible, m.wrong_visible + 2) << "edsm no worse than ssm";
    EXPECT_LE(x.wrong_visible, m.wrong_visible + 2) << "esm-exact no worse than ssm";
  }
}

// Kenzel 2013's stated failure cases (Sect. 5.2.1) on a jenga tower: every
// block shadows the block below it, so a receiver's outline and a caster's
// edge fall in one texel and edges lie under 2 texels apart. A slope-scaled
// offset loses these thin shadows (the blocks' grazing sides are pushed back);
// the receiver-plane test keeps them, and edsm and esm-exact, which fall back
// to that test where their edges cannot decide, must be no worse.
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

TEST(GlEdgeShadowMaps, BlocksShadowingTheBlockBelow) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = jenga_tower();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Light light = sun({0.5f, 1.0f, 0.3f});
  const geom::Camera view = camera({3.5f, 3.0f, 4.5f}, {0, 1.8f, 0}, 45, 0.1f, 100, 240, 180);
  for (int size : {128, 256}) {
    const geom::ShadowError s = score(*state, scene, view, light, Technique::Ssm, size);
    const geom::ShadowError d = score(*state, scene, view, light, Technique::Edsm, size);
    const geom::ShadowError e = score(*state, scene, view, light, Technique::Esm, size);
    const geom::ShadowError x = score(*state, scene, view, light, Technique::EsmExact, size);
    std::printf("jenga tower, map %d: wrong cast-class pixels ssm %zu, edsm %zu, esm %zu, esm-exact %zu (of %zu)\n",
                size, s.wrong_cast, d.wrong_cast, e.wrong_cast, x.wrong_cast, s.cast_pixels);
    SCOPED_TRACE("map " + std::to_string(size));
    // The blocks' thin shadows: the receiver-plane test (shaders/depth_plane.frag)
    // resolves them in the simple map itself, and the silhouette maps keep them.
    // The paper's esm (its own hardware comparison and 0.707-texel dilation)
    // is printed, not bounded: its dilation is coarser than that test.
    EXPECT_GT(s.cast_pixels, 3000u);
    EXPECT_LT(s.wrong_cast * 100, s.cast_pixels) << "ssm resolves the blocks' shadows within 1% of the class";
    // edsm's footprint is compared at the sample's depth (lookup_edsm.frag), not
    // at each texel's centre: a few pixels of the class may differ from ssm.
    EXPECT_LE(d.wrong_cast * 1000, s.wrong_cast * 1000 + s.cast_pixels) << "edsm within 0.1% of the class of ssm";
    EXPECT_LE(x.wrong_cast, s.wrong_cast + 2) << "esm-exact no worse than the simple map";
  }
}

// The default scene's own point light, inside the scene (six cube faces): the
// block tower's upper block outlines itself on the lower block's lit face (a
// receiver's own outline, Sect. 5.2). The simple map (the distance cube) is
// right there; edsm must not be worse. With the nearest comparison deciding
// where no stored edge lies in front of the receiver (the earlier lookup's
// fallback, kept in lookup_edsm.frag's step 1 for this check), edsm had 33 and
// 18 wrong cast-class pixels here at 512 and 1024 against ssm's 1 and 0 (this
// test failed); with step 1 (lit) 0 and 0. sssm (shadow silhouette maps) has
// the same rule for its silhouette points (lookup_sssm.frag) and must be no
// worse than ssm or within 1.5x of edsm: with the nearest comparison it had 37
// and 19 wrong cast-class pixels here.
TEST(GlEdgeShadowMaps, ReceiversOwnOutlineNoWorseThanTheSimpleMap) {
  ASSERT_NE(context(), nullptr);
  geom::ImportResult imported = geom::import_file(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
  ASSERT_TRUE(imported.ok) << imported.error;
  std::string error;
  auto state = render::create_state(imported.scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 640, 480);
  const geom::Light light = geom::light_from_scene(imported.scene.lights);
  for (int size : {512, 1024}) {
    const geom::ShadowError s = score(*state, imported.scene, view, light, Technique::Ssm, size);
    const geom::ShadowError d = score(*state, imported.scene, view, light, Technique::Edsm, size);
    const geom::ShadowError x = score(*state, imported.scene, view, light, Technique::Sssm, size);
    std::printf(
        "default scene, map %d: wrong visible / cast-class pixels ssm %zu / %zu, edsm %zu / %zu, sssm %zu / %zu (of "
        "%zu)\n",
        size, s.wrong_visible, s.wrong_cast, d.wrong_visible, d.wrong_cast, x.wrong_visible, x.wrong_cast,
        s.visible_pixels);
    SCOPED_TRACE("map " + std::to_string(size));
    EXPECT_GT(s.cast_pixels, 10000u);
    EXPECT_LE(d.wrong_visible, s.wrong_visible);
    EXPECT_LE(d.wrong_cast, s.wrong_cast);
    EXPECT_TRUE(x.wrong_cast <= s.wrong_cast || 2 * x.wrong_cast <= 3 * d.wrong_cast)
        << "sssm " << x.wrong_cast << ", ssm " << s.wrong_cast << ", edsm " << d.wrong_cast;
  }
}

TEST(GlEdgeShadowMaps, AgreeWithTheReferenceAtALargeMapSize) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = crossed_pipes();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (const geom::Light& l : lights())
    for (Technique t : {Technique::Edsm, Technique::Esm, Technique::EsmExact}) {
      const Comparison c = render_and_compare(*state, scene, front_view(), l, t, 1024);
      SCOPED_TRACE(render::technique_name(t));
      EXPECT_LT(c.error(), 0.005) << c.wrong << " of " << c.certain;
    }
}

}  // namespace
