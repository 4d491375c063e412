// Every silhouette buffer of one mesh (see geom/silhouette.h): the pipeline
// and the report of what each "only what a scene needs" rule saved.
#include "geom/silhouette.h"

#include <cmath>
#include <cstdio>

#include "geom/adjacency.h"
#include "geom/extrude.h"

namespace geom {

std::vector<LightVolume> scene_lights(const Scene& scene) {
  std::vector<LightVolume> out;
  for (const Light& l : scene.lights) {
    LightVolume v;
    v.name = l.name;
    light_homogeneous(l, v.light);  // geom/scene.h: directional (-direction, 0), else (position, 1)
    out.push_back(v);
  }
  return out;
}

SilhouetteBuffers bake_silhouettes(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                   std::vector<LightVolume> lights, const SilhouetteOptions& options) {
  SilhouetteBuffers b;
  b.weld = weld(positions, indices, 3 * triangle_count, options.weld_tolerance);
  const PositionSpan welded = positions_of(b.weld.positions.data(), b.weld.vertex_count());
  const uint32_t* wi = b.weld.indices.data();
  b.topology = build_topology(welded, wi, triangle_count, options.topology);
  b.planes = compute_face_planes(welded, wi, triangle_count, b.topology, options.planes);
  if (options.esm_quads) b.esm = build_esm_quads(welded, wi, triangle_count, b.topology, b.planes, options.esm);
  if (options.shadow_volume || !lights.empty())
    b.volume = build_shadow_volume(welded, wi, triangle_count, b.topology, b.planes, options.volume);
  if (options.adjacency) {
    b.adjacency.resize(adjacency_index_count(triangle_count));
    build_adjacency(b.adjacency.data(), wi, triangle_count, b.topology);
  }
  for (LightVolume& l : lights) {
    float local[4];
    to_local_light(b.planes.origin, l.light, local);
    l.volume = build_light_volume(b.volume, local);
  }
  b.lights = std::move(lights);
  return b;
}

std::string silhouette_report(const SilhouetteBuffers& b) {
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
  if (e.edges > 0) {  // built (SilhouetteOptions::esm_quads)
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
    std::snprintf(line, sizeof line,
                  "light '%s' (%g, %g, %g, %g): exact volume %llu sides, %llu caps, %llu bytes; rule per-light: "
                  "%llu side records / %llu caps / %lld bytes saved against the generic volume\n",
                  l.name.c_str(), l.light[0], l.light[1], l.light[2], l.light[3], (unsigned long long)lv.sides,
                  (unsigned long long)lv.caps, (unsigned long long)lv.bytes,
                  (unsigned long long)(v.sides - std::min(v.sides, lv.sides)),
                  (unsigned long long)(v.caps - std::min(v.caps, lv.caps)), (long long)v.bytes - (long long)lv.bytes);
    s += line;
  }
  return s;
}

}  // namespace geom
