// geom/shadow_volume.h: static, light-independent stencil shadow volumes that
// stay correct for closed, open and non-manifold meshes.
//
// Arneson, Real-Time Shadows, Sect. 4 (extrusion to infinity with w = 0,
// depth-pass / depth-fail, game levels that are not 2-manifolds), the z-fail
// baseline of Kenzel 2013, Sect. 5. The vertex shader
// (shaders/shadow_volume.vert) decides everything per light; the CPU reference
// in geom/extrude.h does the same math.
//
// Why the counts are right. For a light L and a triangle f, let F(f) be f's
// shadow frustum: the points P whose segment to L crosses f. Its boundary is a
// closed surface: f itself (near cap), one side quad per edge of f extruded
// away from L to infinity, and f projected to infinity (far cap). Oriented
// outward, its winding number (signed crossing count of any ray from P to
// infinity) is 1 inside F(f) and 0 outside. Every face contributes with a
// weight, and the volume is the sum of these oriented closed surfaces:
//   count(P) = sum over faces f of w(f) [P in F(f)],  w(f) in {0, 1}.
// Since all weights are >= 0, count(P) > 0 only if some face blocks P from L.
//   * Double-sided faces (the default, every face): w(f) = 1 for any light
//     off the face's plane (on it, below).
//     F(f) is oriented by f's facing: f as is when L is in front of its plane,
//     f flipped when behind. count(P) = the number of faces crossed by the
//     segment PL: non-zero exactly when blocked, for any mesh and any light.
//   * One-sided faces (ShadowVolumeOptions::one_sided_closed, only for faces of
//     a closed component: every edge has exactly two non-degenerate faces
//     traversing it in opposite directions): w(f) = 1 when L is in front, 0
//     when behind or on its plane. A segment from a light OUTSIDE the solid first enters it
//     through a face whose front sees L, so count(P) > 0 exactly when the
//     component blocks P: the classic volume, half the fill and memory. The
//     caller promises the light never enters such a solid; a light inside one
//     sees everything outside it lit (the classic failure), which is why this
//     is not the default.
// Lights on a face's plane. A face whose plane contains the light has a flat
// frustum (no volume): w(f) = 0 whatever its sidedness. Every test therefore
// has three states, s(f) = +1 front, 0 on, -1 behind (light_side below):
//   on  <=>  |p . L| <= kOnLight * (|p.x L.x| + |p.y L.y| + |p.z L.z| + |p.w L.w|)
// (float, left to right, the same expression in the shader). The bound is
// relative to the terms, i.e. to the local frame's scale at the light, about
// 10 times the float rounding of a plane through a vertex; a light within it
// of a plane is "on" it. Double-sided faces weigh s(f) (the frustum as is,
// flipped, or nothing); one-sided faces weigh [s(f) = +1] (on counts as behind).
// The side quads of neighbouring frusta along a shared edge coincide; they are
// merged per edge. An edge's net multiplicity, in quads oriented as for a face
// in front traversing p0 -> p1, is the sum over its faces of s(f) w(f) (times
// -1 for a face traversing p1 -> p0); a merged record produces exactly that:
//   pair record    two faces A (traversing p0 -> p1) and B (p1 -> p0) of a
//                  manifold, consistent edge. One-sided: net [s(A) = 1] -
//                  [s(B) = 1], in -1..1, stored once. Double-sided: net
//                  s(A) - s(B), in -2..2, stored as two adjacent records: the
//                  first emits [s(A) = 1] - [s(B) = 1] (the one-sided rule),
//                  the second (kSecond set in plane_a) emits [s(B) = -1] -
//                  [s(A) = -1]; their sum is s(A) - s(B). Without a face on
//                  the light both copies are the classic silhouette quad.
//                  Never emitted when A and B share a stored plane (both
//                  classified alike, the sum is always 0).
//   single record  one face traversing p0 -> p1, side B = the same plane
//                  flipped (kFlip negates s): net s(A), -1..1, oriented by the
//                  face's facing, collapsed when the face is on the light.
//                  Used for boundary edges, inconsistent edges and every face
//                  of a non-manifold edge (never in a closed component).
// Caps: a face in front draws its near and far caps, a double-sided face
// behind draws them flipped, a face on the light draws none.
// Because every decision about a face comes from one stored plane and one
// expression, the sides and the caps of one light always agree: the volume is a
// closed oriented surface whatever the rounding, and a face classified wrongly
// (the light within the bound of its plane but not on it, or the reverse) only
// changes the count inside its own frustum, a sliver around that plane.
// Degenerate faces have no plane and no frustum volume: they contribute
// nothing (geom/face_planes.h).
//
// Light at a vertex. Every face through a vertex at the light contains the
// light, so all of that vertex's records and caps collapse and no drawn corner
// lies on the light: the volume is exact. The shaders still send a corner
// without direction to (0, 0, -1, 0) (kAtLight) as a guard.
//
// Limits. A face of a coplanar group (geom/face_planes.h) may lie up to
// coplanar_distance off its stored plane: a light at its vertex, farther than
// the bound from that plane, classifies the face front or behind and the
// corner at the light takes kAtLight: the volume stays closed and finite, but
// the count in a sliver around the light may be wrong. One-sided closed
// components need the light strictly outside: a light on the solid's surface
// sees its faces through the light weigh 0 and the solid behind them lit.
// (build_light_volume keeps such a component double-sided.) Counts are exact off
// the planes through the light (tests/test_shadow_volume.cpp: lights at
// vertices, inside faces, and 1e-5 of the scene's size off the surface).
//
// Drawing. Depth-fail (z-fail, camera anywhere): sides and caps, back faces
// increment on depth fail, front faces decrement. Depth-pass (camera outside
// every volume): sides only, front faces increment on depth pass, back faces
// decrement. A pixel is lit when its stencil count is 0. Use a projection with
// an infinite far plane (or GL_DEPTH_CLAMP): extruded corners have w = 0.
//
// GPU layout. Positions and planes are in the local frame (geom/face_planes.h).
// `planes`: vec4 per plane, bound as an RGBA32F texture buffer (uniform
// samplerBuffer u_planes). Plane index: bits 0-30 index `planes`, bit 31 is a
// flag (below). No index buffers; one instance per record, attribute divisor 1.
// s(plane) = light_side below: +1 front, 0 on, -1 behind.
//
// Sides: glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, side_count), stride 32.
//   location 0  vec3  p0       float x3, offset 0
//   location 1  vec3  p1       float x3, offset 12
//   location 3  uint  plane_a  uint32, offset 24: face A, traversing p0 -> p1;
//                              bit 31 (kSecond): second copy of a double-sided pair
//   location 4  uint  plane_b  uint32, offset 28: face B; bit 31 (kFlip) negates its s
//   Per light: sa = s(A), sb = flip ? -s(B) : s(B); first copy and single:
//   fa = sa > 0, fb = sb > 0; second copy: fa = sa >= 0, fb = sb >= 0.
//   fa == fb: the instance collapses to one point (no fragment). Otherwise
//   (a, b) = fa ? (p1, p0) : (p0, p1) and the corners gl_VertexID 0..3 are a,
//   b, a at infinity, b at infinity, where v at infinity = (v * L.w - L.xyz, 0).
// Caps: glDrawArraysInstanced(GL_TRIANGLES, 0, 6, cap_count), stride 40.
//   location 0  vec3  a        float x3, offset 0
//   location 1  vec3  b        float x3, offset 12
//   location 2  vec3  c        float x3, offset 24
//   location 3  uint  plane    uint32, offset 36; bit 31 = double-sided face
//   Vertices 0-2: the near cap (a, b, c) if front, (a, c, b) if behind and
//   double-sided; 3-5: the far cap at infinity (a, c, b) if front, (a, b, c) if
//   behind and double-sided. A face on the light, or one-sided and behind it,
//   collapses.
//   Sides and caps use one shader (uniform bool u_caps selects the record kind).
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "geom/baked_records.h"
#include "geom/face_planes.h"
#include "geom/span.h"
#include "geom/topology.h"

