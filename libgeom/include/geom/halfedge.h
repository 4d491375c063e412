// geom/halfedge.h: what a half-edge structure (OpenMesh) makes of the mesh.
//
// OpenMesh's TriMesh is the right tool for walking a 2-manifold: boundary
// loops (holes) and the genus of closed components. It refuses faces that
// would make an edge complex (3 or more faces) or a vertex non-manifold; the
// edge table of geom/topology.h keeps those, and this summary counts them, so
// every face is accounted for: added + refused + skipped == triangles.
#pragma once
#include <cstdint>

#include "geom/span.h"
#include "geom/topology.h"

namespace geom {

struct HalfedgeSummary {
  uint64_t added_faces = 0;     // accepted by OpenMesh's add_face
  uint64_t refused_faces = 0;   // refused (complex edge or vertex, inconsistent orientation)
  uint64_t skipped_faces = 0;   // collapsed (two equal welded indices): never offered
  uint64_t boundary_loops = 0;  // holes of the accepted surface
};

// `positions`: welded vertices; `indices`: 3 per triangle, welded. Faces are
// offered in order, so which faces are refused is deterministic.
HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count);

// The same summary read from the mesh's edge table (geom/topology.h, built from
// the same welded indices) where it tells the answer: when no edge is
// non-manifold or inconsistent and every vertex's faces form one fan,
// OpenMesh takes every face (refused = 0) and the holes are the cycles of
// boundary edges, found here in linear time. Otherwise OpenMesh's add_face is
// replayed on the edge table, face by face in order (its answer depends on
// the order faces are offered), with what OpenMesh finds by walking round a
// vertex read from the two ends of each fan: the function above's answer, in
// linear time whatever the valences (tests/test_halfedge.cpp holds the two
// equal on every mesh the tests use, random soups and many-fan "stars").
HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                    const Topology& topology);

// Whether the edge table alone gives the summary (the first path above).
bool halfedges_from_edge_table(const uint32_t* indices, size_t triangle_count, size_t vertex_count,
                               const Topology& topology);

}  // namespace geom
