// The GL tests' fixtures in one place (tests/test_gl_*.cpp): scene builders for
// tiny programmatic scenes, cameras and lights (geom/scene.h's Camera and
// Light), one headless GL context per test process, and the comparison of a
// rendered mask with the ray-cast reference (geom/shadow_reference.h).
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>
#include <string>

#include "geom/import.h"
#include "geom/png.h"
#include "geom/scene.h"
#include "geom/shadow_error.h"
#include "geom/shadow_reference.h"
#include "render/platform.h"
#include "render/render.h"

namespace gltest {

inline void add_triangle(geom::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const uint32_t base = uint32_t(s.vertex_count());
  for (glm::vec3 p : {a, b, c}) s.positions.insert(s.positions.end(), {p.x, p.y, p.z});
  s.indices.insert(s.indices.end(), {base, base + 1, base + 2});
  s.sources.push_back({});
}

// a-b-c-d counter-clockwise seen from the front.
inline void add_quad(geom::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  add_triangle(s, a, b, c);
  add_triangle(s, a, c, d);
}

// A box given by a transform of the unit cube [-1,1]^3, outward-facing
// triangles sharing indexed corners (closed). `skip` lists faces left out
// (0..5: -x +x -y +y -z +z) to make the box open.
inline void add_box(geom::Scene& s, const glm::mat4& m, unsigned skip_mask = 0) {
  const uint32_t base = uint32_t(s.vertex_count());
  for (int i = 0; i < 8; ++i) {
    glm::vec3 p = glm::vec3(m * glm::vec4(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1, 1));
    s.positions.insert(s.positions.end(), {p.x, p.y, p.z});
  }
  //      6-----7     corners: bit 0 = +x, bit 1 = +y, bit 2 = +z
  //     /|    /|
  //    2-----3 |
  //    | 4---|-5
  //    |/    |/
  //    0-----1
  const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (int f = 0; f < 6; ++f) {
    if (skip_mask & (1u << f)) continue;
    const uint32_t* q = faces[f];
    s.indices.insert(s.indices.end(), {base + q[0], base + q[1], base + q[2], base + q[0], base + q[2], base + q[3]});
    s.sources.push_back({});
    s.sources.push_back({});
  }
}

inline glm::mat4 box_at(glm::vec3 centre, glm::vec3 half, float yaw_deg = 0) {
  return glm::scale(glm::rotate(glm::translate(glm::mat4(1), centre), glm::radians(yaw_deg), glm::vec3(0, 1, 0)), half);
}

// Ground: a square at y = 0 of half-size h, facing +y.
inline void add_ground(geom::Scene& s, float h) { add_quad(s, {-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}); }

// A cylinder (closed by two caps) from a to b, `segments` sides.
inline void add_pipe(geom::Scene& s, glm::vec3 a, glm::vec3 b, float radius, int segments) {
  const glm::vec3 axis = glm::normalize(b - a);
  const glm::vec3 u =
      glm::normalize(glm::cross(axis, std::fabs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
  const glm::vec3 v = glm::cross(axis, u);
  auto ring = [&](glm::vec3 c, int i) {
    const float t = 6.28318531f * float(i % segments) / float(segments);
    return c + radius * (std::cos(t) * u + std::sin(t) * v);
  };
  for (int i = 0; i < segments; ++i) {
    add_quad(s, ring(a, i), ring(a, i + 1), ring(b, i + 1), ring(b, i));
    add_triangle(s, a, ring(a, i + 1), ring(a, i));
    add_triangle(s, b, ring(b, i), ring(b, i + 1));
  }
}

// Marks the triangles from `first` on as one caster (a glTF mesh of its own), so
// that techniques working per caster (shadow volumes) see separate objects.
inline void tag_caster(geom::Scene& s, size_t first, uint32_t mesh) {
  for (size_t t = first; t < s.sources.size(); ++t) s.sources[t].mesh = mesh;
}

// geombench's heavy scene (tools/geombench/scenes.cpp), coarser: a sphere of
// radius 1 centred 1.2 over a ground of half-size 3, rippled by 2%
// (sin 37u sin 23v), n x n quads; the ground and the sphere are two casters.
inline geom::Scene rippled_sphere(int n) {
  geom::Scene s;
  add_ground(s, 3);
  tag_caster(s, 0, 0);
  const glm::vec3 c(0, 1.2f, 0);
  const uint32_t base = uint32_t(s.vertex_count());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = 2 * M_PI * (i % n) / n, v = M_PI * (0.02 + 0.96 * j / n);
      const double r = 1 + 0.02 * std::sin(37 * u) * std::sin(23 * v);
      const glm::vec3 p = c + glm::vec3(float(r * std::cos(u) * std::sin(v)), float(r * std::cos(v)),
                                        float(r * std::sin(u) * std::sin(v)));
      s.positions.insert(s.positions.end(), {p.x, p.y, p.z});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = base + j * (n + 1) + i, b = a + 1, cc = a + n + 1, d = cc + 1;
      s.indices.insert(s.indices.end(), {a, b, cc, b, d, cc});
      s.sources.push_back({}), s.sources.push_back({});
    }
  tag_caster(s, 2, 1);
  return s;
}

inline void set3(float out[3], glm::vec3 v) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }
inline glm::vec3 vec3(const float v[3]) { return glm::vec3(v[0], v[1], v[2]); }

// A camera looking from `eye` at `target` (up +y unless given).
inline geom::Camera camera(glm::vec3 eye, glm::vec3 target, float fovy_deg, float near_plane, float far_plane,
                           int width, int height) {
  geom::Camera c;
  set3(c.eye, eye), set3(c.target, target);
  c.fovy_deg = fovy_deg, c.near_plane = near_plane, c.far_plane = far_plane;
  c.width = width, c.height = height;
  return c;
}

inline geom::Light point_light(glm::vec3 p) {
  const double h[4] = {p.x, p.y, p.z, 1};
  return geom::light_from_homogeneous(h);
}

// A directional light towards `towards_light` (it travels along -towards_light).
inline geom::Light sun(glm::vec3 towards_light) {
  const double h[4] = {towards_light.x, towards_light.y, towards_light.z, 0};
  return geom::light_from_homogeneous(h);
}

// A spot at `p` shining along `axis`, `half_angle_deg` from its axis to the cone's edge.
inline geom::Light spot_light(glm::vec3 p, glm::vec3 axis, float half_angle_deg) {
  geom::Light l = point_light(p);
  l.type = geom::LightType::Spot;
  for (int k = 0; k < 3; ++k) l.direction[k] = axis[k];
  l.outer_cone = half_angle_deg * M_PI / 180;
  return l;
}

inline bool directional(const geom::Light& l) { return l.type == geom::LightType::Directional; }

enum class LightKind { Point, Spot, Directional };

// A random camera around a scene of centre `c` and radius `r` (160x120, near
// r/100) and a random light of `kind` for it: the frames of the laws that hold
// on many random views (the warp law, the edge maps' law).
inline void random_frame(std::mt19937& rng, glm::vec3 c, float r, LightKind kind, geom::Camera& view,
                         geom::Light& light) {
  std::uniform_real_distribution<float> u(-1, 1), u01(0, 1);
  const glm::vec3 target = c + glm::vec3(u(rng), 0.3f * u(rng), u(rng)) * (0.7f * r);
  glm::vec3 dir(u(rng), 0.1f + 0.9f * u01(rng), u(rng));
  const glm::vec3 eye = target + glm::normalize(dir) * (r * (0.3f + 1.7f * u01(rng)));
  view = camera(eye, target, 30 + 40 * u01(rng), r * 0.01f, r * 100, 160, 120);
  if (kind == LightKind::Directional) {
    light = sun(glm::vec3(u(rng), 0.05f + u01(rng), u(rng)));
    return;
  }
  const glm::vec3 p = c + glm::vec3(u(rng), 0.1f + u01(rng), u(rng)) * (1.5f * r);
  if (kind == LightKind::Point) {
    light = point_light(p);
  } else {
    const glm::vec3 aim = c + glm::vec3(u(rng), 0, u(rng)) * (0.5f * r);
    light = spot_light(p, aim - p, 20 + 40 * u01(rng));
  }
}

// geombench's colonnade (tools/geombench/scenes.cpp): a ground strip, two rows
// of pillars every 5 m under a flat beam per pair.
inline geom::Scene colonnade() {
  geom::Scene s;
  add_quad(s, {-8, 0, -205}, {-8, 0, 3}, {8, 0, 3}, {8, 0, -205});
  tag_caster(s, 0, 0);
  uint32_t id = 1;
  for (int i = 0; i < 40; ++i) {
    const float z = -5.0f * float(i) - 3;
    for (float x : {-3.0f, 3.0f}) {
      const size_t first = s.sources.size();
      add_pipe(s, {x, 0, z}, {x, 4, z}, 0.35f, 16);
      tag_caster(s, first, id++);
    }
    const size_t first = s.sources.size();
    add_box(s, box_at({0, 4.15f, z}, {3.6f, 0.15f, 0.4f}));
    tag_caster(s, first, id++);
  }
  return s;
}

// One headless context for the whole test process.
inline render::Platform* context() {
  static std::unique_ptr<render::Platform> platform = [] {
    std::string note, error;
    auto p = render::Platform::open(false, 0, 0, "", note, error);
    if (!p) ADD_FAILURE() << error;
    return p;
  }();
  return platform.get();
}

// The bundled scene (data/default_scene.gltf) and its render state, for the
// GL tests that draw it (they link geom::import).
class DefaultSceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(context(), nullptr);
    geom::ImportResult imported = geom::import_file(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
    ASSERT_TRUE(imported.ok) << imported.error;
    scene = imported.scene;
    std::string error;
    state = render::create_state(scene, GEOM_SHADER_DIR, error);
    ASSERT_TRUE(state) << error;
  }
  geom::Scene scene;
  render::StatePtr state;
};

