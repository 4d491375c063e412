// tools/geombench/scenes.cpp: the scenes of scenes.h. Procedural geometry is
// indexed and closed where a real asset would be (boxes, pipes, spheres), each
// object one caster (its own TriangleSource::mesh) so that per-caster shadow
// volumes see separate objects.
#include "scenes.h"

#include <draco/compression/decode.h>

#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>

#include "cli/file.h"
#include "geom/import.h"
#include "geom/shadow_reference.h"

namespace geombench {
namespace {

uint32_t next_mesh(const geom::Scene& s) {
  uint32_t m = 0;
  for (const auto& src : s.sources)
    if (src.mesh != geom::TriangleSource::kNone && src.mesh + 1 > m) m = src.mesh + 1;
  return m;
}

void tag_from(geom::Scene& s, size_t first_triangle) {
  const uint32_t m = next_mesh(s);
  s.sources.resize(s.triangle_count());
  for (size_t t = first_triangle; t < s.sources.size(); ++t) s.sources[t].mesh = m;
}

uint32_t add_vertex(geom::Scene& s, glm::vec3 p) {
  s.positions.insert(s.positions.end(), {p.x, p.y, p.z});
  return uint32_t(s.vertex_count() - 1);
}

// a-b-c-d counter-clockwise seen from the front, one caster.
void add_quad(geom::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  const size_t first = s.triangle_count();
  const uint32_t i = add_vertex(s, a), j = add_vertex(s, b), k = add_vertex(s, c), l = add_vertex(s, d);
  s.indices.insert(s.indices.end(), {i, j, k, i, k, l});
  tag_from(s, first);
}

void add_ground(geom::Scene& s, float x0, float x1, float z0, float z1) {
  add_quad(s, {x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0});
}

// The unit cube [-1,1]^3 under m: 8 shared corners, 12 outward triangles.
void add_box(geom::Scene& s, const glm::mat4& m) {
  const size_t first = s.triangle_count();
  uint32_t c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = add_vertex(s, glm::vec3(m * glm::vec4(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1, 1)));
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : faces) s.indices.insert(s.indices.end(), {c[q[0]], c[q[1]], c[q[2]], c[q[0]], c[q[2]], c[q[3]]});
  tag_from(s, first);
}

glm::mat4 box_at(glm::vec3 centre, glm::vec3 half, float yaw_deg = 0) {
  return glm::scale(glm::rotate(glm::translate(glm::mat4(1), centre), glm::radians(yaw_deg), glm::vec3(0, 1, 0)), half);
}

// A closed cylinder from a to b: `segments` sides, capped by fans.
void add_pipe(geom::Scene& s, glm::vec3 a, glm::vec3 b, float radius, int segments) {
  const size_t first = s.triangle_count();
  const glm::vec3 axis = glm::normalize(b - a);
  const glm::vec3 u =
      glm::normalize(glm::cross(axis, std::fabs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
  const glm::vec3 v = glm::cross(axis, u);
  const uint32_t ca = add_vertex(s, a), cb = add_vertex(s, b), ring = uint32_t(s.vertex_count());
  for (int i = 0; i < segments; ++i) {
    const float t = 6.28318531f * float(i) / float(segments);
    const glm::vec3 r = radius * (std::cos(t) * u + std::sin(t) * v);
    add_vertex(s, a + r);
    add_vertex(s, b + r);
  }
  for (int i = 0; i < segments; ++i) {
    const uint32_t a0 = ring + 2 * i, b0 = a0 + 1, a1 = ring + 2 * ((i + 1) % segments), b1 = a1 + 1;
    s.indices.insert(s.indices.end(), {a0, a1, b1, a0, b1, b0, ca, a1, a0, cb, b0, b1});
  }
  tag_from(s, first);
}

geom::Light directional(glm::vec3 towards_light) {
  const glm::vec3 t = glm::normalize(towards_light);
  const double h[4] = {t.x, t.y, t.z, 0};
  return geom::light_from_homogeneous(h);
}

geom::Light point(glm::vec3 p) {
  const double h[4] = {p.x, p.y, p.z, 1};
  return geom::light_from_homogeneous(h);
}

geom::Camera look(glm::vec3 eye, glm::vec3 target, float near_plane, float far_plane, float fovy = 60) {
  geom::Camera v;
  for (int k = 0; k < 3; ++k) v.eye[k] = eye[k], v.target[k] = target[k];
  v.near_plane = near_plane, v.far_plane = far_plane, v.fovy_deg = fovy;
  return v;
}

// An alley 400 m long along -z: a ground strip and a pillar every 4 m on
// alternating sides, seen from one end at eye height.
void alley(BenchScene& b) {
  add_ground(b.scene, -6, 6, -400, 2);
  for (int i = 1; i <= 100; ++i) {
    const float z = -4.0f * float(i), x = i % 2 ? -2.5f : 2.5f;
    add_box(b.scene, box_at({x, 1.5f, z}, {0.3f, 1.5f, 0.3f}, float(i * 7 % 45)));
  }
  b.hard = true;
  b.default_view = false;
  b.view = look({0, 1.7f, 1.5f}, {0, 1.2f, -30}, 0.1f, 500);
}

// A colonnade 200 m long along -z: a ground strip, two rows of round pillars
// (16-sided, 0.35 m radius, 4 m tall) every 5 m under a flat roof beam per
// pair, seen from one end at eye height: receivers from 0.5 m to 200 m.
void colonnade(BenchScene& b) {
  add_ground(b.scene, -8, 8, -205, 3);
  for (int i = 0; i < 40; ++i) {
    const float z = -5.0f * float(i) - 3;
    for (float x : {-3.0f, 3.0f}) add_pipe(b.scene, {x, 0, z}, {x, 4, z}, 0.35f, 16);
    add_box(b.scene, box_at({0, 4.15f, z}, {3.6f, 0.15f, 0.4f}));
  }
  b.hard = true;
  b.default_view = false;
  b.view = look({0.8f, 1.7f, 2}, {0.2f, 1.5f, -40}, 0.1f, 400);
}

// A raw Draco mesh file (the Stanford bunny of Draco's test data).
// Scaled to a largest extent of 1, standing on y = 0, centred on the y axis.
bool add_draco(geom::Scene& s, const std::string& path, std::string& error) {
  std::string bytes;
  if (!cli::read_file(path, bytes, error)) return error = path + ": " + error, false;
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return error = path + ": not a Draco mesh: " + decoded.status().error_msg_string(), false;
  const draco::Mesh& mesh = *decoded.value();
  const draco::PointAttribute* att = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!att || att->num_components() != 3) return error = path + ": no 3-component POSITION attribute", false;
  const size_t first = s.triangle_count(), base = s.vertex_count(), np = mesh.num_points();
  glm::vec3 lo(1e30f), hi(-1e30f);
  std::vector<glm::vec3> p(np);
  for (size_t i = 0; i < np; ++i) {
    float v[3];
    if (!att->ConvertValue<float, 3>(att->mapped_index(draco::PointIndex(uint32_t(i))), v))
      return error = path + ": point " + std::to_string(i) + " cannot be read", false;
    p[i] = glm::vec3(v[0], v[1], v[2]);
    lo = glm::min(lo, p[i]), hi = glm::max(hi, p[i]);
  }
  const glm::vec3 ext = hi - lo;
  const float scale = 1.0f / std::max(std::max(ext.x, ext.y), std::max(ext.z, 1e-30f));
  const glm::vec3 origin((lo.x + hi.x) / 2, lo.y, (lo.z + hi.z) / 2);
  for (glm::vec3 q : p) add_vertex(s, (q - origin) * scale);
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      if (face[k].value() >= np) return error = path + ": face " + std::to_string(f) + " out of range", false;
      s.indices.push_back(uint32_t(base + face[k].value()));
    }
  }
  tag_from(s, first);
  return true;
}

