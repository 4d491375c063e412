// The pipeline statistics of the shadow passes (render::PassCounters,
// ARB_pipeline_statistics_query) and the laws of the edge passes that they
// show: the figures Kenzel 2013, Sect. 5.1 (figs. 5.3, 5.4) sets beside the
// times, on llvmpipe through EGL.
//
//   side view:        sun (directional)
//                    /
//        +--+       /     a box floating over a flat ground of k x k quads;
//        +--+             the ground tessellated 2k x 2k has four times the
//   ==================    triangles and no more silhouette edges (its inner
//                         edges are coplanar, its border twice as long)
#include <algorithm>
#include <cstdio>
#include <map>

#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

// A flat ground of k x k quads (2 k^2 triangles, y = 0, half size 4) and a box over it.
geom::Scene ground_and_box(int k) {
  geom::Scene s;
  const float h = 4, step = 2 * h / float(k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const float x0 = -h + i * step, z0 = -h + j * step, x1 = x0 + step, z1 = z0 + step;
      add_quad(s, {x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0});
    }
  add_box(s, box_at({0.3f, 1.2f, -0.2f}, {0.8f, 0.5f, 0.6f}, 20));
  return s;
}

// A UV sphere of `rings` x 2 `rings` quads (closed; every edge a candidate:
// none coplanar) at `centre`, over a ground of 4 x 4 quads.
geom::Scene sphere_on_ground(int rings, glm::vec3 centre, float radius) {
  geom::Scene s = ground_and_box(4);
  const uint32_t base = uint32_t(s.vertex_count());
  const int segments = 2 * rings;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const float t = float(M_PI) * float(i) / float(rings), p = 2 * float(M_PI) * float(j) / float(segments);
      const glm::vec3 v =
          centre + radius * glm::vec3(std::sin(t) * std::cos(p), std::cos(t), std::sin(t) * std::sin(p));
      s.positions.insert(s.positions.end(), {v.x, v.y, v.z});
    }
  auto at = [&](int i, int j) { return base + uint32_t(i * segments + (j % segments)); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {  // outward: counter-clockwise seen from outside
      if (i > 0) s.indices.insert(s.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j)}), s.sources.push_back({});
      if (i + 1 < rings)
        s.indices.insert(s.indices.end(), {at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)}), s.sources.push_back({});
    }
  return s;
}

geom::Camera view() { return camera({2.0f, 6.0f, 7.0f}, {0, 0, 0}, 50, 0.1f, 100, 160, 120); }

struct Frame {
  std::vector<render::PassTime> times;
  std::string projection;
};

Frame frame(render::State& state, const geom::Light& light, Technique t, int size = 256) {
  render::FrameSettings fs;
  fs.technique = t, fs.output = render::Output::Mask, fs.shadow_map_size = size;
  geom::PngImage mask;
  Frame f;
  std::string error;
  EXPECT_TRUE(render::render(state, view(), light, fs, mask, f.times, error)) << error;
  f.projection = render::drawn_projection(state);
  return f;
}

// The counters of the passes whose name starts with `prefix`, summed.
render::PassCounters passes(const Frame& f, const std::string& prefix) {
  render::PassCounters sum;
  for (const render::PassTime& t : f.times)
    if (t.pass.rfind(prefix, 0) == 0) sum += t.counters;
  return sum;
}

std::vector<geom::Light> lights() {
  return {sun({0.4f, 1.0f, 0.3f}), sun({-0.7f, 0.6f, 0.2f}), sun({0.1f, 1.0f, -0.9f}),
          spot_light({1.0f, 6.0f, 2.0f}, {-0.15f, -1.0f, -0.35f}, 40)};
}

}  // namespace

// The depth map draws every scene triangle once per face; the counts are there
// for every technique's shadow passes and nothing else.
TEST(GlPassCounters, DepthMapPrimitivesAreTheSceneTriangles) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = ground_and_box(8);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (const geom::Light& light : lights()) {
    const Frame f = frame(*state, light, Technique::Ssm);
    ASSERT_EQ(f.projection, "fitted frustum");
    const render::PassCounters c = render::shadow_counters(f.times);
    ASSERT_TRUE(c.valid) << "the context has no ARB_pipeline_statistics_query";
    EXPECT_EQ(c.primitives, scene.triangle_count());
    EXPECT_EQ(c.gs_invocations, 0u);
    EXPECT_GT(c.vs_invocations, 0u);
    EXPECT_GT(c.fs_invocations, 0u);
    // The shading pass is not a shadow pass: its counts stay out of the sum.
    render::PassCounters all;
    for (const render::PassTime& t : f.times) all += t.counters;
    EXPECT_GT(all.primitives, c.primitives);
  }
}

// edsm and sssm find their silhouette edges without a geometry shader;
// edsm-gs and sssm-gs, the papers' path, run it over every triangle with
// adjacency in each edge pass (edsm: two per face, one per peeled edge).
TEST(GlPassCounters, EdsmAndSssmRunNoGeometryShader) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = ground_and_box(8);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  struct Pair {
    Technique vs, gs;
    const char* edge_pass;
    uint64_t passes;
  };
  for (const Pair& pair : {Pair{Technique::Edsm, Technique::EdsmGs, "edge distance map", 2},
                           Pair{Technique::Sssm, Technique::SssmGs, "silhouette map", 1}})
    for (const geom::Light& light : lights())
      for (int size : {128, 512}) {
        SCOPED_TRACE(std::string(render::technique_name(pair.vs)) + " " + std::to_string(size));
        const Frame d = frame(*state, light, pair.vs, size);
        const render::PassCounters c = render::shadow_counters(d.times);
        ASSERT_TRUE(c.valid);
        EXPECT_EQ(c.gs_invocations, 0u);
        EXPECT_GT(passes(d, pair.edge_pass).fs_invocations, 0u);
        const Frame g = frame(*state, light, pair.gs, size);
        EXPECT_EQ(render::shadow_counters(g.times).gs_invocations, pair.passes * scene.triangle_count());
      }
}

