// geom/adjacency.h: index buffers for GL_TRIANGLES_ADJACENCY.
//
// For the geometry-shader silhouette test of edge distance shadow maps
// (Kenzel 2013, Sect. 3.2.1): an edge is a silhouette when the
// triangle and its neighbour across that edge project with opposite windings.
//
// Layout: 6 uint32 indices per input triangle (i0 i1 i2), in triangle order:
//   i0, n01, i1, n12, i2, n20
// where nXY is the vertex opposite edge XY in the neighbouring triangle. Draw
// with glDrawElements(GL_TRIANGLES_ADJACENCY, 6 * triangle_count,
// GL_UNSIGNED_INT, 0) over the same (welded) vertex buffer. The geometry shader
// sees the triangle as vertices 0, 2, 4 and the neighbour of edge (0, 2) as
// (0, 1, 2), of (2, 4) as (2, 3, 4), of (4, 0) as (4, 5, 0).
//
// Choosing the neighbour of edge a -> b of triangle t (indices welded, so
// "the same edge" is the same vertex pair):
//   manifold        the other triangle, which traverses b -> a.
//   non-manifold    the first triangle in input order, other than t, traversing
//                   b -> a; if none, the first other triangle traversing a -> b.
//   inconsistent    the other triangle traverses a -> b too. Its opposite vertex
//                   is given all the same: the shader's neighbour (a, x, b) then
//                   has the winding the neighbour would have if consistently
//                   oriented, so the test stays meaningful.
//   boundary        no other triangle: the triangle's own opposite vertex (i2 for
//                   edge i0 -> i1). The neighbour (i0, i2, i1) is the triangle
//                   itself reversed, so its projected winding is always opposite:
//                   a boundary edge is a silhouette for every viewpoint, which is
//                   right for an open surface, seen and casting from both sides.
//   collapsed t     (two equal indices) has no edges: its own opposite vertices,
//                   and it is nobody's neighbour.
// Positions are not read: the result depends only on the indices.
#pragma once
#include <cstddef>
#include <cstdint>

#include "geom/topology.h"

namespace geom {

// The size of the buffer, known in advance: 6 indices per triangle.
inline size_t adjacency_bound(size_t triangle_count) { return 6 * triangle_count; }
inline size_t adjacency_index_count(size_t triangle_count) { return adjacency_bound(triangle_count); }

// Writes adjacency_bound(triangle_count) indices to caller-owned `out`.
// Precondition (asserted with this function's name where NDEBUG is not
// defined): `indices` hold 3 per triangle, each < vertex_count. Memory: about 12 bytes per triangle
// of scratch; O(n log n) time whatever the valences. Returns false only if a
// temporary allocation fails.
bool build_adjacency(uint32_t* out, const uint32_t* indices, size_t triangle_count, size_t vertex_count);

// The same buffer from the mesh's edge table (geom/topology.h, built from these
// indices, its per-face tables kept: face_edges.size() == 3 * triangle_count,
// asserted like the above): no scratch memory, linear in the triangles
// whatever the valences. Always true.
bool build_adjacency(uint32_t* out, const uint32_t* indices, size_t triangle_count, const Topology& topology);

}  // namespace geom