// A Quake 3 map (z up, units of an inch): the light 120 units above the floor
// triangle nearest the level's centre, the camera above another floor triangle
// 300 to 700 units away, looking at the light's floor point.
bool quake3(BenchScene& b, std::string& error) {
  const std::string path = "/usr/share/games/openarena/baseoa/pak1-maps.pk3:maps/oa_dm1.bsp";
  geom::ImportResult r = geom::import_file(path);
  if (!r.ok) return error = r.error, false;
  b.scene = std::move(r.scene);
  const geom::Scene& s = b.scene;
  glm::vec3 lo(1e30f), hi(-1e30f);
  std::vector<glm::vec3> floors;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      const float* q = &s.positions[3 * size_t(s.indices[3 * t + k])];
      p[k] = glm::vec3(q[0], q[1], q[2]);
      lo = glm::min(lo, p[k]), hi = glm::max(hi, p[k]);
    }
    const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const float area = glm::length(n);
    if (area > 2 * 64 * 64 && n.z > 0.99f * area) floors.push_back((p[0] + p[1] + p[2]) / 3.0f);
  }
  if (floors.empty()) return error = path + ": no floor triangle to put the light above", false;
  const glm::vec3 centre = (lo + hi) * 0.5f;
  glm::vec3 lf = floors[0];
  for (glm::vec3 f : floors)
    if (glm::distance(f, centre) < glm::distance(lf, centre)) lf = f;
  b.light = point(lf + glm::vec3(0, 0, 120));
  // The camera: of up to 64 floor points 200 to 900 units from the light's, the
  // one whose view (eye 56 units above it, looking at the light's floor point)
  // shows the most of both lit and shadowed surface in a small reference image:
  // a view into a wall or out of the level scores nothing.
  std::vector<glm::vec3> candidates;
  for (glm::vec3 f : floors)
    if (glm::distance(f, lf) >= 200 && glm::distance(f, lf) <= 900) candidates.push_back(f);
  const size_t step = std::max<size_t>(1, candidates.size() / 64);
  size_t best_score = 0;
  b.default_view = false;
  b.view = look(lf + glm::vec3(300, 0, 56), lf + glm::vec3(0, 0, 40), 2, 8000, 75);
  b.view.up[0] = 0, b.view.up[1] = 0, b.view.up[2] = 1;
  for (size_t i = 0; i < candidates.size(); i += step) {
    geom::Camera v = look(candidates[i] + glm::vec3(0, 0, 56), lf + glm::vec3(0, 0, 40), 2, 8000, 75);
    v.up[0] = 0, v.up[1] = 0, v.up[2] = 1;
    geom::Camera c = v;
    c.width = 64, c.height = 48;
    const geom::ShadowReference ref = geom::shadow_reference(geom::positions_of(s.positions.data(), s.vertex_count()),
                                                             s.indices.data(), s.indices.size(), c, b.light);
    if (!ref.ok) continue;
    size_t lit = 0, dark = 0, none = 0;
    for (uint8_t m : ref.mask) (m == 255 ? lit : m == 0 ? dark : none)++;
    const size_t score = none > ref.mask.size() / 10 ? 0 : std::min(lit, dark);
    if (score > best_score) best_score = score, b.view = v;
  }
  b.hard = true;
  return true;
}

}  // namespace

