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

}  // namespace geom
