// The baked container's costs: CRC-32C throughput, Reader::open (full
// validation of every byte) and serialize_baked on the container of a
// 204,800-triangle mesh, and the whole bake of that mesh (weld, topology, face
// planes, ESM quads, shadow volume, adjacency, one light) without the write.
//   build/bench/bench_baked [--benchmark_repetitions=5 --benchmark_report_aggregates_only=true]
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "geom/bake.h"
#include "geom/baked_reader.h"
#include "geom/baked_writer.h"

namespace {

// n x n quads on a sphere, the u = 0 / u = 1 column duplicated (a UV seam).
geom::Scene sphere(int n) {
  geom::Scene s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double u = 2 * M_PI * i / n, v = M_PI * (0.02 + 0.96 * j / n);
      s.positions.insert(s.positions.end(), {float(std::cos(u) * std::sin(v)), float(std::cos(v)),
                                             float(std::sin(u) * std::sin(v))});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.indices.insert(s.indices.end(), {a, c, b, b, c, d});
    }
  s.sources.resize(s.indices.size() / 3);
  s.files.push_back("sphere");
  return s;
}

const geom::Scene& scene() {
  static geom::Scene s = sphere(320);  // 204,800 triangles
  return s;
}

geom::BakeOptions options() {
  geom::BakeOptions o;
  const double point[4] = {3, 4, 5, 1};
  o.lights = {geom::light_from_homogeneous(point)};
  return o;
}

const std::vector<geom::BakedSection>& sections() {
  static std::vector<geom::BakedSection> s = geom::bake_scene(scene(), "sphere", options()).sections;
  return s;
}

const std::vector<unsigned char>& container() {
  static std::vector<unsigned char> bytes = [] {
    std::vector<unsigned char> b;
    std::string error;
    geom::serialize_baked(sections(), b, error);
    return b;
  }();
  return bytes;
}

void BM_Crc32c(benchmark::State& state) {
  std::vector<unsigned char> data(size_t(state.range(0)));
  for (size_t i = 0; i < data.size(); ++i) data[i] = uint8_t(i * 2654435761u >> 24);
  for (auto _ : state) benchmark::DoNotOptimize(geom::baked::crc32c(data.data(), data.size()));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(data.size()));
}
BENCHMARK(BM_Crc32c)->Arg(4096)->Arg(1 << 24);

void BM_ReaderOpen(benchmark::State& state) {
  const auto& bytes = container();
  geom::baked::Reader r;
  for (auto _ : state) {
    bool ok = r.open(bytes.data(), bytes.size());
    if (!ok) state.SkipWithError(r.error().c_str());
    benchmark::DoNotOptimize(ok);
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes.size()));
  state.counters["file_MB"] = double(bytes.size()) / 1e6;
  state.counters["sections"] = double(r.sections().size());
}
BENCHMARK(BM_ReaderOpen)->Unit(benchmark::kMillisecond);

void BM_Serialize(benchmark::State& state) {
  std::vector<unsigned char> out;
  std::string error;
  for (auto _ : state) {
    geom::serialize_baked(sections(), out, error);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(out.size()));
}
BENCHMARK(BM_Serialize)->Unit(benchmark::kMillisecond);

void BM_BakeScene(benchmark::State& state) {
  const geom::Scene& s = scene();
  const geom::BakeOptions o = options();
  for (auto _ : state) {
    geom::BakeResult r = geom::bake_scene(s, "sphere", o);
    if (!r.ok) state.SkipWithError(r.error.c_str());
    benchmark::DoNotOptimize(r.sections.data());
  }
  state.counters["tris/s"] =
      benchmark::Counter(double(s.triangle_count()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BakeScene)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
