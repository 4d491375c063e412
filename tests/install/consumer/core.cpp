// geom::core's consumer (tests/install/run.sh): weld, topology, face planes,
// ESM quads and the shadow volume of a cube made in memory, through the
// pipeline; no third-party library is linked (run.sh checks the link line).
#include <geom/pipeline.h>

#include <cstdio>
#include <vector>

int main() {
  // A unit cube as a soup: 12 triangles, 36 corners, outward winding.
  const float c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const uint32_t faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                 {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};
  std::vector<float> soup;
  std::vector<uint32_t> indices;
  for (const auto& f : faces)
    for (uint32_t v : f) {
      indices.push_back(uint32_t(soup.size() / 3));
      soup.insert(soup.end(), c[v], c[v] + 3);
    }
  const geom::Pipeline run = geom::run_pipeline(geom::positions_of(soup.data(), soup.size() / 3), indices.data(), 12);
  if (run.weld.vertex_count() != 8 || run.topology.stats.closed_components != 1) {
    std::fprintf(stderr, "Error: the cube did not weld into one closed component\n");
    return 1;
  }
  std::printf("core: %zu vertices, %zu ESM quads, %zu volume sides\n", run.weld.vertex_count(), run.esm.quads.size(),
              run.volume.sides.size());
  return 0;
}
