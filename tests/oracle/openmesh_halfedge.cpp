// The tests' OpenMesh oracle of the half-edge summary (openmesh_halfedge.h).
#include "openmesh_halfedge.h"

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

}  // namespace geom
