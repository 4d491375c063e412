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

// A punctual light, in world space: the one light type of the project (the
// importers, the bake, focus regions, the renderer and the reference all take
// it). glTF's convention (KHR_lights_punctual): `direction` is the direction
// in which the light travels (a directional light's rays, a spot's axis); it
// need not be unit length. Doubles, so that a light far from the origin keeps
// its precision in the per-frame focus computation (geom/focus.h).
struct Light {
  LightType type = LightType::Point;
  std::string name;
  double position[3] = {0, 0, 0};          // point and spot
  double direction[3] = {0, 0, -1};        // where the light travels (spot, directional)
  double range = 0;                        // point, spot: beyond it no light (0 = infinite)
  double inner_cone = 0;                   // radians, spot only (angle from axis)
  double outer_cone = 0.7853981633974483;  // radians, spot only (angle from axis to cone edge)
  float color[3] = {1, 1, 1};
  float intensity = 1;
};

// The homogeneous form the shaders take (u_light): (x, y, z, 1) at a point or
// spot light's position, (-direction, 0) for a directional light (the
// direction towards the light at infinity). The one conversion of the project.
void light_homogeneous(const Light& light, double out[4]);
// The inverse: w != 0 a point light at (x, y, z) / w, w == 0 a directional
// light travelling along -(x, y, z).
Light light_from_homogeneous(const double h[4]);
// The light a viewer or benchmark shows a scene with: the first light the
// scene declares, else a directional light from above (travelling along
// -(0.4, 1, 0.6)).
Light light_from_scene(const std::vector<Light>& lights);

// A perspective camera (right-handed look-at, OpenGL conventions): eye,
// target and up in world space, vertical field of view in degrees, near and
// far planes as view-space depths, the image size in pixels (aspect = width /
// height).
struct Camera {
  float eye[3] = {0, 0, 5}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  float fovy_deg = 60, near_plane = 0.1f, far_plane = 1000;
  int width = 320, height = 240;
};

// A camera as matrices (an engine has these): column-major doubles like
// OpenGL and glTF, world -> eye (looks down -z) and eye -> clip (depth -1..1).
struct CameraMatrices {
  double view[16];
  double projection[16];
};
// gluLookAt + gluPerspective. fovy in degrees (0 < fovy < 180), aspect = width
// / height > 0, 0 < near < far; far may be +infinity (an infinite far plane).
// Degenerate input leaves NaN in the projection (compute_focus reports it).
CameraMatrices camera_look_at(const double eye[3], const double target[3], const double up[3], double fovy_degrees,
                              double aspect, double near_dist, double far_dist);
// From an engine's own matrices (column-major floats, as glUniformMatrix4fv takes them).
CameraMatrices camera_from_matrices(const float view[16], const float projection[16]);

struct Scene {
  std::vector<float> positions;         // xyz per vertex, world space
  std::vector<uint32_t> indices;        // 3 per triangle, into positions
  std::vector<TriangleSource> sources;  // one per triangle
  std::vector<std::string> files;       // source file names (TriangleSource::file)
  std::vector<Light> lights;
  std::vector<std::string> warnings;  // non-fatal problems, each naming the file

  // Per-format counts a report may show (e.g. BSP "polygon", "mesh", "patch",
  // "billboard" faces and the triangles each produced). Key, value pairs.
  std::vector<std::pair<std::string, uint64_t>> source_counts;

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace geom
