// geom/extrude.h: the CPU reference of the GPU extrusion.
//
// The same math, in the same float operations, as shaders/shadow_volume.vert
// and shaders/esm_quad.vert, one instance at a time (see the layouts in
// geom/shadow_volume.h and geom/esm_quads.h). Tests check the laws on it;
// `geombake volume` writes its result as a mesh users can open.
//
// Lights here are the shaders' input form (u_light): float (x, y, z, w) in
// the local frame of the buffers (geom/face_planes.h); w = 1 a point light at
// (x, y, z), w = 0 a directional light lying at infinity in direction
// (x, y, z) (towards the light; its rays travel along -(x, y, z)). A
// geom::Light (geom/scene.h) comes to it in two steps, each the project's one
// conversion: light_homogeneous gives the homogeneous form in input
// coordinates (doubles), to_local_light below moves that into the local frame.
// A corner extruded to infinity is (v * L.w - L.xyz, 0): away from the light;
// (0, 0, -1, 0) when that is zero (a point light exactly on the vertex, see
// "Limits" in geom/shadow_volume.h).
#pragma once
#include <cstdint>
#include <vector>

#include "geom/esm_quads.h"
#include "geom/shadow_volume.h"

namespace geom {

// Homogeneous light in input coordinates (light_homogeneous) -> the shaders'
// form in the local frame `origin`: (xyz - origin * w, w), in double, then float.
void to_local_light(const double origin[3], const double light[4], float out[4]);

// One shadow-volume side instance: writes the 4 strip corners (x, y, z, w) and
// returns true when the quad is open for `light`; false: it collapses.
bool side_corners(const SvSide& side, const float* planes, const float light[4], float out[4][4]);
// One cap instance: writes the 6 corners (near cap 0-2, far cap 3-5); false: it collapses.
bool cap_corners(const SvCap& cap, const float* planes, const float light[4], float out[6][4]);

// Everything one light rasterizes from a volume, as homogeneous triangles
// (12 floats each: 3 corners x, y, z, w), oriented outward, in the local frame.
// A side strip gives two triangles (0, 1, 2) and (2, 1, 3); collapsed instances
// give none. `caps` = false: what depth-pass draws (sides only).
std::vector<float> extrude_volume(const ShadowVolume& volume, const float light[4], bool caps = true);

// One ESM quad instance: corner k (gl_VertexID) moved along q by +len if its
// side's plane has the light in front, by -len/2 otherwise, where len =
// extrude_scale * w of the corner in clip space (`light_view_proj`: 16 floats,
// column-major, local frame -> light clip space). Writes 4 corners (x, y, z, 1)
// in the local frame; returns true when the quad is open (the two sides moved
// differently).
bool esm_corners(const EsmQuad& quad, const float* planes, const float light[4], const float light_view_proj[16],
                 float extrude_scale, float out[4][4]);

// The finite shadow volume of `geombake volume`: extrude_volume with each
// corner at infinity replaced by a finite point on the same ray, so that every
// far cap and far edge lies `distance` or more outside the axis-aligned box
// `lo`..`hi` (input coordinates: the scene's bounds). Directional light: every
// corner moves the same length (box diagonal + distance) away from the light,
// a far cap is its face translated. Point light: every far corner lies on one
// sphere around the light, of radius (farthest box corner + distance) / c,
// where c > 0 is the least distance from the centre to a far cap's triangle of
// unit directions (small when a face spans nearly 180 degrees seen from the
// light; clamped at 1e-3). Inside the box the count equals the infinite
// volume's. Faces oriented outward, a face repeated where its multiplicity is
// 2 or more; output in input coordinates, corners welded by exact position.
struct VolumeMesh {
  std::vector<double> positions;  // xyz per vertex
  std::vector<uint32_t> indices;  // 3 per triangle
};
VolumeMesh finite_volume(const ShadowVolume& volume, const float light[4], const double lo[3], const double hi[3],
                         double distance);

}  // namespace geom