struct Comparison {
  size_t certain = 0;                            // pixels outside the reference's uncertain set
  size_t wrong = 0;                              // of them, pixels where the mask differs from the reference
  size_t lit = 0, shadowed = 0, background = 0;  // reference counts over certain pixels
  double error() const { return certain ? double(wrong) / double(certain) : 0.0; }
};

inline Comparison compare(const geom::PngImage& mask, const geom::ShadowReference& ref) {
  Comparison c;
  EXPECT_EQ(mask.width, ref.width);
  EXPECT_EQ(mask.height, ref.height);
  EXPECT_EQ(mask.channels, 1);
  if (mask.pixels.size() != ref.mask.size()) return c;
  for (size_t i = 0; i < ref.mask.size(); ++i) {
    if (ref.uncertain[i]) continue;
    ++c.certain;
    c.wrong += mask.pixels[i] != ref.mask[i];
    c.lit += ref.mask[i] == 255, c.shadowed += ref.mask[i] == 0, c.background += ref.mask[i] == 128;
  }
  return c;
}

// Renders the mask of `technique` and computes the reference of the same setup.
inline Comparison render_and_compare(render::State& state, const geom::Scene& scene, const geom::Camera& view,
                                     const geom::Light& light, render::Technique technique, int map_size,
                                     geom::PngImage* mask_out = nullptr, geom::ShadowReference* ref_out = nullptr) {
  render::FrameSettings fs;
  fs.technique = technique;
  fs.output = render::Output::Mask;
  fs.shadow_map_size = map_size;
  geom::PngImage mask;
  std::vector<render::PassTime> times;
  std::string error;
  EXPECT_TRUE(render::render(state, view, light, fs, mask, times, error)) << error;
  geom::ShadowReference ref = geom::shadow_reference(geom::positions_of(scene.positions.data(), scene.vertex_count()),
                                                     scene.indices.data(), scene.indices.size(), view, light);
  EXPECT_TRUE(ref.ok) << ref.error;
  if (mask_out) *mask_out = mask;
  const Comparison c = compare(mask, ref);
  if (const char* dir = std::getenv("GEOM_GL_TEST_DUMP")) {  // debugging aid: the mask and the reference
    static int counter = 0;
    const std::string base =
        std::string(dir) + "/" + std::to_string(counter++) + "_" + render::technique_name(technique);
    geom::PngImage r = mask;
    r.pixels = ref.mask;
    geom::write_png(base + ".png", mask, error);
    geom::write_png(base + "_ref.png", r, error);
  }
  if (ref_out) *ref_out = std::move(ref);
  return c;
}