void add_sphere(geom::Scene& s, int n, float radius, const float centre[3]) {
  const size_t first = s.triangle_count();
  const uint32_t base = uint32_t(s.vertex_count());
  const glm::vec3 c(centre[0], centre[1], centre[2]);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = 2 * M_PI * (i % n) / n, v = M_PI * (0.02 + 0.96 * j / n);
      const double r = radius * (1 + 0.02 * std::sin(37 * u) * std::sin(23 * v));
      add_vertex(s, c + glm::vec3(float(r * std::cos(u) * std::sin(v)), float(r * std::cos(v)),
                                  float(r * std::sin(u) * std::sin(v))));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = base + j * (n + 1) + i, b = a + 1, cc = a + n + 1, d = cc + 1;
      s.indices.insert(s.indices.end(), {a, b, cc, b, d, cc});
    }
  const uint32_t top = add_vertex(s, c + glm::vec3(0, radius * 0.9995f, 0));
  const uint32_t bottom = add_vertex(s, c - glm::vec3(0, radius * 0.9995f, 0));
  for (int i = 0; i < n; ++i) {
    s.indices.insert(s.indices.end(), {top, base + uint32_t(i + 1), base + uint32_t(i)});
    const uint32_t a = base + n * (n + 1) + i;
    s.indices.insert(s.indices.end(), {bottom, a, a + 1});
  }
  tag_from(s, first);
}

std::vector<std::string> scene_names() {
  return {"default", "pipes", "jenga",     "heavy",  "wide-depth", "duelling",
          "grazing", "scan",  "colonnade", "behind", "near-plane", "quake3"};
}
std::vector<std::string> quick_scene_names() { return {"default", "pipes", "grazing"}; }