// Edge passes follow silhouette edges, not triangles: the ground four times
// finer quadruples the depth map's primitives (ssm) and edsm-gs's edge
// passes, while edsm's edge passes grow at most as the ground's border does
// (twice), its inner edges being coplanar.
TEST(GlPassCounters, EdgePassPrimitivesFollowSilhouetteEdgesNotTriangles) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene coarse = ground_and_box(16), fine = ground_and_box(32);
  ASSERT_EQ(fine.triangle_count() - 12, 4 * (coarse.triangle_count() - 12));
  std::string error;
  auto a = render::create_state(coarse, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(a) << error;
  auto b = render::create_state(fine, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(b) << error;
  for (const geom::Light& light : lights()) {
    auto ratio = [&](Technique t, const char* prefix) {
      const double pa = double(passes(frame(*a, light, t), prefix).primitives);
      const double pb = double(passes(frame(*b, light, t), prefix).primitives);
      EXPECT_GT(pa, 0) << render::technique_name(t);
      return pb / std::max(pa, 1.0);
    };
    const double ssm = ratio(Technique::Ssm, "depth map");
    EXPECT_GT(ssm, 3.8);
    EXPECT_LT(ssm, 4.01);
    EXPECT_GT(ratio(Technique::EdsmGs, "edge distance map"), 3.8);  // the geometry shader's input: every triangle
    EXPECT_LE(ratio(Technique::Edsm, "edge distance map"), 2.0);
  }
}

// A caster of many candidate edges (a sphere: thousands, none coplanar): the
// silhouette edges are found once per frame ("silhouette edges") and the edge
// passes draw them alone, far fewer primitives than edsm-gs's triangles, with
// a mask as close to the reference as edsm-gs's.
TEST(GlPassCounters, EdgePassesDrawOnlyTheSilhouetteOfALargeCaster) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = sphere_on_ground(40, {0.2f, 1.6f, 0.1f}, 1.2f);
  ASSERT_GT(scene.triangle_count(), 6000u);
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  for (const geom::Light& light : lights()) {
    const Frame d = frame(*state, light, Technique::Edsm, 512), g = frame(*state, light, Technique::EdsmGs, 512);
    const render::PassCounters de = passes(d, "edge distance map"), ge = passes(g, "edge distance map");
    ASSERT_GT(de.primitives, 0u);
    EXPECT_LE(4 * de.primitives, ge.primitives) << de.primitives << " against " << ge.primitives;
    EXPECT_EQ(render::shadow_counters(d.times).gs_invocations, 0u);
    EXPECT_EQ(std::count_if(d.times.begin(), d.times.end(),
                            [](const render::PassTime& t) { return t.pass == "silhouette edges"; }),
              1);
    const geom::ShadowError e = score(*state, scene, view(), light, Technique::Edsm, 512);
    const geom::ShadowError r = score(*state, scene, view(), light, Technique::EdsmGs, 512);
    EXPECT_LE(e.wrong_cast, r.wrong_cast + 3) << "edsm " << e.wrong_cast << ", edsm-gs " << r.wrong_cast;
    EXPECT_GT(e.cast_pixels, 1000u);
    std::printf(
        "edge-pass primitives edsm %llu, edsm-gs %llu; wrong cast-class pixels edsm %zu, edsm-gs %zu (of %zu)\n",
        (unsigned long long)de.primitives, (unsigned long long)ge.primitives, e.wrong_cast, r.wrong_cast,
        e.cast_pixels);
  }
}

// Many small casters (a grid of boxes, each its own glTF node and so its own
// caster of 12 candidate edges, over the ground and box of ground_and_box(4)):
// the edge passes draw the silhouette edges alone here too, not every
// candidate edge: a box's silhouette from a light outside it has at most 6
// edges, the first caster's (the ground's 16 border edges and its box) at most
// 22, 2 triangles each per edge pass. Drawing every caster's records, each
// closed quad submitted, would be 2 x 12 per box.
TEST(GlPassCounters, EdgePassesDrawOnlyTheSilhouettesOfManySmallCasters) {
  ASSERT_NE(context(), nullptr);
  geom::Scene scene = ground_and_box(4);
  constexpr int kSide = 10;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) {
      const size_t first = scene.triangle_count();
      add_box(scene, box_at({-3.5f + 0.7f * float(i), 0.3f, -3.5f + 0.7f * float(j)}, {0.15f, 0.3f, 0.15f},
                            float(i * 13 + j * 7)));
      for (size_t t = first; t < scene.triangle_count(); ++t) scene.sources[t].node = uint32_t(1 + i * kSide + j);
    }
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const uint64_t bound = 2 * (6 * kSide * kSide + 22);
  for (const geom::Light& light : lights()) {
    const Frame d = frame(*state, light, Technique::Edsm, 256), s = frame(*state, light, Technique::Sssm, 256);
    ASSERT_EQ(d.projection, "fitted frustum");
    const render::PassCounters second = passes(d, "edge distance map,"), both = passes(d, "edge distance map");
    EXPECT_GT(second.primitives, 0u);
    EXPECT_LE(second.primitives, bound);
    EXPECT_EQ(both.primitives, 2 * second.primitives);  // the first and the peeled pass draw the same quads
    EXPECT_LE(passes(s, "silhouette map").primitives, bound);
  }
}