// The mask of a technique scored by class against the reference (geom/shadow_error.h).
inline geom::ShadowError score(render::State& state, const geom::Scene& scene, const geom::Camera& view,
                               const geom::Light& light, render::Technique t, int size) {
  geom::PngImage mask;
  geom::ShadowReference ref;
  render_and_compare(state, scene, view, light, t, size, &mask, &ref);
  return geom::shadow_error(mask.pixels, ref);
}

// geombench's wide-depth alley (tools/geombench/scenes.cpp): a ground strip
// 400 m long along -z and a box pillar every 4 m on alternating sides.
inline geom::Scene alley() {
  geom::Scene s;
  add_quad(s, {-6, 0, -400}, {-6, 0, 2}, {6, 0, 2}, {6, 0, -400});
  tag_caster(s, 0, 0);
  for (int i = 1; i <= 100; ++i) {
    const float z = -4.0f * float(i), x = i % 2 ? -2.5f : 2.5f;
    const size_t first = s.sources.size();
    add_box(s, box_at({x, 1.5f, z}, {0.3f, 1.5f, 0.3f}, float(i * 7 % 45)));
    tag_caster(s, first, uint32_t(i));
  }
  return s;
}

// A random frame in the alley: the camera at eye height near its open end,
// looking down it (receivers from 0.1 m to hundreds of metres), 160 x 120;
// a sun anywhere 10 to 70 degrees above the horizon, from any side: across
// the alley, facing the camera, behind it.
inline void random_alley_frame(std::mt19937& rng, geom::Camera& view, geom::Light& light) {
  std::uniform_real_distribution<float> u(-1, 1), u01(0, 1);
  const glm::vec3 eye(1.5f * u(rng), 1.2f + 1.5f * u01(rng), 2 - 30 * u01(rng));
  const glm::vec3 target(2 * u(rng), 1.5f * u01(rng), eye.z - 20 - 80 * u01(rng));
  view = camera(eye, target, 60, 0.1f, 500, 160, 120);
  const float azimuth = 6.2831853f * u01(rng), elevation = 0.1745f + 1.0472f * u01(rng);
  light = sun({std::cos(elevation) * std::cos(azimuth), std::sin(elevation), std::cos(elevation) * std::sin(azimuth)});
}

}  // namespace gltest
