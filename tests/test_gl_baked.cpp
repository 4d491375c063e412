// geomview drawing a baked container (geom/bake.h -> geom/baked_writer.h ->
// render::create_state_baked) instead of baking in process: the buffers as they
// lie in the file give the exact shadow-volume mask (the law of
// test_gl_shadow_volumes), and hostile containers are refused with a message.
#include "geom/bake.h"
#include "geom/baked_writer.h"
#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

// Two boxes (one floating), a sheet and a ground: closed and open casters in one file.
geom::Scene scene() {
  geom::Scene s;
  add_ground(s, 5);
  add_box(s, box_at({-1.2f, 0.6f, 0}, {0.6f, 0.6f, 0.6f}, 25));
  add_box(s, box_at({1.2f, 2.0f, 0.5f}, {0.4f, 0.3f, 0.5f}, -10));
  add_quad(s, {0.0f, 1.5f, -2.0f}, {0.0f, 1.7f, -1.0f}, {1.5f, 1.7f, -1.0f}, {1.5f, 1.5f, -2.0f});
  return s;
}

std::vector<unsigned char> baked_bytes(const geom::Scene& s, const geom::BakeOptions& options = {}) {
  const geom::BakeResult bake = geom::bake_scene(s, "test scene", options);
  EXPECT_TRUE(bake.ok) << bake.error;
  std::vector<unsigned char> bytes;
  std::string error;
  EXPECT_TRUE(geom::serialize_baked(bake.sections, bytes, error)) << error;
  return bytes;
}

geom::Camera view() { return camera({4, 5, 7}, {0, 0.7f, 0}, 50, 0.1f, 100, 160, 120); }

TEST(GlBaked, VolumesFromTheFileMatchTheReference) {
  ASSERT_NE(context(), nullptr);
  const std::vector<unsigned char> bytes = baked_bytes(scene());
  geom::Scene from_file;
  std::string error;
  auto state = render::create_state_baked(bytes.data(), bytes.size(), GEOM_SHADER_DIR, from_file, error);
  ASSERT_TRUE(state) << error;
  EXPECT_EQ(from_file.triangle_count(), scene().triangle_count());
  geom::Light point, dir;
  point = point_light({-1.0f, 5.0f, -2.0f});
  dir = sun({0.5f, 1.0f, -0.3f});
  for (const geom::Light& l : {point, dir})
    for (Technique t : {Technique::Sv, Technique::SvZFail, Technique::SvZPass}) {
      const Comparison c = render_and_compare(*state, from_file, view(), l, t, 256);
      SCOPED_TRACE(render::technique_name(t));
      EXPECT_EQ(c.wrong, 0u) << c.wrong << " of " << c.certain;
      EXPECT_GT(c.shadowed, 300u);
    }
  // The shadow-map techniques that read the file's ESM quads and adjacency run too.
  for (Technique t : {Technique::Esm, Technique::Edsm}) {
    const Comparison c = render_and_compare(*state, from_file, view(), point, t, 1024);
    EXPECT_LT(c.error(), 0.01) << render::technique_name(t);
  }
}