namespace geom {

// The relative bound of "light on the plane" (see above); the shader's kOnLight.
constexpr float kOnLight = 2e-6f;

// +1 light in front of `plane` (x, y, z, w: w = 1 point, w = 0 direction),
// 0 on it, -1 behind: exactly the float expression of shaders/shadow_volume.vert.
inline int light_side(const float plane[4], const float light[4]) {
  float s = plane[0] * light[0];
  s = s + plane[1] * light[1];
  s = s + plane[2] * light[2];
  s = s + plane[3] * light[3];
  float m = std::fabs(plane[0] * light[0]);
  m = m + std::fabs(plane[1] * light[1]);
  m = m + std::fabs(plane[2] * light[2]);
  m = m + std::fabs(plane[3] * light[3]);
  m = m * kOnLight;
  return s > m ? 1 : (s < -m ? -1 : 0);
}

// SvSide (32 bytes) and SvCap (40 bytes), the records: geom/baked_records.h (standard library only).

struct ShadowVolumeStats {
  uint64_t edges = 0;                     // all edges of the topology
  uint64_t pair_edges = 0;                // manifold consistent edges given a pair record
  uint64_t single_records = 0;            // boundary, inconsistent and non-manifold face records
  uint64_t skipped_coplanar = 0;          // pair edges not emitted: shared stored plane
  uint64_t skipped_coplanar_records = 0;  // the records they would have taken (2 each double-sided)
  uint64_t one_sided_faces = 0;           // faces of closed components, with one_sided_closed
  uint64_t double_sided_faces = 0;        // all other non-degenerate faces
  uint64_t degenerate_faces = 0;          // no plane, no cap
  uint64_t sides = 0, caps = 0;           // records
  uint64_t bytes = 0;                     // sides * 32 + caps * 40 + planes * 16
  uint64_t naive_sides = 0;               // one record per edge and face: every face's own frustum
  uint64_t naive_bytes = 0;               // naive_sides * 32 + caps * 40 + planes * 16
  uint64_t components = 0, closed_components = 0;
  uint64_t light_one_sided = 0;  // per-light volume: closed components treated one-sided
};

struct ShadowVolume {
  double origin[3] = {0, 0, 0};  // local frame (geom/face_planes.h)
  std::vector<float> planes;     // vec4 per plane
  std::vector<SvSide> sides;
  std::vector<SvCap> caps;
  ShadowVolumeStats stats;
  // CPU-side, not uploaded: per record, its component (faces connected through
  // shared edges); per component, whether it is closed. build_light_volume uses
  // them (only it reads them); empty with ShadowVolumeOptions::component_ids off.
  std::vector<uint32_t> side_component, cap_component;
  std::vector<uint8_t> component_closed;
  // Set by build_light_volume: the light (local frame) this volume is exact for.
  bool per_light = false;
  float light[4] = {0, 0, 0, 0};
};

struct ShadowVolumeOptions {
  bool one_sided_closed = false;  // classic one-sided closed components (lights outside them only)
  // Fill side_component, cap_component, component_closed and stats.components /
  // closed_components. Off (and one_sided_closed off), the components are never
  // computed: same records and caps, less time and memory; build_light_volume
  // then keeps every component double-sided (correct, larger). A bake without
  // lights has no use for them.
  bool component_ids = true;
  // Set, the side records (then the caps) go to it in pieces, in order, as
  // they are made, and are not kept: the result's sides and side_component
  // (caps and cap_component) stay empty, its stats count every record. What
  // it throws ends the build. (A stream of the volume cannot feed
  // build_light_volume.)
  std::function<void(const SvSide* records, size_t count)> sides_out;
  std::function<void(const SvCap* records, size_t count)> caps_out;
};

// The generic, light-independent volume of a welded mesh. Preconditions
// (asserted with this function's name where NDEBUG is not defined): every
// index < positions.size(); `topology` and `planes` made from these triangles
// (planes.face_plane.size() == triangle_count).
ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, const FacePlanes& planes,
                                 const ShadowVolumeOptions& options = {});
