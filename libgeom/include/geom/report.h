// geom/report.h: the topology report of one input, for people and machines.
//
// `analyze` runs the pipeline's first stages (geom/pipeline.h: weld, topology,
// OpenMesh's half-edge summary) over an imported scene; `report_json` writes one JSON
// object on one line with these keys (counts over the non-collapsed triangles
// after the weld, see geom/topology.h for the definitions):
//   file, triangles, vertices, edges, boundary_edges, manifold_edges,
//   inconsistent_edges, non_manifold_edges, max_edge_faces, coplanar_edges,
//   convex_edges, concave_edges, collapsed_triangles, zero_area_triangles,
//   duplicate_triangles, components, closed_components, closed,
//   euler_characteristic, boundary_loops and openmesh_refused_faces (OpenMesh's
//   half-edge view of the same mesh, geom/halfedge.h), lights, warnings (array of strings),
//   source_faces (BSP only: {"polygon": {"faces": n, "triangles": n}, ...}),
//   stages (with timing: [{"stage", "seconds", "peak_rss_bytes"}]).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geom/halfedge.h"
#include "geom/pipeline.h"
#include "geom/scene.h"
#include "geom/topology.h"

namespace geom {

struct Report {
  std::string file;
  TopologyStats stats;
  HalfedgeSummary halfedge;  // OpenMesh's view: boundary loops, refused faces
  uint64_t lights = 0;
  std::vector<std::pair<std::string, uint64_t>> source_counts;  // Scene::source_counts
  std::vector<std::string> warnings;
  std::vector<StageTiming> stages;  // empty unless timing was asked for
};

// Runs the pipeline's weld, topology and half-edge summary over `scene` with
// `options`' settings (the buffers it asks for are not built) and fills
// `report` (its `file` left as it is; with options.timing the stages
// "weld", "topology" and "halfedge" appended).
void analyze(const Scene& scene, const PipelineOptions& options, Report& report);
// Fills `report` from a pipeline `run` over `scene` (run with halfedge): all
// but `file`; the run's stages are appended.
void report_of(const Scene& scene, const Pipeline& run, Report& report);

std::string report_json(const Report& report);
std::string report_text(const Report& report);

}  // namespace geom