namespace {

// The procedural scenes; false when `name` is none of them.
bool procedural_scene(const std::string& name, BenchScene& b) {
  if (name == "pipes") {
    add_ground(b.scene, -4, 4, -3, 4);
    add_quad(b.scene, {-4, 0, -2}, {4, 0, -2}, {4, 4, -2}, {-4, 4, -2});
    add_pipe(b.scene, {-3, 0.5f, 0}, {3, 3.5f, -0.6f}, 0.12f, 24);
    add_pipe(b.scene, {-3, 3.5f, -0.3f}, {3, 0.5f, 0.3f}, 0.12f, 24);
    b.light = point({0.5f, 3, 5});
    b.hard = true;
    b.default_view = false;
    b.view = look({-2.5f, 2.5f, 6}, {0, 1.8f, -1}, 0.1f, 50);
    b.description = "crossed pipes in front of a wall, point light (Bujnak 2004's test scene)";
  } else if (name == "jenga") {
    add_ground(b.scene, -12, 12, -12, 12);
    for (int tower = 0; tower < 9; ++tower)
      for (int level = 0; level < 55; ++level)
        for (int k = 0; k < 3; ++k) {
          const glm::vec3 base(-6.0f + 6.0f * float(tower % 3), 0.0f, -6.0f + 6.0f * float(tower / 3));
          const float off = 0.52f * float(k - 1), y = 0.15f + 0.3f * float(level);
          const bool turn = level % 2;
          const glm::vec3 c = base + (turn ? glm::vec3(off, y, 0) : glm::vec3(0, y, off));
          add_box(b.scene, box_at(c, turn ? glm::vec3(0.25f, 0.149f, 0.78f) : glm::vec3(0.78f, 0.149f, 0.25f)));
        }
    b.light = directional({0.5f, 1.0f, 0.3f});
    b.hard = true;
    b.description = "9 jenga towers, 17,820 triangles (Kenzel 2013's jenga size)";
  } else if (name == "heavy") {
    add_ground(b.scene, -3, 3, -3, 3);
    const float c[3] = {0, 1.2f, 0};
    add_sphere(b.scene, 500, 1, c);
    b.light = point({2, 4, 1.5f});
    b.description = "a rippled sphere of 501,000 triangles (Kenzel 2013's phaeno size)";
  } else if (name == "wide-depth") {
    alley(b);
    b.light = directional({1, 0.7f, 0});
    b.description = "400 m alley, directional light perpendicular to the view (Stamminger and Drettakis 2002, Fig. 1)";
  } else if (name == "duelling") {
    alley(b);
    b.light = directional({0, 0.6f, -1});
    b.description = "400 m alley, light facing the camera (duelling frusta)";
  } else if (name == "grazing") {
    add_ground(b.scene, -10, 10, -10, 10);
    for (int i = 0; i < 12; ++i)
      add_box(b.scene,
              box_at({-6.0f + float(i % 4) * 4, 0.5f, -4.0f + float(i / 4) * 4}, {0.5f, 0.5f, 0.5f}, float(i * 17)));
    b.light = directional({1, 0.0525f, 0.3f});
    b.hard = true;
    b.description = "blocks on a ground, directional light 3 degrees above it";
  } else if (name == "colonnade") {
    colonnade(b);
    b.light = directional({1, 0.45f, 0.15f});
    b.description = "200 m colonnade, sun from the side (wide depth range lit from the side)";
  } else if (name == "behind") {
    colonnade(b);
    b.light = point({1.5f, 6, 9});
    b.description = "200 m colonnade, point light behind and above the camera";
  } else {
    return false;
  }
  return true;
}

// A file of the file scenes: under $GEOMBENCH_DATA when set (a folder holding
// default_scene.gltf and bunny_gltf.drc, as scripts/gpu-timing.sh packs it),
// else where the source tree keeps it.
std::string data_file(const std::string& name, const std::string& source_path) {
  const char* dir = std::getenv("GEOMBENCH_DATA");
  return dir && *dir ? std::string(dir) + "/" + name : source_path;
}

// The scenes read from files (the bundled scene, the bunny, the Quake 3 map).
bool file_scene(const std::string& name, BenchScene& b, std::string& error) {
  if (name == "default") {
    const std::string path =
        data_file("default_scene.gltf", std::string(GEOMBENCH_SOURCE_DIR) + "/data/default_scene.gltf");
    geom::ImportResult r = geom::import_file(path);
    if (!r.ok) return error = r.error, false;
    b.scene = std::move(r.scene);
    b.light = geom::light_from_scene(b.scene.lights);
    b.description = "data/default_scene.gltf, its own light";
  } else if (name == "near-plane") {
    const std::string path =
        data_file("default_scene.gltf", std::string(GEOMBENCH_SOURCE_DIR) + "/data/default_scene.gltf");
    geom::ImportResult r = geom::import_file(path);
    if (!r.ok) return error = r.error, false;
    b.scene = std::move(r.scene);
    b.light = geom::light_from_scene(b.scene.lights);
    b.default_view = false;
    b.view = look({6, 3, 5}, {2.5f, 1.2f, -1}, 6, 100, 45);  // the near plane 6 of the 8 units to the wall
    b.hard = true;
    b.description = "data/default_scene.gltf, near plane 6 units from the eye, in the pipes' shadow";
  } else if (name == "scan") {
    add_ground(b.scene, -1.5f, 1.5f, -1.5f, 1.5f);
    const std::string drc = data_file("bunny_gltf.drc", std::string(GEOMBENCH_TEST_DATA) + "/draco/bunny_gltf.drc");
    if (!add_draco(b.scene, drc, error)) return false;
    b.light = point({0.9f, 1.8f, 0.7f});
    b.hard = true;
    b.description = "the Stanford bunny (Draco test data), point light";
  } else if (name == "quake3") {
    if (!quake3(b, error)) return false;
    b.description = "OpenArena oa_dm1, point light inside the level";
  } else {
    return error = "unknown scene '" + name + "'", false;
  }
  return true;
}

}  // namespace

bool make_scene(const std::string& name, BenchScene& b, std::string& error) {
  b = BenchScene();
  b.name = name;
  return procedural_scene(name, b) || file_scene(name, b, error);
}

}  // namespace geombench
