// geom/halfedge.h: what a half-edge structure (OpenMesh's TriMesh) makes of
// the mesh, computed from the mesh's edge table without one.
//
// A half-edge structure refuses faces that would make an edge complex (3 or
// more faces) or a vertex non-manifold; the edge table of geom/topology.h keeps
// those, and this summary counts them, so every face is accounted for:
// added + refused + skipped == triangles. The counts are OpenMesh's (its
// add_face, faces offered in order); the library does not link OpenMesh.
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

// `positions`: welded vertices; `indices`: 3 per triangle, welded;
// `topology`: their edge table (geom/topology.h). Where the edge table tells
// the answer (no edge is non-manifold or inconsistent and every vertex's
// faces form one fan),
// OpenMesh takes every face (refused = 0) and the holes are the cycles of
// boundary edges, found here in linear time. Otherwise OpenMesh's add_face is
// replayed on the edge table, face by face in order (its answer depends on
// the order faces are offered), with what OpenMesh finds by walking round a
// vertex read from the two ends of each fan: OpenMesh's answer, in linear
// time whatever the valences.
HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                    const Topology& topology);

// Whether the edge table alone gives the summary (the first path above).
bool halfedges_from_edge_table(const uint32_t* indices, size_t triangle_count, size_t vertex_count,
                               const Topology& topology);

}  // namespace geom
