// Stencil shadow volumes (sv, sv-zpass, sv-zfail) against the ray-cast
// reference. Law (Arneson, Sect. 4): the mask equals the exact one on every
// pixel not within one pixel of a true boundary, for closed, open and
// non-manifold casters, with the camera outside and inside a shadow volume.
// Depth-pass with the camera inside a volume is the classic failure: it is
// checked to fail, which shows the comparison can.
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

// Closed boxes on an (open) ground square.
geom::Scene closed_scene() {
  geom::Scene s;
  add_ground(s, 6);
  tag_caster(s, 0, 0);
  size_t first = s.sources.size();
  add_box(s, box_at({-1.5f, 0.6f, 0}, {0.6f, 0.6f, 0.6f}, 20));
  tag_caster(s, first, 1);
  first = s.sources.size();
  add_box(s, box_at({1.0f, 1.0f, -1.0f}, {0.5f, 1.0f, 0.8f}, -35));
  tag_caster(s, first, 2);
  first = s.sources.size();
  add_box(s, box_at({1.5f, 2.4f, 1.5f}, {0.4f, 0.3f, 0.5f}, 10));  // floating
  tag_caster(s, first, 3);
  return s;
}

// Open casters: a box without top and bottom (a square tube), a single
// floating quad, a box missing one side.
geom::Scene open_scene() {
  geom::Scene s;
  add_ground(s, 6);
  tag_caster(s, 0, 0);
  size_t first = s.sources.size();
  add_box(s, box_at({-1.5f, 1.0f, 0}, {0.5f, 1.0f, 0.5f}, 15), (1u << 2) | (1u << 3));
  tag_caster(s, first, 1);
  first = s.sources.size();
  add_quad(s, {0.5f, 2.0f, -1.0f}, {0.5f, 2.3f, 0.5f}, {2.0f, 2.3f, 0.5f}, {2.0f, 2.0f, -1.0f});
  tag_caster(s, first, 2);
  first = s.sources.size();
  add_box(s, box_at({1.2f, 0.8f, 2.0f}, {0.5f, 0.8f, 0.4f}, -20), 1u << 1);
  tag_caster(s, first, 3);
  return s;
}

// Non-manifold casters: a "book" of three pages sharing their spine (an edge of
// three faces), and two boxes touching along one edge (an edge of four faces).
//
//   book, seen along the spine:     \ | /      boxes:  +---+
//                                    \|/               |   |
//                                     * spine          +---*---+
//                                                          |   |
//                                                          +---+
geom::Scene non_manifold_scene() {
  geom::Scene s;
  add_ground(s, 6);
  tag_caster(s, 0, 0);
  size_t first = s.sources.size();
  const glm::vec3 spine0(-2.0f, 1.2f, -0.8f), spine1(-2.0f, 1.2f, 0.8f);
  for (float angle : {-50.0f, 0.0f, 40.0f}) {
    const float a = glm::radians(angle);
    const glm::vec3 off(std::sin(a) * 1.0f, std::cos(a) * 1.0f, 0);
    add_quad(s, spine0, spine1, spine1 + off, spine0 + off);
  }
  tag_caster(s, first, 1);
  first = s.sources.size();
  add_box(s, box_at({0.5f, 1.5f, 0.0f}, {0.5f, 0.5f, 0.5f}));
  add_box(s, box_at({1.5f, 2.5f, 0.0f}, {0.5f, 0.5f, 0.5f}));
  tag_caster(s, first, 2);
  return s;
}

geom::Camera view_from(glm::vec3 eye, glm::vec3 target) { return camera(eye, target, 55, 0.05f, 100, 160, 120); }

std::vector<geom::Light> lights() {
  std::vector<geom::Light> out;
  geom::Light point;
  point = point_light({-1.0f, 5.0f, -2.5f});
  out.push_back(point);
  geom::Light spot = point;
  spot = point_light({2.5f, 6.0f, 2.0f});
  spot.type = geom::LightType::Spot;
  for (int k = 0; k < 3; ++k) spot.direction[k] = glm::vec3(-2.5f, -6.0f, -2.0f)[k];
  spot.outer_cone = 38 * M_PI / 180;
  out.push_back(spot);
  geom::Light dir;
  dir = sun({-0.5f, 0.9f, 0.35f});
  out.push_back(dir);
  return out;
}