// A light the scene declares gets its exact volume (build_light_volume), baked in
// process or read from the file; the mask stays exact.
TEST(GlBaked, ExactVolumesOfDeclaredLights) {
  ASSERT_NE(context(), nullptr);
  geom::Scene s = scene();
  geom::Light point;
  point.type = geom::LightType::Point;
  point.position[0] = -1.0f, point.position[1] = 5.0f, point.position[2] = -2.0f;
  s.lights.push_back(point);
  geom::Light sun;
  sun.type = geom::LightType::Directional;
  sun.direction[0] = -0.5f, sun.direction[1] = -1.0f, sun.direction[2] = 0.3f;  // travels along
  s.lights.push_back(sun);
  const std::vector<unsigned char> bytes = baked_bytes(s);
  geom::Scene from_file;
  std::string error;
  auto baked = render::create_state_baked(bytes.data(), bytes.size(), GEOM_SHADER_DIR, from_file, error);
  ASSERT_TRUE(baked) << error;
  auto in_process = render::create_state(s, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(in_process) << error;
  geom::Light l0, l1;
  l0 = point_light({-1.0f, 5.0f, -2.0f});
  l1 = gltest::sun({0.5f, 1.0f, -0.3f});
  for (render::State* state : {baked.get(), in_process.get()})
    for (const geom::Light& l : {l0, l1})
      for (Technique t : {Technique::SvZPass, Technique::SvZFail}) {
        const Comparison c = render_and_compare(*state, s, view(), l, t, 256);
        EXPECT_EQ(c.wrong, 0u) << c.wrong << " of " << c.certain;
        render::FrameSettings fs;
        fs.technique = t;
        geom::PngImage image;
        std::vector<render::PassTime> times;
        ASSERT_TRUE(render::render(*state, view(), l, fs, image, times, error)) << error;
        bool exact = false;
        for (const auto& pt : times) exact = exact || pt.pass.find("exact") != std::string::npos;
        EXPECT_TRUE(exact) << "the declared light's exact volume should be drawn";
      }
}

TEST(GlBaked, MissingBuffersAreNamed) {
  ASSERT_NE(context(), nullptr);
  geom::BakeOptions options;
  options.pipeline.volume = false;
  options.scene_lights = false;
  const std::vector<unsigned char> bytes = baked_bytes(scene(), options);
  geom::Scene from_file;
  std::string error;
  auto state = render::create_state_baked(bytes.data(), bytes.size(), GEOM_SHADER_DIR, from_file, error);
  ASSERT_TRUE(state) << error;
  render::FrameSettings fs;
  fs.technique = Technique::Sv;
  geom::PngImage image;
  std::vector<render::PassTime> times;
  EXPECT_FALSE(render::render(*state, view(), geom::Light(), fs, image, times, error));
  EXPECT_NE(error.find("no buffers for sv"), std::string::npos) << error;
}

TEST(GlBaked, HostileContainersAreRefused) {
  ASSERT_NE(context(), nullptr);
  const std::vector<unsigned char> bytes = baked_bytes(scene());
  geom::Scene from_file;
  std::string error;
  // Every truncation is refused (the reader checks the length and checksums).
  for (size_t n = 0; n < bytes.size(); n += 1 + n / 7) {
    EXPECT_FALSE(render::create_state_baked(bytes.data(), n, GEOM_SHADER_DIR, from_file, error)) << n;
    EXPECT_FALSE(error.empty());
  }
  // A well-formed file whose index points outside the positions.
  std::vector<geom::BakedSection> sections;
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<uint32_t> bad = {0, 1, 7};
  sections.push_back(
      geom::make_baked_section(geom::baked::SectionType::Positions, geom::baked::Format::F32x3, 12, "positions", p));
  sections.push_back(
      geom::make_baked_section(geom::baked::SectionType::Indices, geom::baked::Format::U32, 4, "indices", bad));
  std::vector<unsigned char> file;
  ASSERT_TRUE(geom::serialize_baked(sections, file, error)) << error;
  EXPECT_FALSE(render::create_state_baked(file.data(), file.size(), GEOM_SHADER_DIR, from_file, error));
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;
  // Adjacency indices out of range, everything else valid.
  sections[1] = geom::make_baked_section(geom::baked::SectionType::Indices, geom::baked::Format::U32, 4, "indices",
                                         std::vector<uint32_t>{0, 1, 2});
  sections.push_back(geom::make_baked_section(geom::baked::SectionType::AdjacencyIndices, geom::baked::Format::U32, 4,
                                              "adjacency", std::vector<uint32_t>{0, 9, 1, 2, 2, 0}));
  ASSERT_TRUE(geom::serialize_baked(sections, file, error)) << error;
  EXPECT_FALSE(render::create_state_baked(file.data(), file.size(), GEOM_SHADER_DIR, from_file, error));
  EXPECT_NE(error.find("adjacency index"), std::string::npos) << error;
}

}  // namespace
