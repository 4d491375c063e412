// bake_in_memory: the silhouette buffers of a mesh made in memory with
// geom::core alone (no third-party library, no file), in the two ways the
// core offers (docs/library.md, "The core's API"):
//   1. untrusted triangles through run_pipeline_checked: a Status (an
//      ErrorCode and "NAME: what is wrong") instead of a throw or a crash;
//   2. the stages one by one into the caller's own memory, each output sized
//      in advance by its *_bound function (meshoptimizer's style).
// The buffers are ready for glBufferData as they lie (the records of
// geom/baked_records.h, in the local frame planes.origin).
#include <geom/adjacency.h>
#include <geom/pipeline.h>

#include <cstdio>
#include <vector>

int main() {
  // A unit cube as 12 separate triangles (36 corners, as a mesh with UV seams
  // arrives), outward winding; the weld recovers its 8 vertices.
  const float corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const uint32_t faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                 {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};
  std::vector<float> soup;
  std::vector<uint32_t> indices;
  for (const auto& f : faces)
    for (uint32_t v : f) {
      indices.push_back(uint32_t(soup.size() / 3));
      soup.insert(soup.end(), corner[v], corner[v] + 3);
    }
  const geom::PositionSpan positions = geom::positions_of(soup.data(), soup.size() / 3);
  geom::Light sun;  // a static light: its exact volume is baked too
  sun.type = geom::LightType::Directional;
  sun.direction[0] = -0.3f, sun.direction[1] = -1.0f, sun.direction[2] = -0.2f;  // where its light travels

  // 1. Untrusted data: checked, answered with a code and a message.
  std::vector<uint32_t> damaged = indices;
  damaged[7] = 99;
  const geom::PipelineResult refused = geom::run_pipeline_checked("cube", positions, damaged.data(), damaged.size());
  std::printf("refused (%s): %s\n", geom::error_code_name(refused.code), refused.error.c_str());
  const geom::PipelineResult checked =
      geom::run_pipeline_checked("cube", positions, indices.data(), indices.size(), {sun});
  if (!checked.ok) {
    std::fprintf(stderr, "Error: %s\n", checked.error.c_str());
    return 1;
  }
  const geom::Pipeline& run = checked.run;
  const geom::TopologyStats& t = run.topology.stats;
  std::printf("welded %zu corners into %zu vertices; %llu edges, %llu closed component(s)\n", positions.size(),
              run.weld.vertex_count(), (unsigned long long)t.edges, (unsigned long long)t.closed_components);
  std::printf("ESM quads: %zu (%zu bytes), volume sides: %zu, caps: %zu; the light's exact volume: %zu sides\n",
              run.esm.quads.size(), run.esm.quads.size() * sizeof(geom::EsmQuad), run.volume.sides.size(),
              run.volume.caps.size(), run.lights.empty() ? size_t(0) : run.lights[0].volume.sides.size());

  // 2. Trusted data, caller-owned output: every array sized by its bound
  // before the stage runs (a real engine would place them in its own arena).
  const size_t tc = indices.size() / 3;
  std::vector<float> welded(3 * geom::weld_bound(positions.size()));
  std::vector<uint32_t> remap(positions.size()), welded_indices(indices.size());
  const size_t vc =
      geom::weld(welded.data(), remap.data(), welded_indices.data(), positions, indices.data(), indices.size());
  const geom::PositionSpan wp = geom::positions_of(welded.data(), vc);
  const geom::Topology topology = geom::build_topology(wp, welded_indices.data(), tc);
  const geom::FacePlanes planes = geom::compute_face_planes(wp, welded_indices.data(), tc, topology);
  std::vector<uint32_t> adjacency(geom::adjacency_bound(tc));
  geom::build_adjacency(adjacency.data(), welded_indices.data(), tc, topology);
  std::vector<geom::EsmQuad> quads(geom::esm_quads_bound(tc));
  const geom::EsmQuads esm = geom::build_esm_quads(quads.data(), wp, welded_indices.data(), tc, topology, planes);
  std::vector<geom::SvSide> sides(geom::shadow_volume_sides_bound(tc));
  std::vector<geom::SvCap> caps(geom::shadow_volume_caps_bound(tc));
  const geom::ShadowVolume volume =
      geom::build_shadow_volume(sides.data(), caps.data(), wp, welded_indices.data(), tc, topology, planes);
  std::printf("caller-owned: %zu vertices (bound %zu), %llu of %zu ESM quads, %llu of %zu sides, %llu of %zu caps\n",
              vc, geom::weld_bound(positions.size()), (unsigned long long)esm.stats.quads, quads.size(),
              (unsigned long long)volume.stats.sides, sides.size(), (unsigned long long)volume.stats.caps, caps.size());

  const bool same = vc == run.weld.vertex_count() && esm.stats.quads == run.esm.quads.size() &&
                    volume.stats.sides == run.volume.sides.size() && adjacency == run.adjacency;
  return refused.code == geom::ErrorCode::IndexOutOfRange && same && t.closed_components == 1 ? 0 : 1;
}
