// The size law for the silhouette maps (sssm, sssm-gs; Sen et al. 2003) on
// geombench's jenga frame (tools/geombench/scenes.cpp, rebuilt here vertex for
// vertex, 640 x 480; the same figures as geombench's): error_visible
// (geom/shadow_error.h) at 4096 texels at most half its value at 512 (or under 0.01% of the visible
// pixels), and no size worse than the one before by more than 0.02 points
// (0.0002 of the visible pixels), from 256 to 4096.
#include <cstdio>

#include "gl_fixtures.h"

using namespace gltest;
using render::Technique;

namespace {

// The geometry of geombench's scenes: closed, indexed objects (shared corners),
// so that silhouette edges are found as geombench finds them.
uint32_t vertex(geom::Scene& s, glm::vec3 p) {
  s.positions.insert(s.positions.end(), {p.x, p.y, p.z});
  return uint32_t(s.vertex_count() - 1);
}

void ground(geom::Scene& s, float x0, float x1, float z0, float z1) {
  const uint32_t i = vertex(s, {x0, 0, z0}), j = vertex(s, {x0, 0, z1}), k = vertex(s, {x1, 0, z1}),
                 l = vertex(s, {x1, 0, z0});
  s.indices.insert(s.indices.end(), {i, j, k, i, k, l});
}

void box(geom::Scene& s, const glm::mat4& m) {
  uint32_t c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = vertex(s, glm::vec3(m * glm::vec4(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1, 1)));
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : faces) s.indices.insert(s.indices.end(), {c[q[0]], c[q[1]], c[q[2]], c[q[0]], c[q[2]], c[q[3]]});
}

void finish(geom::Scene& s) { s.sources.resize(s.triangle_count()); }

// Nine towers of 55 levels of three blocks, crossed level by level, under a sun.
geom::Scene jenga() {
  geom::Scene s;
  ground(s, -12, 12, -12, 12);
  for (int tower = 0; tower < 9; ++tower)
    for (int level = 0; level < 55; ++level)
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 base(-6.0f + 6.0f * float(tower % 3), 0.0f, -6.0f + 6.0f * float(tower / 3));
        const float off = 0.52f * float(k - 1), y = 0.15f + 0.3f * float(level);
        const bool turn = level % 2;
        const glm::vec3 c = base + (turn ? glm::vec3(off, y, 0) : glm::vec3(0, y, off));
        box(s, box_at(c, turn ? glm::vec3(0.25f, 0.149f, 0.78f) : glm::vec3(0.78f, 0.149f, 0.25f)));
      }
  finish(s);
  return s;
}

constexpr int kSizes[] = {256, 512, 1024, 2048, 4096};

// error_visible at each of kSizes, printed; the law's misses as text (empty: it holds).
std::string size_law(render::State& state, const geom::Scene& scene, const geom::Camera& view, const geom::Light& light,
                     Technique t, const char* name) {
  double e[5];
  std::string misses;
  std::printf("%s %s:", name, render::technique_name(t));
  for (int i = 0; i < 5; ++i) {
    const geom::ShadowError s = score(state, scene, view, light, t, kSizes[i]);
    e[i] = s.error_visible;
    std::printf(" %d %.5f (%zu px)", kSizes[i], e[i], s.wrong_visible);
    if (i > 0 && e[i] > e[i - 1] + 0.0002)
      misses += " " + std::to_string(kSizes[i - 1]) + "->" + std::to_string(kSizes[i]);
  }
  std::printf("\n");
  if (e[4] > std::max(0.5 * e[1], 1e-4)) misses += " 4096 not half of 512";
  return misses;
}

}  // namespace

// geombench's jenga frame: the default framing of the scene's bounds, a sun.
TEST(GlSizeLawEdges, SilhouetteMapsOnJenga) {
  ASSERT_NE(context(), nullptr);
  const geom::Scene scene = jenga();
  std::string error;
  auto state = render::create_state(scene, GEOM_SHADER_DIR, error);
  ASSERT_TRUE(state) << error;
  const geom::Camera view = render::default_view(*state, 640, 480);
  const geom::Light light = sun(glm::normalize(glm::vec3(0.5f, 1.0f, 0.3f)));
  for (Technique t : {Technique::Sssm, Technique::SssmGs})
    EXPECT_EQ(size_law(*state, scene, view, light, t, "jenga"), "") << render::technique_name(t);
}
