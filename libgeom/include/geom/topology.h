// geom/topology.h: the edge table and classification of a welded triangle mesh.
//
// Built from welded indices (geom/weld.h). Nothing is lost on non-manifold
// input: every non-collapsed triangle contributes its three edges, however many
// faces an edge has (OpenMesh's add_face refuses such "complex edges"; this
// table does not, and geom/halfedge.h counts the faces OpenMesh would refuse).
//
// Definitions (all over the non-collapsed triangles):
//   collapsed triangle  two of its welded indices are equal; it has no edges
//   zero-area triangle  three distinct vertices, collinear (|cross| <= eps * |e|^2)
//   duplicate triangle  same vertex set as an earlier triangle (either winding)
//   boundary edge       used by exactly 1 triangle
//   manifold edge       2 triangles traversing it in opposite directions
//   inconsistent edge   2 triangles traversing it in the same direction
//   non-manifold edge   3 or more triangles (face_count says how many)
//   dihedral angle      for a manifold edge between two non-degenerate faces,
//                       the interior angle between them: 180 = flat, 90 = cube edge
//   coplanar            normals within `coplanar_degrees` of each other
//   convex / concave    the other face's far vertex is behind / in front of the plane
//   component           triangles connected through shared welded vertices
//   closed component    none of its edges is boundary or non-manifold
#pragma once
#include <cstdint>
#include <vector>

#include "geom/span.h"

namespace geom {

enum class EdgeKind : uint8_t { Boundary, Manifold, Inconsistent, NonManifold };
enum class EdgeShape : uint8_t { None, Coplanar, Convex, Concave };  // None: not manifold, or a degenerate face

enum FaceFlag : uint8_t {
  kFaceCollapsed = 1,
  kFaceZeroArea = 2,
  kFaceDuplicate = 4,
};

struct Edge {
  uint32_t v0, v1;      // welded vertices, v0 < v1
  uint32_t first;       // first entry in Topology::edge_faces
  uint32_t face_count;  // number of entries
  EdgeKind kind;
  EdgeShape shape;
  float dihedral_degrees;  // manifold edges between non-degenerate faces; else 0 (and when not asked for)
};

struct TopologyStats {
  uint64_t triangles = 0;  // all input triangles
  uint64_t vertices = 0;   // welded vertices used by a non-collapsed triangle
  uint64_t edges = 0;
  uint64_t boundary_edges = 0, manifold_edges = 0, inconsistent_edges = 0, non_manifold_edges = 0;
  uint64_t coplanar_edges = 0, convex_edges = 0, concave_edges = 0;
  uint64_t collapsed_triangles = 0, zero_area_triangles = 0, duplicate_triangles = 0;
  uint64_t components = 0, closed_components = 0;
  uint32_t max_edge_faces = 0;       // the most triangles sharing one edge
  int64_t euler_characteristic = 0;  // vertices - edges + non-collapsed triangles
  bool closed = true;                // no boundary and no non-manifold edge
};

struct Topology {
  static constexpr uint32_t kNone = 0xffffffffu;
  std::vector<Edge> edges;  // sorted by (v0, v1)
  // Per edge, its faces: (triangle << 1) | reversed, where reversed = 1 when the
  // triangle traverses the edge v1 -> v0. In triangle order.
  std::vector<uint32_t> edge_faces;
  std::vector<uint32_t> face_edges;  // 3 per triangle: edges (i0,i1), (i1,i2), (i2,i0); kNone if collapsed
  // 3 per triangle, beside face_edges: where an edge has exactly two faces
  // (manifold or inconsistent), the other face's slot of it, 3 * face + k;
  // else kNone. The walks round a vertex and across an edge read it.
  std::vector<uint32_t> face_twins;
  std::vector<uint8_t> face_flags;       // FaceFlag bits per triangle
  std::vector<uint32_t> face_component;  // component id per triangle; kNone if collapsed
  TopologyStats stats;
};

struct TopologyOptions {
  double coplanar_degrees = 0.01;  // normals closer than this: the edge is coplanar
  // Fill Edge::dihedral_degrees (an acos per manifold edge). Off, every edge's
  // is 0 and nothing else changes: the bake and the report turn it off, as no
  // stage of theirs reads an angle.
  bool dihedral_angles = true;
};

// `positions`: the welded vertices; `indices`: 3 per triangle, welded.
Topology build_topology(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                        const TopologyOptions& options = {});

}  // namespace geom
