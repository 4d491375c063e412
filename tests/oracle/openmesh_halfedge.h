// openmesh_halfedge.h: the tests' oracle for geom/halfedge.h, OpenMesh itself.
//
// OpenMesh's TriMesh is the right tool for walking a 2-manifold: boundary
// loops (holes) and the genus of closed components. It refuses faces that
// would make an edge complex (3 or more faces) or a vertex non-manifold.
// The library computes the same summary from its edge table (geom/halfedge.h,
// no OpenMesh); the tests compare the two on every mesh they use.
#pragma once
#include <cstdint>

#include "geom/halfedge.h"
#include "geom/span.h"

namespace geom {

// `positions`: welded vertices; `indices`: 3 per triangle, welded. Faces are
// offered to OpenMesh's add_face in order, so which faces are refused is deterministic.
HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count);

}  // namespace geom
