// bake_in_memory: the silhouette buffers of a mesh made in memory with
// geom::core alone (no third-party library, no file): a cube welded from a
// triangle soup, its topology, its ESM quads, its generic shadow volume and
// the exact volume of one static light, ready for glBufferData as they lie
// (the records of geom/baked_records.h, in the local frame run.planes.origin).
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
  geom::Light sun;  // a static light: its exact volume is baked too
  sun.type = geom::LightType::Directional;
  sun.direction[0] = -0.3f, sun.direction[1] = -1.0f, sun.direction[2] = -0.2f;  // where its light travels
  const geom::Pipeline run =
      geom::run_pipeline(geom::positions_of(soup.data(), soup.size() / 3), indices.data(), indices.size() / 3, {sun});
  const geom::TopologyStats& t = run.topology.stats;
  std::printf("welded %zu corners into %zu vertices; %llu edges, %llu closed component(s)\n", soup.size() / 3,
              run.weld.vertex_count(), (unsigned long long)t.edges, (unsigned long long)t.closed_components);
  std::printf("ESM quads: %zu (%zu bytes), volume sides: %zu, caps: %zu; the light's exact volume: %zu sides\n",
              run.esm.quads.size(), run.esm.quads.size() * sizeof(geom::EsmQuad), run.volume.sides.size(),
              run.volume.caps.size(), run.lights.empty() ? size_t(0) : run.lights[0].volume.sides.size());
  return run.weld.vertex_count() == 8 && t.closed_components == 1 ? 0 : 1;
}
