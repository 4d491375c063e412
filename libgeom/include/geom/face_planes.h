// geom/face_planes.h: one stored plane per face, shared by coplanar neighbours.
//
// Every silhouette buffer (geom/esm_quads.h, geom/shadow_volume.h) decides per
// light, in the vertex shader, whether the light is in front of a face by
// evaluating that face's stored plane. Two faces that share a stored plane are
// classified identically for every light, bit for bit, so the edge between them
// can never open a quad: it is not emitted at all ("only what a scene
// needs") and no crack can appear where it was.
//
// Local frame. Buffers store float positions and planes relative to `origin`
// (the centre of the bounding box of the referenced vertices, in double). A
// mesh 1e5 units from the world origin keeps full float precision; the caller
// passes lights in that same frame (geom/extrude.h: to_local_light).
//
// Plane: (nx, ny, nz, d), n the unit normal of the face's front (the side from
// which the triangle i0 i1 i2 is counter-clockwise), n . p + d = 0 for p in the
// local frame. Computed in double from the welded positions, stored as float.
// (The baked file's FacePlanes section holds them moved to input coordinates,
// d - n . origin, one per triangle; the ESM and volume plane tables stay local:
// geom/baked_reader.h's table gives each section's frame.)
//
// Coplanar groups (region growing, deterministic, in triangle order): a face
// not yet grouped starts a group whose plane is its own; the group grows over
// manifold, consistently wound edges to neighbours whose normal is within
// `coplanar_degrees` of the group's normal and whose three vertices are within
// `coplanar_distance` (times the bounding-box diagonal) of the group's plane.
// Comparing against the seed, never the last member, keeps a gently curved
// surface from drifting into one plane.
//
// Degenerate faces (topology's collapsed or zero-area triangles, or a normal
// that is zero in double) have no plane (kNone): they cast no shadow (their
// shadow frustum has no volume), emit no cap and contribute to no edge.
#pragma once
#include <cstdint>
#include <vector>

#include "geom/span.h"
#include "geom/topology.h"

namespace geom {

struct FacePlaneOptions {
  double coplanar_degrees = 0.01;   // normals closer than this may share a plane
  double coplanar_distance = 1e-6;  // vertices this close to the plane (relative to the bounds diagonal)
};

struct FacePlanes {
  static constexpr uint32_t kNone = 0xffffffffu;
  double origin[3] = {0, 0, 0};      // the local frame's origin in input coordinates
  double diagonal = 0;               // bounding-box diagonal of the referenced vertices
  std::vector<float> planes;         // 4 floats per stored plane (see above)
  std::vector<uint32_t> face_plane;  // per triangle: index of its plane, kNone if degenerate
  std::vector<double> normals;       // per triangle: unit normal in double (0,0,0 if degenerate)
  uint64_t degenerate_faces = 0;     // faces without a plane
  uint64_t shared_faces = 0;         // faces that reuse the plane of an earlier face of their group
  size_t plane_count() const { return planes.size() / 4; }
};

// `positions`, `indices` (3 per triangle) and `topology` describe the same welded mesh.
FacePlanes compute_face_planes(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                               const Topology& topology, const FacePlaneOptions& options = {});

// The test every shader and the CPU reference apply: is `light` (x, y, z, w; w = 1
// a point, w = 0 a direction towards the light) strictly in front of `plane`?
// Written exactly as in shaders/*.vert: p.x*l.x + p.y*l.y + p.z*l.z + p.w*l.w > 0,
// evaluated left to right in float.
inline bool light_in_front(const float plane[4], const float light[4]) {
  float s = plane[0] * light[0];
  s = s + plane[1] * light[1];
  s = s + plane[2] * light[2];
  s = s + plane[3] * light[3];
  return s > 0.0f;
}

}  // namespace geom
