// Half-edge summary through OpenMesh (geom/halfedge.h). OpenMesh types stay in
// this file.
#include "geom/halfedge.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Utils/Property.hh>
#include <mutex>
#include <vector>

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
  static std::once_flag silenced;
  std::call_once(silenced, [] { omerr().disable(); });
  for (size_t f = 0; f < triangle_count; ++f) {
    const uint32_t* v = indices + 3 * f;
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      ++s.skipped_faces;
      continue;
    }
    if (mesh.add_face(vh[v[0]], vh[v[1]], vh[v[2]]).is_valid())
      ++s.added_faces;
    else
      ++s.refused_faces;
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
    } while (g != h && !mesh.property(visited, g));
  }
  return s;
}

}  // namespace geom
