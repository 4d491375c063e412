// Half-edge summary (geom/halfedge.h): from the edge table where every vertex
// is a single fan, else through OpenMesh. OpenMesh types stay in this file.
//
// Why the table suffices there: OpenMesh's add_face refuses a face only at a
// complex edge (the edge already has a face on that side: an inconsistent or
// non-manifold edge in the finished mesh), at a complex vertex (the vertex's
// fan is already closed: it would end with two fans) or when it cannot
// re-link the fans around a vertex into a free gap (which needs another fan
// left at the vertex once the mesh is complete). With none of those, every
// face is added, and the boundary half-edge leaving a vertex is unique, so
// the holes are exactly the cycles of boundary edges.
#include "geom/halfedge.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Utils/Property.hh>
#include <mutex>
#include <vector>

#include "work_count.h"

namespace geom {

HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  HalfedgeSummary s;
  Mesh mesh;
  std::vector<Mesh::VertexHandle> vh(positions.size());
  for (size_t i = 0; i < vh.size(); ++i)
    vh[i] = mesh.add_vertex(Mesh::Point(positions[i].x, positions[i].y, positions[i].z));
  // add_face reports each refusal on OpenMesh's process-wide error stream; the
  // summary counts them instead. Silenced once (toggling it back on would race
  // between threads baking in parallel).
  std::vector<uint32_t> around(positions.size(), 0);  // faces added at each vertex (for the work count)
  uint64_t steps = 0;
  static std::once_flag silenced;
  std::call_once(silenced, [] { omerr().disable(); });
  for (size_t f = 0; f < triangle_count; ++f) {
    const uint32_t* v = indices + 3 * f;
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      ++s.skipped_faces;
      continue;
    }
    steps += 1 + around[v[0]] + around[v[1]] + around[v[2]];
    if (mesh.add_face(vh[v[0]], vh[v[1]], vh[v[2]]).is_valid()) {
      ++s.added_faces;
      ++around[v[0]], ++around[v[1]], ++around[v[2]];
    } else {
      ++s.refused_faces;
    }
  }
  OpenMesh::HPropHandleT<bool> visited;
  mesh.add_property(visited);
  for (auto h : mesh.halfedges()) mesh.property(visited, h) = false;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || mesh.property(visited, h)) continue;
    ++s.boundary_loops;
    auto g = h;
    do {
      mesh.property(visited, g) = true;
      g = mesh.next_halfedge_handle(g);
      ++steps;
    } while (g != h && !mesh.property(visited, g));
  }
  detail::count_work(steps);
  return s;
}

namespace {

// Which corner of face `f` holds vertex `v`.
inline int corner_of(const uint32_t* f, uint32_t v) { return f[0] == v ? 0 : f[1] == v ? 1 : 2; }

// Walks the fan of each vertex through its manifold edges, corner to corner:
// each corner is visited once. False as soon as a vertex has a second fan.
bool single_fans(const uint32_t* indices, size_t triangle_count, size_t vertex_count, const Topology& t) {
  std::vector<uint8_t> seen(triangle_count, 0);  // bit k: corner k visited
  std::vector<uint8_t> fans(vertex_count, 0);
  uint64_t steps = 0;
  struct Count {  // added on every way out
    uint64_t& steps;
    ~Count() { detail::count_work(steps); }
  } count{steps};
  auto other_face = [&](uint32_t e, uint32_t f) -> uint32_t {
    const Edge& edge = t.edges[e];
    if (edge.face_count != 2) return Topology::kNone;
    const uint32_t a = t.edge_faces[edge.first] >> 1, b = t.edge_faces[edge.first + 1] >> 1;
    return a == f ? b : a;
  };
  for (size_t f0 = 0; f0 < triangle_count; ++f0) {
    if (t.face_flags[f0] & kFaceCollapsed) continue;
    for (int k0 = 0; k0 < 3; ++k0) {
      if (seen[f0] >> k0 & 1) continue;
      const uint32_t v = indices[3 * f0 + k0];
      if (fans[v]++) return false;
      seen[f0] |= uint8_t(1 << k0);
      // Both ways round v from (f0, k0): out through the edge leaving v, then
      // through the edge entering it.
      for (int way = 0; way < 2; ++way) {
        uint32_t f = uint32_t(f0), e = t.face_edges[3 * f0 + (way ? (k0 + 2) % 3 : k0)];
        for (;;) {
          const uint32_t g = other_face(e, f);
          if (g == Topology::kNone) break;
          const int k = corner_of(indices + 3 * size_t(g), v);
          if (seen[g] >> k & 1) break;  // back at the start: a closed fan
          seen[g] |= uint8_t(1 << k);
          ++steps;
          const uint32_t e0 = t.face_edges[3 * size_t(g) + k], e1 = t.face_edges[3 * size_t(g) + (k + 2) % 3];
          e = e0 == e ? e1 : e0;
          f = g;
        }
      }
    }
  }
  return true;
}

}  // namespace

bool halfedges_from_edge_table(const uint32_t* indices, size_t triangle_count, size_t vertex_count,
                               const Topology& topology) {
  return topology.stats.non_manifold_edges == 0 && topology.stats.inconsistent_edges == 0 &&
         single_fans(indices, triangle_count, vertex_count, topology);
}

HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                    const Topology& t) {
  if (!halfedges_from_edge_table(indices, triangle_count, positions.size(), t))
    return summarize_halfedges(positions, indices, triangle_count);
  HalfedgeSummary s;
  s.skipped_faces = t.stats.collapsed_triangles;
  s.added_faces = triangle_count - s.skipped_faces;
  // Each boundary edge as the half-edge its face does not use; the one leaving
  // a vertex is unique (one fan per vertex), so following them walks each hole.
  std::vector<uint32_t> leaving(positions.size(), Topology::kNone);
  auto from_to = [&](const Edge& e, uint32_t& from, uint32_t& to) {
    const bool reversed = t.edge_faces[e.first] & 1;  // the face runs v1 -> v0: the hole runs v0 -> v1
    from = reversed ? e.v0 : e.v1;
    to = reversed ? e.v1 : e.v0;
  };
  for (uint32_t i = 0; i < t.edges.size(); ++i) {
    if (t.edges[i].kind != EdgeKind::Boundary) continue;
    uint32_t from, to;
    from_to(t.edges[i], from, to);
    leaving[from] = i;
  }
  std::vector<uint8_t> walked(t.edges.size(), 0);
  uint64_t steps = t.edges.size();
  for (uint32_t i = 0; i < t.edges.size(); ++i) {
    if (t.edges[i].kind != EdgeKind::Boundary || walked[i]) continue;
    ++s.boundary_loops;
    for (uint32_t e = i; e != Topology::kNone && !walked[e];) {
      walked[e] = 1;
      ++steps;
      uint32_t from, to;
      from_to(t.edges[e], from, to);
      e = leaving[to];
    }
  }
  detail::count_work(steps);
  return s;
}

}  // namespace geom