void check_scene(const geom::Scene& scene, const char* name) {
  ASSERT_NE(context(), nullptr);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera views[] = {view_from({4, 5, 8}, {0, 0.5f, 0}), view_from({-6, 3, -5}, {0, 0.8f, 0}),
                                view_from({0.5f, 9, 0.5f}, {0, 0, 0})};
  for (const geom::Camera& v : views)
    for (const geom::Light& l : lights())
      for (Technique t : {Technique::Sv, Technique::SvZPass, Technique::SvZFail}) {
        const Comparison c = render_and_compare(*state, scene, v, l, t, 256);
        SCOPED_TRACE(std::string(name) + " " + render::technique_name(t) + " light w=" +
                     std::to_string(directional(l) ? 0.0f : 1.0f) + (l.type == geom::LightType::Spot ? " spot" : ""));
        EXPECT_EQ(c.wrong, 0u) << c.wrong << " of " << c.certain << " certain pixels differ";
        EXPECT_GT(c.shadowed, 200u);
        EXPECT_GT(c.lit, 200u);
      }
}

TEST(GlShadowVolumes, ClosedCastersMatchTheReference) { check_scene(closed_scene(), "closed"); }
TEST(GlShadowVolumes, OpenCastersMatchTheReference) { check_scene(open_scene(), "open"); }
TEST(GlShadowVolumes, NonManifoldCastersMatchTheReference) { check_scene(non_manifold_scene(), "non-manifold"); }

// The camera below the floating box, inside its shadow volume, looking out over
// lit ground and other shadows.
TEST(GlShadowVolumes, CameraInsideAVolume) {
  ASSERT_NE(context(), nullptr);
  for (bool closed : {true, false}) {
    const geom::Scene scene = closed ? closed_scene() : open_scene();
    std::string error;
    auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
    ASSERT_TRUE(state) << error;
    geom::Light l;
    // Straight above the floating caster (closed: the box at y 2.1..2.7; open: the quad at y 2..2.3).
    const glm::vec3 above = closed ? glm::vec3(1.5f, 8, 1.5f) : glm::vec3(1.25f, 8, -0.25f);
    l = point_light({above});
    const glm::vec3 eye(above.x + 0.05f, 1.2f, above.z - 0.05f);
    const geom::Camera v = view_from(eye, eye + glm::vec3(-3, -1.0f, -2));
    for (Technique t : {Technique::Sv, Technique::SvZFail}) {
      const Comparison c = render_and_compare(*state, scene, v, l, t, 256);
      SCOPED_TRACE(render::technique_name(t));
      EXPECT_EQ(c.wrong, 0u) << c.wrong << " of " << c.certain << " certain pixels differ";
      EXPECT_GT(c.lit, 500u);
    }
    const Comparison zpass = render_and_compare(*state, scene, v, l, Technique::SvZPass, 256);
    EXPECT_GT(zpass.error(), 0.2) << "depth-pass with the camera inside a volume should invert the count";
  }
}