// The same, taking planes.planes into ShadowVolume::planes instead of copying
// it (planes.planes is left empty; the rest of `planes` is only read).
ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, FacePlanes&& planes,
                                 const ShadowVolumeOptions& options = {});

// The exact volume of one static light (local frame, w = 1 point, w = 0 direction
// towards the light): only the side records that open for it, and only the
// caps that draw. Closed components get the one-sided treatment, now safe
// because the CPU knows where the light is: the light outside the solid
// (parity of a ray cast from it in double, the solid's side from its signed
// volume) counts front faces (first copies of pairs), inside it counts back
// faces (second copies); each pair record then appears once instead of twice,
// and a cap only where it counts. A
// component whose faces come within 1e-6 of its diagonal of the light, or
// whose ray casts keep grazing an edge, stays double-sided. Same layout and
// shader; the plane table is {L / |L|^2, -L / |L|^2} (index 0 always in
// front, 1 always behind for that light), so the GPU reproduces the CPU's
// decisions exactly. Returns an empty volume with per_light = false when the
// light is all zeros.
ShadowVolume build_light_volume(const ShadowVolume& generic, const float light[4]);

// The most side records build_shadow_volume makes for `triangle_count`
// triangles: one per face of each edge (a pair record's two copies stand for
// two faces), so 3 per triangle; and caps: one per triangle.
inline size_t shadow_volume_sides_bound(size_t triangle_count) { return 3 * triangle_count; }
inline size_t shadow_volume_caps_bound(size_t triangle_count) { return triangle_count; }

// The generic volume written to caller-owned memory: `sides` holds
// shadow_volume_sides_bound(triangle_count) records, `caps`
// shadow_volume_caps_bound(triangle_count); the result carries the origin,
// the plane table and the stats (stats.sides and stats.caps: the counts
// written, byte for byte the vector's), its sides, caps and their component
// ids empty (so it cannot feed build_light_volume). options.sides_out and
// caps_out must not be set.
ShadowVolume build_shadow_volume(SvSide* sides, SvCap* caps, PositionSpan positions, const uint32_t* indices,
                                 size_t triangle_count, const Topology& topology, const FacePlanes& planes,
                                 const ShadowVolumeOptions& options = {});

}  // namespace geom
