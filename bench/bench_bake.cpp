// Silhouette bake throughput on a procedural mesh of 820,480 triangles (a UV
// sphere with a seam split, as exported assets have, plus a ripple so that not
// every quad is planar), one core, against meshopt_generateAdjacencyIndexBuffer
// on the same mesh in the same run. Before the table: what each rule saved
// and the bytes per emitted extended-shadow-map edge.
//   build/bench/bench_bake [--benchmark_repetitions=5 --benchmark_report_aggregates_only=true]
#include <benchmark/benchmark.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "geom/adjacency.h"
#include "geom/esm_quads.h"
#include "geom/extrude.h"
#include "geom/face_planes.h"
#include "geom/shadow_volume.h"
#include "geom/silhouette.h"
#include "geom/topology.h"
#include "geom/weld.h"

namespace {

struct Mesh {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
};

// n x n quads on a sphere, the u = 0 / u = 1 column duplicated (a UV seam),
// the poles closed by fans (a closed surface, outward counter-clockwise); the
// upper half rippled (non-planar quads, concave edges), the lower half smooth
// (planar quads: their diagonals are coplanar edges).
Mesh sphere(int n) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double u = 2 * M_PI * (i % n) / n, v = M_PI * (0.02 + 0.96 * j / n);
      double r = 1 + (j > n / 2 ? 0.02 * std::sin(37 * u) * std::sin(23 * v) : 0.0);
      m.positions.insert(m.positions.end(), {float(r * std::cos(u) * std::sin(v)), float(r * std::cos(v)),
                                             float(r * std::sin(u) * std::sin(v))});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
    }
  const uint32_t top = uint32_t(m.vertex_count()), bottom = top + 1;
  m.positions.insert(m.positions.end(), {0, 1, 0, 0, -1, 0});
  for (int i = 0; i < n; ++i) {
    m.indices.insert(m.indices.end(), {top, uint32_t(i + 1), uint32_t(i)});
    const uint32_t a = n * (n + 1) + i;
    m.indices.insert(m.indices.end(), {bottom, a, a + 1});
  }
  return m;
}

const Mesh& big() {
  static Mesh m = sphere(640);  // 820,480 triangles
  return m;
}

struct Welded {
  geom::WeldResult weld;
  geom::Topology topology;
  geom::FacePlanes planes;
};
const Welded& welded() {
  static Welded w = [] {
    Welded r;
    const Mesh& m = big();
    r.weld = geom::weld(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(), m.indices.size());
    auto p = geom::positions_of(r.weld.positions.data(), r.weld.vertex_count());
    r.topology = geom::build_topology(p, r.weld.indices.data(), m.triangle_count());
    r.planes = geom::compute_face_planes(p, r.weld.indices.data(), m.triangle_count(), r.topology);
    return r;
  }();
  return w;
}

void tris_per_second(benchmark::State& state) {
  state.counters["tris/s"] =
      benchmark::Counter(double(big().triangle_count()), benchmark::Counter::kIsIterationInvariantRate);
}

// The whole bake: weld, topology, planes, ESM quads, shadow volume, adjacency.
void BM_BakeAll(benchmark::State& state) {
  const Mesh& m = big();
  for (auto _ : state) {
    auto b = geom::bake_silhouettes(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(),
                                    m.triangle_count(), {});
    benchmark::DoNotOptimize(b.esm.quads.data());
  }
  tris_per_second(state);
}

// The bake after weld + topology (what this module adds).
void BM_BuffersFromTopology(benchmark::State& state) {
  const Welded& w = welded();
  const size_t n = big().triangle_count();
  auto p = geom::positions_of(w.weld.positions.data(), w.weld.vertex_count());
  std::vector<uint32_t> adj(geom::adjacency_index_count(n));
  for (auto _ : state) {
    auto planes = geom::compute_face_planes(p, w.weld.indices.data(), n, w.topology);
    auto esm = geom::build_esm_quads(p, w.weld.indices.data(), n, w.topology, planes);
    auto sv = geom::build_shadow_volume(p, w.weld.indices.data(), n, w.topology, planes);
    geom::build_adjacency(adj.data(), w.weld.indices.data(), n, w.weld.vertex_count());
    benchmark::DoNotOptimize(esm.quads.data());
    benchmark::DoNotOptimize(sv.sides.data());
  }
  tris_per_second(state);
}

void BM_FacePlanes(benchmark::State& state) {
  const Welded& w = welded();
  auto p = geom::positions_of(w.weld.positions.data(), w.weld.vertex_count());
  for (auto _ : state) {
    auto planes = geom::compute_face_planes(p, w.weld.indices.data(), big().triangle_count(), w.topology);
    benchmark::DoNotOptimize(planes.planes.data());
  }
  tris_per_second(state);
}

