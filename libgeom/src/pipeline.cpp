// The one pipeline (geom/pipeline.h): weld -> topology -> half-edge summary ->
// face planes -> adjacency -> ESM quads -> shadow volume -> light volumes, each
// stage the library's own (one algorithm per file), and the report of what
// each "only what a scene needs" rule saved.
#include "geom/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "geom/adjacency.h"
#include "geom/extrude.h"
#include "geom/process.h"
#include "geom/validate.h"

namespace geom {

Pipeline run_pipeline(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                      const std::vector<Light>& lights, const PipelineOptions& options,
                      const std::function<void(const char* stage, Pipeline& run)>& after_stage) {
  using clock = std::chrono::steady_clock;
  Pipeline p;
  auto mark = clock::now();
  const auto done = [&](const char* stage) {
    if (options.timing) {
      const auto now = clock::now();
      p.stages.push_back({stage, std::chrono::duration<double>(now - mark).count(), peak_rss_bytes()});
      mark = now;
    }
    if (after_stage) after_stage(stage, p);
  };
  const size_t tc = triangle_count;
  p.weld = weld(positions, indices, 3 * tc, options.weld_tolerance);
  done("weld");
  const PositionSpan welded = positions_of(p.weld.positions.data(), p.weld.vertex_count());
  const uint32_t* wi = p.weld.indices.data();
  p.topology = build_topology(welded, wi, tc, {options.coplanar_degrees, options.dihedral_angles});
  done("topology");
  if (options.halfedge) {
    p.halfedge = summarize_halfedges(welded, wi, tc, p.topology);
    done("halfedge");
  }
  const bool volume = options.volume || !lights.empty();
  if (options.face_planes || options.esm || volume) {
    p.planes = compute_face_planes(welded, wi, tc, p.topology, {options.coplanar_degrees, options.coplanar_distance});
    done("planes");
  }
  if (options.adjacency) {  // while the per-face tables are whole
    p.adjacency.resize(adjacency_index_count(tc));
    build_adjacency(p.adjacency.data(), wi, tc, p.topology);
    done("adjacency");
  }
  if (options.release_early) {  // no later stage reads them
    std::vector<uint32_t>().swap(p.topology.face_edges);
    std::vector<uint32_t>().swap(p.topology.face_twins);
    std::vector<uint32_t>().swap(p.topology.face_component);
    std::vector<uint8_t>().swap(p.topology.face_flags);
  }
  if (options.esm) {
    p.esm = build_esm_quads(welded, wi, tc, p.topology, p.planes, options.esm_options);
    done("esm");
  }
  if (options.release_early) std::vector<double>().swap(p.planes.normals);  // only the ESM quads read them
  if (volume) {
    p.volume = build_shadow_volume(welded, wi, tc, p.topology, p.planes, options.volume_options);
    done("volume");
  }
  if (options.release_early) {  // the edge table: read by the volume last
    std::vector<Edge>().swap(p.topology.edges);
    std::vector<uint32_t>().swap(p.topology.edge_faces);
  }
  p.lights.reserve(lights.size());
  for (const Light& light : lights) {
    double h[4];
    float local[4];
    light_homogeneous(light, h);
    to_local_light(p.planes.origin, h, local);
    p.lights.push_back({light, build_light_volume(p.volume, local)});
  }
  if (!lights.empty()) done("lights");
  return p;
}

PipelineResult run_pipeline_checked(const std::string& name, PositionSpan positions, const uint32_t* indices,
                                    size_t index_count, const std::vector<Light>& lights,
                                    const PipelineOptions& options) {
  PipelineResult r;
  static_cast<Status&>(r) = validate_triangles(positions, indices, index_count, name);
  if (!r.ok) return r;
  for (const Light& light : lights) {
    double h[4];
    light_homogeneous(light, h);
    const bool finite = std::isfinite(h[0]) && std::isfinite(h[1]) && std::isfinite(h[2]) && std::isfinite(h[3]);
    if (!finite || (h[0] == 0 && h[1] == 0 && h[2] == 0 && h[3] == 0)) {
      r.ok = false;
      r.code = ErrorCode::NonFinite;
      r.error = name + ": light '" + light.name + "' is not a usable (x, y, z, w): non-finite or all zero";
      return r;
    }
  }
  try {
    r.run = run_pipeline(positions, indices, index_count / 3, lights, options);
  } catch (const std::bad_alloc&) {
    r = PipelineResult();
    r.code = ErrorCode::OutOfMemory;
    r.error = name + ": out of memory in the pipeline";
  }
  return r;
}

std::string silhouette_report(const Pipeline& b) {
  std::string s;
  char line[512];
  auto pct = [](double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; };
  const EsmStats& e = b.esm.stats;
  const ShadowVolumeStats& v = b.volume.stats;
  std::snprintf(line, sizeof line,
                "faces: %llu (%llu degenerate, no shadow), stored planes: %zu (%llu faces share a coplanar "
                "neighbour's plane)\n",
                (unsigned long long)b.topology.stats.triangles, (unsigned long long)b.planes.degenerate_faces,
                b.planes.plane_count(), (unsigned long long)b.planes.shared_faces);
  s += line;
  if (e.edges > 0) {  // built (PipelineOptions::esm)
    std::snprintf(line, sizeof line,
                  "esm quads: %llu candidate edges, %llu emitted (%.1f%%), %llu quads (%llu bevel edges), %llu "
                  "bytes = %.1f per emitted edge (naive 160-byte layout, every candidate: %llu bytes)\n",
                  (unsigned long long)e.candidate_edges, (unsigned long long)e.emitted_edges,
                  pct(e.emitted_edges, e.candidate_edges), (unsigned long long)e.quads,
                  (unsigned long long)e.bevel_edges, (unsigned long long)e.bytes,
                  e.emitted_edges ? double(e.bytes) / e.emitted_edges : 0.0, (unsigned long long)e.naive_bytes);
    s += line;
    std::snprintf(line, sizeof line,
                  "  rule coplanar: %llu edges skipped, %llu quads / %llu bytes saved (naive layout)\n"
                  "  rule concave:  %llu edges skipped, %llu quads / %llu bytes saved (naive layout)\n"
                  "  packing: %llu bytes saved against the naive layout\n",
                  (unsigned long long)e.skipped_coplanar, (unsigned long long)e.skipped_coplanar,
                  (unsigned long long)(e.skipped_coplanar * 160), (unsigned long long)e.skipped_concave,
                  (unsigned long long)e.skipped_concave, (unsigned long long)(e.skipped_concave * 160),
                  (unsigned long long)(e.naive_bytes > e.bytes ? e.naive_bytes - e.bytes : 0));
    s += line;
  }
  std::snprintf(line, sizeof line,
                "shadow volume: %llu side records (%llu pair edges, %llu single), %llu caps, %llu one-sided / "
                "%llu double-sided faces, %llu bytes (per-face frusta: %llu sides, %llu bytes)\n"
                "  rule coplanar: %llu side records / %llu bytes saved\n",
                (unsigned long long)v.sides, (unsigned long long)v.pair_edges, (unsigned long long)v.single_records,
                (unsigned long long)v.caps, (unsigned long long)v.one_sided_faces,
                (unsigned long long)v.double_sided_faces, (unsigned long long)v.bytes,
                (unsigned long long)v.naive_sides, (unsigned long long)v.naive_bytes,
                (unsigned long long)v.skipped_coplanar_records,
                (unsigned long long)(v.skipped_coplanar_records * sizeof(SvSide)));
  s += line;
  for (const LightVolume& l : b.lights) {
    const ShadowVolumeStats& lv = l.volume.stats;
    double h[4];
    light_homogeneous(l.light, h);
    std::snprintf(line, sizeof line,
                  "light '%s' (%g, %g, %g, %g): exact volume %llu sides, %llu caps, %llu bytes; rule per-light: "
                  "%llu side records / %llu caps / %lld bytes saved against the generic volume\n",
                  l.light.name.c_str(), h[0], h[1], h[2], h[3], (unsigned long long)lv.sides,
                  (unsigned long long)lv.caps, (unsigned long long)lv.bytes,
                  (unsigned long long)(v.sides - std::min(v.sides, lv.sides)),
                  (unsigned long long)(v.caps - std::min(v.caps, lv.caps)), (long long)v.bytes - (long long)lv.bytes);
    s += line;
  }
  return s;
}

}  // namespace geom
