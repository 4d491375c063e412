// The silhouette maps' edge map is one target that every face and frame
// draws into again (render/src/edge_pass.cpp): each edge pass must start from
// its technique's "no edge" value, whatever the previous pass, face, frame,
// technique (edge-map format) or map size left there. Law: a frame rendered by
// a state that has drawn other frames before gives the very mask of the same
// frame rendered by a fresh state, on random cameras and lights of each kind,
// with techniques and map sizes (odd ones too) changing from frame to frame.
//
//   a few blocks on a ground, a random camera and light per frame; the
//   sequence edsm 96, sssm 96, esm-exact 96, edsm 97, esm 64, edsm-soft 128 ...
//   (each frame's format and size differ from the last one's)
#include <random>

#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

geom::Scene blocks() {
  geom::Scene s;
  add_ground(s, 5);
  add_box(s, box_at({0.0f, 0.6f, 0.0f}, {0.5f, 0.6f, 0.4f}, 15));
  add_box(s, box_at({-1.6f, 1.5f, 0.8f}, {0.6f, 0.2f, 0.6f}, -30));
  add_box(s, box_at({1.5f, 0.9f, -1.2f}, {0.3f, 0.9f, 0.3f}, 50));
  add_pipe(s, {-2.5f, 2.2f, -1.0f}, {2.5f, 2.0f, 1.5f}, 0.15f, 12);
  return s;
}

geom::PngImage draw(render::State& state, const geom::Camera& view, const geom::Light& light, Technique t, int size) {
  render::FrameSettings fs;
  fs.technique = t, fs.output = render::Output::Mask, fs.shadow_map_size = size;
  fs.light_radius = 0.05f;
  geom::PngImage mask;
  std::vector<render::PassTime> times;
  std::string error;
  EXPECT_TRUE(render::render(state, view, light, fs, mask, times, error)) << error;
  return mask;
}

}  // namespace

TEST(GlEdgeMapReuse, AFrameAfterOthersEqualsTheSameFrameDrawnFresh) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = blocks();
  std::string error;
  auto reused = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(reused) << error;
  const Technique order[] = {Technique::Edsm,   Technique::Sssm,    Technique::EsmExact, Technique::Edsm,
                             Technique::Esm,    Technique::EdsmSoft, Technique::EdsmGs,  Technique::SssmGs};
  const int sizes[] = {96, 96, 96, 97, 64, 128, 97, 61};
  std::mt19937 rng(2026);
  size_t differing_frames = 0, drawn = 0;
  for (int round = 0; round < 3; ++round)
    for (LightKind kind : {LightKind::Point, LightKind::Directional, LightKind::Spot})
      for (size_t i = 0; i < std::size(order); ++i) {
        geom::Camera view;
        geom::Light light;
        random_frame(rng, {0, 0.8f, 0}, 5, kind, view, light);
        const Technique t = order[(i + size_t(round)) % std::size(order)];
        const int size = sizes[(i + 2 * size_t(round)) % std::size(sizes)];
        SCOPED_TRACE(std::string(render::technique_name(t)) + " at " + std::to_string(size) + ", round " +
                     std::to_string(round) + ", light kind " + std::to_string(int(kind)));
        const geom::PngImage again = draw(*reused, view, light, t, size);
        auto fresh_state = render::create_state(scene, GEOM_SHADER_DIR, error);
        ASSERT_TRUE(fresh_state) << error;
        const geom::PngImage fresh = draw(*fresh_state, view, light, t, size);
        ASSERT_EQ(again.pixels.size(), fresh.pixels.size());
        size_t differ = 0, shadowed = 0;
        for (size_t p = 0; p < fresh.pixels.size(); ++p) {
          differ += again.pixels[p] != fresh.pixels[p];
          shadowed += fresh.pixels[p] == 0;
        }
        EXPECT_EQ(differ, 0u);
        differing_frames += differ > 0;
        drawn += shadowed > 0;
      }
  EXPECT_EQ(differing_frames, 0u);
  // Not a vacuous law: most frames hold shadows.
  EXPECT_GT(drawn, 3 * std::size(order) * 3 / 2);
}