void BM_EsmQuads(benchmark::State& state) {
  const Welded& w = welded();
  auto p = geom::positions_of(w.weld.positions.data(), w.weld.vertex_count());
  for (auto _ : state) {
    auto esm = geom::build_esm_quads(p, w.weld.indices.data(), big().triangle_count(), w.topology, w.planes);
    benchmark::DoNotOptimize(esm.quads.data());
  }
  tris_per_second(state);
}

void BM_ShadowVolume(benchmark::State& state) {
  const Welded& w = welded();
  auto p = geom::positions_of(w.weld.positions.data(), w.weld.vertex_count());
  for (auto _ : state) {
    auto sv = geom::build_shadow_volume(p, w.weld.indices.data(), big().triangle_count(), w.topology, w.planes);
    benchmark::DoNotOptimize(sv.sides.data());
  }
  tris_per_second(state);
}

void BM_LightVolume(benchmark::State& state) {
  const Welded& w = welded();
  auto p = geom::positions_of(w.weld.positions.data(), w.weld.vertex_count());
  static const geom::ShadowVolume sv =
      geom::build_shadow_volume(p, w.weld.indices.data(), big().triangle_count(), w.topology, w.planes);
  const float light[4] = {2.0f, 3.0f, 1.0f, 1.0f};
  for (auto _ : state) {
    auto lv = geom::build_light_volume(sv, light);
    benchmark::DoNotOptimize(lv.sides.data());
  }
  tris_per_second(state);
}

// Adjacency from welded indices (what the bake does), and weld + adjacency
// from the seamed input (what meshoptimizer's function does: it remaps by
// position itself).
void BM_Adjacency(benchmark::State& state) {
  const Welded& w = welded();
  const size_t n = big().triangle_count();
  std::vector<uint32_t> adj(geom::adjacency_index_count(n));
  for (auto _ : state) {
    geom::build_adjacency(adj.data(), w.weld.indices.data(), n, w.weld.vertex_count());
    benchmark::DoNotOptimize(adj.data());
  }
  tris_per_second(state);
}

void BM_WeldAdjacency(benchmark::State& state) {
  const Mesh& m = big();
  std::vector<uint32_t> adj(geom::adjacency_index_count(m.triangle_count()));
  for (auto _ : state) {
    auto wr = geom::weld(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(), m.indices.size());
    geom::build_adjacency(adj.data(), wr.indices.data(), m.triangle_count(), wr.vertex_count());
    benchmark::DoNotOptimize(adj.data());
  }
  tris_per_second(state);
}

void BM_MeshoptAdjacency(benchmark::State& state) {
  const Mesh& m = big();
  std::vector<unsigned int> adj(m.indices.size() * 2);
  for (auto _ : state) {
    meshopt_generateAdjacencyIndexBuffer(adj.data(), m.indices.data(), m.indices.size(), m.positions.data(),
                                         m.vertex_count(), 12);
    benchmark::DoNotOptimize(adj.data());
  }
  tris_per_second(state);
}

void BM_MeshoptAdjacencyWelded(benchmark::State& state) {
  const Welded& w = welded();
  std::vector<unsigned int> adj(w.weld.indices.size() * 2);
  for (auto _ : state) {
    meshopt_generateAdjacencyIndexBuffer(adj.data(), w.weld.indices.data(), w.weld.indices.size(),
                                         w.weld.positions.data(), w.weld.vertex_count(), 12);
    benchmark::DoNotOptimize(adj.data());
  }
  tris_per_second(state);
}

void print_savings() {
  const Mesh& m = big();
  std::vector<geom::LightVolume> lights(1);
  lights[0].light[0] = 2, lights[0].light[1] = 3, lights[0].light[2] = 1, lights[0].light[3] = 1;
  lights[0].name = "point";
  auto b = geom::bake_silhouettes(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(),
                                  m.triangle_count(), lights);
  std::printf("mesh: %zu triangles, %zu welded vertices\n%s", m.triangle_count(), b.weld.vertex_count(),
              geom::silhouette_report(b).c_str());
  std::printf("esm: %.1f%% of candidate edges emitted, %.2f bytes per emitted edge (%.2f for the records alone)\n",
              100.0 * b.esm.stats.emitted_edges / b.esm.stats.candidate_edges,
              double(b.esm.stats.bytes) / b.esm.stats.emitted_edges,
              double(b.esm.quads.size() * sizeof(geom::EsmQuad)) / b.esm.stats.emitted_edges);
}

}  // namespace

BENCHMARK(BM_BakeAll)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuffersFromTopology)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FacePlanes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EsmQuads)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShadowVolume)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LightVolume)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Adjacency)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshoptAdjacencyWelded)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WeldAdjacency)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshoptAdjacency)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  print_savings();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
