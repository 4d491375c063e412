// geom/esm_quads.h: the degenerate silhouette quads of extended shadow maps.
//
// Bujnak 2004, Sect. 3.1 and 4.1, Fig. 3-5. Each
// candidate edge becomes a degenerate quad whose four corners are the two edge
// endpoints taken twice: once on side A, once on side B. A corner carries its
// position, the plane of its side's face and the quad's extrusion vector q. Per
// light, the vertex shader (shaders/esm_quad.vert) moves a corner by +q * len
// when the light is in front of its side's plane and by -q * len / 2 when it is
// behind, so both sides land on the same line (the quad stays degenerate and
// draws nothing) unless the light is in front of one plane and behind the
// other: exactly when the edge is a silhouette. `len` = extrude_scale * the
// corner's clip w, so the quad covers a constant width in shadow-map texels.
//
// Extrusion vector: q = normalize(nA + nB), the bisector of the two face
// normals. Where the dihedral angle between the faces is under 90 degrees
// (nA . nB < 0), one q would be nearly parallel to some silhouette-making light
// directions, so the edge gets two quads against the bevel plane
// B = normalize(planeA + planeB) (figure 5): (A, bevel) with q1 = normalize(nA +
// nB') and (bevel, B) with q2 = normalize(nB' + nB), nB' the bevel normal. For
// any light in front of A and behind B, exactly one of the two opens. Width:
// a quad opens for lights in the two opposite wedges where its planes disagree,
// and its projected width is then at least cos(phi / 2) of the nominal 1.5 len,
// phi <= 90 degrees the angle between its two normals: >= 70.7% (section 4.1).
//
// Candidate edges ("only edges that can bound a shadow"):
//   manifold, consistent, convex       one quad, or two with the bevel
//   manifold, consistent, concave      none: for a consistently oriented surface
//                                      the quad would lie behind the front face,
//                                      inside the occluder (section 3.1); kept
//                                      with EsmOptions::keep_concave
//   both faces share a stored plane    none (geom/face_planes.h)
//   boundary edge (open surface)       a knife edge between the face's plane and
//                                      the same plane flipped (bit 31): split
//                                      against the bevel plane through the edge
//                                      whose normal u lies in the face's plane,
//                                      pointing away from it, so two quads:
//                                      (face, bevel) with q = normalize(n + u)
//                                      and (bevel, flipped face) with q =
//                                      normalize(u - n). Exactly one opens for
//                                      any light off the planes: a sheet's
//                                      border always bounds its shadow
//   inconsistent (same direction)      one quad, side B's plane flipped (the
//                                      neighbour's winding corrected), treated
//                                      as convex/concave like a manifold edge
//   non-manifold (3+ faces)            the two boundary-style quads per face
//   degenerate faces                   ignored (no plane)
//
// GPU layout. Draw: glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, quad_count),
// one instance per EsmQuad (vertex attribute divisor 1, stride 36 bytes, the
// records tightly packed as `quads` lies in memory), no index buffer. The
// corner is gl_VertexID: 0 = p0 on side A, 1 = p1 on side A, 2 = p0 on side
// B, 3 = p1 on side B. Attributes:
//   location 0  vec3  p0            float x3, offset 0
//   location 1  vec3  p1            float x3, offset 12
//   location 2  uint  plane_a       uint32,   offset 24 (glVertexAttribIPointer)
//   location 3  uint  plane_b       uint32,   offset 28 (glVertexAttribIPointer)
//   location 4  vec2  q             int16 x2, offset 32, normalized (snorm16),
//                                   octahedral encoding of the unit vector q
// Plane index: bits 0-30 index `planes` (a vec4 per plane, bound as an
// RGBA32F texture buffer, uniform samplerBuffer u_planes); bit 31 flips the
// test for that side ("in front" becomes "not in front"). Positions and planes
// are in the local frame of geom/face_planes.h. Memory: 36 bytes per quad plus
// 16 per referenced plane (the naive layout, 4 corners x (position, plane,
// extrusion vector) in float, takes 160 bytes per quad).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "geom/baked_records.h"
#include "geom/face_planes.h"
#include "geom/span.h"
#include "geom/topology.h"

namespace geom {

// EsmQuad, the 36-byte record: geom/baked_records.h (standard library only, for engines).

struct EsmStats {
  uint64_t edges = 0;             // all edges of the topology
  uint64_t candidate_edges = 0;   // edges with at least one non-degenerate face
  uint64_t emitted_edges = 0;     // edges that got at least one quad
  uint64_t skipped_coplanar = 0;  // shared stored plane: can never open
  uint64_t skipped_concave = 0;   // inside the occluder
  uint64_t quads = 0;             // records (2 for a bevel edge, 2 per face of a boundary / non-manifold edge)
  uint64_t bevel_edges = 0;       // edge-face pairs split against a bevel plane
  uint64_t bytes = 0;             // quads * 36 + planes * 16
  uint64_t naive_bytes = 0;       // 160 bytes per quad of every candidate edge, nothing skipped
};

struct EsmQuads {
  double origin[3] = {0, 0, 0};  // local frame (geom/face_planes.h)
  std::vector<float> planes;     // vec4 per plane: referenced face planes and bevel planes, by first use
  std::vector<EsmQuad> quads;
  EsmStats stats;
};

struct EsmOptions {
  bool keep_concave = false;        // also emit concave manifold edges
  double bevel_below_degrees = 90;  // dihedral angle under which an edge gets two quads
  // Set, the quads go to it in pieces, in order, as they are made, and are not
  // kept: the result's quads stay empty, its stats count every quad (planes are
  // kept as ever). What it throws ends the build.
  std::function<void(const EsmQuad* quads, size_t count)> quads_out;
};

// Preconditions (asserted with this function's name where NDEBUG is not
// defined): every index < positions.size(); `topology` and `planes` made from
// these triangles (planes.face_plane.size() == triangle_count).
EsmQuads build_esm_quads(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                         const Topology& topology, const FacePlanes& planes, const EsmOptions& options = {});

// The most quads build_esm_quads makes for `triangle_count` triangles: at
// most two per face of each of its three edges (a bevel edge, a boundary or
// non-manifold face's knife pair), so 6 per triangle.
inline size_t esm_quads_bound(size_t triangle_count) { return 6 * triangle_count; }

// The same quads written to caller-owned memory, `out`, which holds
// esm_quads_bound(triangle_count) records; the result carries the origin, the
// plane table and the stats, its `quads` empty: stats.quads is the count
// written, byte for byte the vector's. options.quads_out must not be set.
EsmQuads build_esm_quads(EsmQuad* out, PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                         const Topology& topology, const FacePlanes& planes, const EsmOptions& options = {});

// Octahedral encoding of a unit vector into two snorm16 values, and back (the
// shader's decode, in float). Round-trip angular error under 0.01 degrees.
void octahedral_encode(const double v[3], int16_t out[2]);
void octahedral_decode(const int16_t in[2], float v[3]);

}  // namespace geom
