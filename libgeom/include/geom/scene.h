// geom/scene.h: the imported scene, flattened to world space.
//
// Every importer (glTF, OBJ, PLY, OFF, STL, Quake 3 BSP / MD3) produces this:
// one triangle soup in world coordinates (node transforms applied, instances
// expanded), each triangle tagged with where it came from, plus the punctual
// lights the file declares. Units and handedness are those of the file (glTF:
// metres, right-handed, +Y up).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace geom {

// Where a triangle came from. Indices into the file's own arrays; kNone where
// the format has no such notion (an OBJ has no nodes, an STL no meshes).
struct TriangleSource {
  static constexpr uint32_t kNone = 0xffffffffu;
  uint32_t file = 0;           // index into Scene::files
  uint32_t mesh = kNone;       // glTF mesh, OBJ object/group, BSP model, MD3 surface
  uint32_t primitive = kNone;  // glTF primitive, BSP face
  uint32_t node = kNone;       // glTF node that instanced the mesh
};

enum class LightType : uint8_t { Directional, Point, Spot };

// A punctual light (KHR_lights_punctual semantics, in world space).
struct Light {
  LightType type = LightType::Point;
  std::string name;
  float position[3] = {0, 0, 0};    // point and spot
  float direction[3] = {0, 0, -1};  // unit; the direction the light travels (spot, directional)
  float range = 0;                  // 0 = infinite
  float inner_cone = 0;             // radians, spot only (angle from axis)
  float outer_cone = 0.7853982f;    // radians, spot only (angle from axis to cone edge)
  float color[3] = {1, 1, 1};
  float intensity = 1;
};

struct Scene {
  std::vector<float> positions;         // xyz per vertex, world space
  std::vector<uint32_t> indices;        // 3 per triangle, into positions
  std::vector<TriangleSource> sources;  // one per triangle
  std::vector<std::string> files;       // source file names (TriangleSource::file)
  std::vector<Light> lights;
  std::vector<std::string> warnings;    // non-fatal problems, each naming the file

  // Per-format counts a report may show (e.g. BSP "polygon", "mesh", "patch",
  // "billboard" faces and the triangles each produced). Key, value pairs.
  std::vector<std::pair<std::string, uint64_t>> source_counts;

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace geom