// Hard cases: coordinates far from the origin, the light behind
// the viewer, the light in the plane of faces (grazing); the light exactly at
// a caster's vertex and inside a caster's face (LightOnACaster below).
TEST(GlShadowVolumes, HardCases) {
  ASSERT_NE(context(), nullptr);
  struct Setup {
    const char* name;
    glm::vec3 offset;
    geom::Camera view;
    geom::Light light;
  };
  std::vector<Setup> setups;
  geom::Light point;
  point = point_light({-1.0f, 5.0f, -2.5f});
  setups.push_back({"far from the origin", glm::vec3(1.0e5f, 0, -1.0e5f), view_from({4, 5, 8}, {0, 0.5f, 0}), point});
  geom::Light behind;
  behind = point_light({6.0f, 7.0f, 12.0f});  // behind the camera at (4, 5, 8) looking at the origin
  setups.push_back({"light behind the viewer", glm::vec3(0), view_from({4, 5, 8}, {0, 0.5f, 0}), behind});
  geom::Light grazing;
  grazing = point_light({-4.0f, 1.2f, 3.0f});  // in the plane of the first box's top face (y = 1.2)
  setups.push_back({"light in a face's plane", glm::vec3(0), view_from({4, 5, 8}, {0, 0.5f, 0}), grazing});
  for (Setup& setup : setups) {
    geom::Scene scene = closed_scene();
    for (size_t i = 0; i < scene.positions.size(); i += 3)
      for (int k = 0; k < 3; ++k) scene.positions[i + k] += setup.offset[k];
    set3(setup.view.eye, vec3(setup.view.eye) + setup.offset),
        set3(setup.view.target, vec3(setup.view.target) + setup.offset);
    if (!directional(setup.light))  // moved with the scene, in float as the scene's positions are
      for (int k = 0; k < 3; ++k) setup.light.position[k] = float(float(setup.light.position[k]) + setup.offset[k]);
    std::string error;
    auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
    ASSERT_TRUE(state) << error;
    for (Technique t : {Technique::Sv, Technique::SvZFail}) {
      const Comparison c = render_and_compare(*state, scene, setup.view, setup.light, t, 256);
      SCOPED_TRACE(std::string(setup.name) + " " + render::technique_name(t));
      EXPECT_EQ(c.wrong, 0u) << c.wrong << " of " << c.certain << " certain pixels differ";
      EXPECT_GT(c.lit + c.shadowed, 5000u);
    }
  }
}

// The light exactly at the top corner of the floating box, and inside one of
// its top triangles: the faces through the light have flat frusta and
// collapse (geom/shadow_volume.h), the rest matches the reference.
TEST(GlShadowVolumes, LightOnACaster) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = closed_scene();
  size_t top = 0;
  for (size_t v = 0; v < scene.vertex_count(); ++v)
    if (scene.positions[3 * v + 1] > scene.positions[3 * top + 1]) top = v;
  size_t face = 0;  // a triangle through that corner
  while (face + 1 < scene.triangle_count() && scene.indices[3 * face] != top && scene.indices[3 * face + 1] != top &&
         scene.indices[3 * face + 2] != top)
    ++face;
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (int where = 0; where < 2; ++where) {
    geom::Light l;
    glm::vec3 p(0);
    for (int k = 0; k < 3; ++k)
      p[k] = where == 0 ? scene.positions[3 * top + k]
                        : (scene.positions[3 * scene.indices[3 * face] + k] +
                           scene.positions[3 * scene.indices[3 * face + 1] + k] +
                           scene.positions[3 * scene.indices[3 * face + 2] + k]) /
                              3;
    l = point_light({p});
    for (Technique t : {Technique::Sv, Technique::SvZFail}) {
      const Comparison c = render_and_compare(*state, scene, view_from({4, 5, 8}, {0, 0.5f, 0}), l, t, 256);
      SCOPED_TRACE(std::string(where == 0 ? "at a vertex " : "inside a face ") + render::technique_name(t));
      EXPECT_EQ(c.wrong, 0u) << c.wrong << " of " << c.certain << " certain pixels differ";
      EXPECT_GT(c.lit + c.shadowed, 5000u);
    }
  }
}

// An empty scene renders background only, with every technique.
TEST(GlShadowVolumes, EmptyScene) {
  ASSERT_NE(context(), nullptr);
  std::string error;
  auto state = render::create_state(geom::Scene(), GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  geom::Light l;
  l = point_light({1, 5, 2});
  for (Technique t : render::available_techniques()) {
    render::FrameSettings fs;
    fs.technique = t;
    fs.output = render::Output::Mask;
    fs.inspect = true;
    geom::PngImage mask;
    std::vector<render::PassTime> times;
    ASSERT_TRUE(render::render(*state, view_from({4, 5, 8}, {0, 0, 0}), l, fs, mask, times, error))
        << render::technique_name(t) << ": " << error;
    size_t background = 0;
    for (uint8_t v : mask.pixels) background += v == 128;
    EXPECT_EQ(background, mask.pixels.size()) << render::technique_name(t);
  }
}

}  // namespace
