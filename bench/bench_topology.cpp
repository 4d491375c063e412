// Import-free benchmark of weld + topology on a procedural mesh of 819,200
// triangles (a UV sphere with a seam split, as exported assets have), against
// meshopt_generateAdjacencyIndexBuffer and an OpenMesh TriMesh build of the
// same triangles, in the same run. Also the import of the same mesh as binary
// STL and OBJ from memory. Peak memory per triangle is printed before the table.
//   build/bench/bench_topology [--benchmark_repetitions=5 --benchmark_report_aggregates_only=true]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "geom/import.h"
#include "geom/process.h"
#include "geom/report.h"
#include "geom/topology.h"
#include "geom/weld.h"
#include "peers.h"

namespace {

struct Mesh {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
};

// n x n quads on a sphere, the u = 0 / u = 1 column duplicated (a UV seam).
Mesh sphere(int n) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double u = 2 * M_PI * i / n, v = M_PI * (0.02 + 0.96 * j / n);
      m.positions.insert(m.positions.end(),
                         {float(std::cos(u) * std::sin(v)), float(std::cos(v)), float(std::sin(u) * std::sin(v))});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  return m;
}

const Mesh& big() {
  static Mesh m = sphere(640);  // 819,200 triangles
  return m;
}

void BM_Weld(benchmark::State& state) {
  const Mesh& m = big();
  for (auto _ : state) {
    auto w =
        geom::weld(geom::positions_of(m.positions.data(), m.positions.size() / 3), m.indices.data(), m.indices.size());
    benchmark::DoNotOptimize(w.indices.data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(m.indices.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_WeldTopology(benchmark::State& state) {
  const Mesh& m = big();
  for (auto _ : state) {
    auto w =
        geom::weld(geom::positions_of(m.positions.data(), m.positions.size() / 3), m.indices.data(), m.indices.size());
    auto t = geom::build_topology(geom::positions_of(w.positions.data(), w.vertex_count()), w.indices.data(),
                                  w.indices.size() / 3);
    benchmark::DoNotOptimize(t.edges.data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(m.indices.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_MeshoptAdjacency(benchmark::State& state) {
  const Mesh& m = big();
  std::vector<unsigned int> adjacency;
  for (auto _ : state) {
    geom_bench::meshopt_adjacency(m.positions.data(), m.positions.size() / 3, m.indices.data(), m.indices.size(),
                                  adjacency);
    benchmark::DoNotOptimize(adjacency.data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(m.indices.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_OpenMeshTriMesh(benchmark::State& state) {
  const Mesh& m = big();
  // OpenMesh needs shared vertices: give it the welded indices (weld not timed).
  auto w =
      geom::weld(geom::positions_of(m.positions.data(), m.positions.size() / 3), m.indices.data(), m.indices.size());
  for (auto _ : state) benchmark::DoNotOptimize(geom_bench::openmesh_trimesh(w));
  state.counters["tris/s"] =
      benchmark::Counter(double(m.indices.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

std::string as_binary_stl(const Mesh& m) {
  std::string s(80, ' ');
  uint32_t n = uint32_t(m.indices.size() / 3);
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (uint32_t f = 0; f < n; ++f) {
    float rec[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) std::memcpy(&rec[3 + 3 * k], &m.positions[3 * size_t(m.indices[3 * f + k])], 12);
    s.append(reinterpret_cast<const char*>(rec), 48);
    s.append(2, '\0');
  }
  return s;
}

std::string as_obj(const Mesh& m) {
  std::string s;
  char buf[96];
  for (size_t i = 0; i < m.positions.size(); i += 3) {
    std::snprintf(buf, sizeof buf, "v %.7g %.7g %.7g\n", m.positions[i], m.positions[i + 1], m.positions[i + 2]);
    s += buf;
  }
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    std::snprintf(buf, sizeof buf, "f %u %u %u\n", m.indices[i] + 1, m.indices[i + 1] + 1, m.indices[i + 2] + 1);
    s += buf;
  }
  return s;
}

void BM_ImportSTL(benchmark::State& state) {
  static const std::string bytes = as_binary_stl(big());
  for (auto _ : state) {
    auto r = geom::import_memory("sphere.stl", bytes.data(), bytes.size());
    if (!r.ok) state.SkipWithError(r.error.c_str());
    benchmark::DoNotOptimize(r.scene.indices.data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(big().indices.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_ImportOBJ(benchmark::State& state) {
  static const std::string bytes = as_obj(big());
  for (auto _ : state) {
    auto r = geom::import_memory("sphere.obj", bytes.data(), bytes.size());
    if (!r.ok) state.SkipWithError(r.error.c_str());
    benchmark::DoNotOptimize(r.scene.indices.data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(big().indices.size() / 3), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(BM_Weld)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WeldTopology)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshoptAdjacency)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenMeshTriMesh)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ImportSTL)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ImportOBJ)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  // Peak memory of weld + topology, measured before anything else grows the heap.
  const Mesh& m = big();
  const size_t tris = m.indices.size() / 3;
  uint64_t before = geom::peak_rss_bytes();
  {
    auto w =
        geom::weld(geom::positions_of(m.positions.data(), m.positions.size() / 3), m.indices.data(), m.indices.size());
    auto t = geom::build_topology(geom::positions_of(w.positions.data(), w.vertex_count()), w.indices.data(), tris);
    benchmark::DoNotOptimize(t.edges.data());
  }
  uint64_t after = geom::peak_rss_bytes();
  std::printf("mesh: %zu triangles; weld + topology peak memory: %.1f bytes per triangle (input mesh excluded)\n", tris,
              double(after - before) / double(tris));
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
