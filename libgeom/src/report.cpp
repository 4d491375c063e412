// The topology report (geom/report.h): from a pipeline run, and its two renderings.
#include "geom/report.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>

#include "geom/json_quote.h"
#include "json_write.h"

namespace geom {

std::string json_quote(const std::string& s) { return json::quote(s); }

namespace {

// "polygon.faces" -> {"polygon": {"faces": n}}; keeps the order of first appearance.
std::vector<std::pair<std::string, std::vector<std::pair<std::string, uint64_t>>>> group_counts(
    const std::vector<std::pair<std::string, uint64_t>>& counts) {
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, uint64_t>>>> groups;
  for (const auto& [key, value] : counts) {
    size_t dot = key.find('.');
    std::string group = dot == std::string::npos ? key : key.substr(0, dot);
    std::string field = dot == std::string::npos ? "count" : key.substr(dot + 1);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == group; });
    if (it == groups.end()) {
      groups.push_back({group, {}});
      it = groups.end() - 1;
    }
    it->second.push_back({field, value});
  }
  return groups;
}

}  // namespace

void analyze(const Scene& scene, const PipelineOptions& options, Report& report) {
  PipelineOptions o = options;
  o.halfedge = true;
  o.face_planes = o.esm = o.volume = o.adjacency = false;
  o.release_early = true;
  report_of(scene,
            run_pipeline(positions_of(scene.positions.data(), scene.vertex_count()), scene.indices.data(),
                         scene.triangle_count(), {}, o),
            report);
}

void report_of(const Scene& scene, const Pipeline& run, Report& report) {
  report.stats = run.topology.stats;
  report.halfedge = run.halfedge;
  report.lights = scene.lights.size();
  report.source_counts = scene.source_counts;
  report.warnings = scene.warnings;
  report.stages.insert(report.stages.end(), run.stages.begin(), run.stages.end());
}

std::string report_json(const Report& r) {
  const TopologyStats& s = r.stats;
  std::string o = "{\"file\":" + json::quote(r.file);
  auto num = [&](const char* key, uint64_t v) { o += ",\"" + std::string(key) + "\":" + json::count(v); };
  num("triangles", s.triangles);
  num("vertices", s.vertices);
  num("edges", s.edges);
  num("boundary_edges", s.boundary_edges);
  num("manifold_edges", s.manifold_edges);
  num("inconsistent_edges", s.inconsistent_edges);
  num("non_manifold_edges", s.non_manifold_edges);
  num("max_edge_faces", s.max_edge_faces);
  num("coplanar_edges", s.coplanar_edges);
  num("convex_edges", s.convex_edges);
  num("concave_edges", s.concave_edges);
  num("collapsed_triangles", s.collapsed_triangles);
  num("zero_area_triangles", s.zero_area_triangles);
  num("duplicate_triangles", s.duplicate_triangles);
  num("components", s.components);
  num("closed_components", s.closed_components);
  o += std::string(",\"closed\":") + (s.closed ? "true" : "false");
  o += ",\"euler_characteristic\":" + std::to_string(s.euler_characteristic);
  num("boundary_loops", r.halfedge.boundary_loops);
  num("openmesh_refused_faces", r.halfedge.refused_faces);
  num("lights", r.lights);
  o += ",\"warnings\":[";
  for (size_t i = 0; i < r.warnings.size(); ++i) o += (i ? "," : "") + json::quote(r.warnings[i]);
  o += "]";
  if (!r.source_counts.empty()) {
    o += ",\"source_faces\":{";
    auto groups = group_counts(r.source_counts);
    for (size_t g = 0; g < groups.size(); ++g) {
      o += (g ? "," : "") + json::quote(groups[g].first) + ":{";
      for (size_t i = 0; i < groups[g].second.size(); ++i)
        o += (i ? "," : "") + json::quote(groups[g].second[i].first) + ":" + json::count(groups[g].second[i].second);
      o += "}";
    }
    o += "}";
  }
  if (!r.stages.empty()) {
    o += ",\"stages\":[";
    for (size_t i = 0; i < r.stages.size(); ++i) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.6f", r.stages[i].seconds);
      o += std::string(i ? "," : "") + "{\"stage\":" + json::quote(r.stages[i].stage) + ",\"seconds\":" + buf +
           ",\"peak_rss_bytes\":" + json::count(r.stages[i].peak_rss_bytes) + "}";
    }
    o += "]";
  }
  o += "}";
  return o;
}

std::string report_text(const Report& r) {
  const TopologyStats& s = r.stats;
  char buf[2048];
  std::snprintf(buf, sizeof buf,
                "%s\n"
                "  triangles   %llu (%llu collapsed, %llu zero-area, %llu duplicate)\n"
                "  vertices    %llu (welded, used)\n"
                "  edges       %llu: %llu manifold, %llu boundary, %llu inconsistent, %llu non-manifold (up to %u "
                "faces)\n"
                "  shape       %llu coplanar, %llu convex, %llu concave\n"
                "  components  %llu (%llu closed); mesh is %s; Euler characteristic %lld\n"
                "  half-edges  %llu boundary loops; OpenMesh refused %llu faces (complex edges or vertices)\n"
                "  lights      %llu\n",
                r.file.c_str(), (unsigned long long)s.triangles, (unsigned long long)s.collapsed_triangles,
                (unsigned long long)s.zero_area_triangles, (unsigned long long)s.duplicate_triangles,
                (unsigned long long)s.vertices, (unsigned long long)s.edges, (unsigned long long)s.manifold_edges,
                (unsigned long long)s.boundary_edges, (unsigned long long)s.inconsistent_edges,
                (unsigned long long)s.non_manifold_edges, s.max_edge_faces, (unsigned long long)s.coplanar_edges,
                (unsigned long long)s.convex_edges, (unsigned long long)s.concave_edges,
                (unsigned long long)s.components, (unsigned long long)s.closed_components, s.closed ? "closed" : "open",
                (long long)s.euler_characteristic, (unsigned long long)r.halfedge.boundary_loops,
                (unsigned long long)r.halfedge.refused_faces, (unsigned long long)r.lights);
  std::string o = buf;
  for (const auto& [group, fields] : group_counts(r.source_counts)) {
    o += "  " + group + ":";
    for (const auto& [field, value] : fields) o += " " + std::to_string(value) + " " + field;
    o += "\n";
  }
  for (const StageTiming& st : r.stages) {
    std::snprintf(buf, sizeof buf, "  stage %-10s %9.3f ms, peak RSS %.1f MB\n", st.stage.c_str(), st.seconds * 1e3,
                  st.peak_rss_bytes / 1048576.0);
    o += buf;
  }
  for (const std::string& w : r.warnings) o += "  Warning: " + w + "\n";
  return o;
}

}  // namespace geom
