// glTF import speed (geom::import_memory / import_file, the dispatcher's
// validation included) on:
//   - the 800,000-triangle grid of bench_import_meshfmt (401 x 1001 vertices) as
//     a GLB with FLOAT positions and UNSIGNED_INT indices, as a GLB with
//     KHR_mesh_quantization positions (normalized SHORT, byteStride 8), and as a
//     .gltf with a base64 data-URI buffer;
//   - 1,000 instances of a 800-triangle mesh (node transforms, 800,000 triangles);
//   - 2CylinderEngine from assimp-testmodels, plain GLB and Draco-compressed.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "geom/import.h"

namespace {

struct Grid {
  int w, h;
  size_t triangles() const { return size_t(w - 1) * size_t(h - 1) * 2; }
};

float height(int x, int y) { return 0.001f * float((x * 7 + y * 13) % 101); }

void append(std::vector<unsigned char>& out, const void* p, size_t n) {
  const unsigned char* b = static_cast<const unsigned char*>(p);
  out.insert(out.end(), b, b + n);
}

// Binary payload: positions (FLOAT or normalized SHORT with 2 bytes padding),
// then UNSIGNED_INT indices. Returns the JSON describing it (no buffers entry).
std::string grid_payload(Grid g, bool quantized, std::vector<unsigned char>& bin, int instances) {
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      float p[3] = {x * 0.01f, y * 0.01f, height(x, y)};
      if (quantized) {
        int16_t q[4] = {int16_t(p[0] / 10.01f * 32767), int16_t(p[1] / 10.01f * 32767), int16_t(p[2] * 32767), 0};
        append(bin, q, 8);
      } else {
        append(bin, p, 12);
      }
    }
  const size_t pos_bytes = bin.size();
  for (int y = 0; y + 1 < g.h; ++y)
    for (int x = 0; x + 1 < g.w; ++x) {
      uint32_t a = uint32_t(y * g.w + x), b = a + 1, c = a + uint32_t(g.w), d = c + 1;
      uint32_t t[6] = {a, b, d, a, d, c};
      append(bin, t, sizeof t);
    }
  const size_t vertices = size_t(g.w) * size_t(g.h);
  std::string nodes, roots;
  for (int i = 0; i < instances; ++i) {
    nodes += std::string(i ? "," : "") + "{\"mesh\":0,\"translation\":[" + std::to_string(i % 40) + "," +
             std::to_string(i / 40) + ",0]}";
    roots += std::string(i ? "," : "") + std::to_string(i);
  }
  return std::string("{\"asset\":{\"version\":\"2.0\"},") +
         (quantized ? "\"extensionsUsed\":[\"KHR_mesh_quantization\"],\"extensionsRequired\":[\"KHR_mesh_quantization\"]," : "") +
         "\"scene\":0,\"scenes\":[{\"nodes\":[" + roots + "]}],\"nodes\":[" + nodes + "]," +
         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]," +
         "\"bufferViews\":[{\"buffer\":0,\"byteLength\":" + std::to_string(pos_bytes) +
         (quantized ? ",\"byteStride\":8" : "") + "},{\"buffer\":0,\"byteOffset\":" + std::to_string(pos_bytes) +
         ",\"byteLength\":" + std::to_string(bin.size() - pos_bytes) + "}]," +
         "\"accessors\":[{\"bufferView\":0,\"componentType\":" + (quantized ? "5122,\"normalized\":true" : "5126") +
         ",\"count\":" + std::to_string(vertices) + ",\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5125,\"count\":" +
         std::to_string(g.triangles() * 3) + ",\"type\":\"SCALAR\"}],";
}

std::vector<unsigned char> make_glb(Grid g, bool quantized, int instances = 1) {
  std::vector<unsigned char> bin;
  std::string json = grid_payload(g, quantized, bin, instances);  // fills bin first
  json += "\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + "}]}";
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<unsigned char> out;
  auto u32 = [&](uint32_t v) { append(out, &v, 4); };
  u32(0x46546C67), u32(2), u32(uint32_t(28 + json.size() + bin.size()));
  u32(uint32_t(json.size())), u32(0x4E4F534A);
  append(out, json.data(), json.size());
  u32(uint32_t(bin.size())), u32(0x004E4942);
  append(out, bin.data(), bin.size());
  return out;
}

std::string make_gltf_data_uri(Grid g) {
  std::vector<unsigned char> bin;
  std::string json = grid_payload(g, false, bin, 1);
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string b64;
  b64.reserve(bin.size() / 3 * 4 + 4);
  for (size_t i = 0; i < bin.size(); i += 3) {
    uint32_t v = uint32_t(bin[i]) << 16 | (i + 1 < bin.size() ? uint32_t(bin[i + 1]) << 8 : 0) |
                 (i + 2 < bin.size() ? bin[i + 2] : 0);
    b64 += k[v >> 18 & 63];
    b64 += k[v >> 12 & 63];
    b64 += i + 1 < bin.size() ? k[v >> 6 & 63] : '=';
    b64 += i + 2 < bin.size() ? k[v & 63] : '=';
  }
  return json + "\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) +
         ",\"uri\":\"data:application/octet-stream;base64," + b64 + "\"}]}";
}

void run(benchmark::State& state, const char* name, const void* data, size_t size) {
  size_t triangles = 0;
  for (auto _ : state) {
    geom::ImportResult r = geom::import_memory(name, data, size);
    if (!r.ok) {
      state.SkipWithError(r.error.c_str());
      return;
    }
    triangles = r.scene.triangle_count();
    benchmark::DoNotOptimize(r.scene.positions.data());
  }
  state.counters["triangles"] = double(triangles);
  state.counters["tri/s"] = benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(size));
}

void BM_GlbFloat(benchmark::State& state) {
  static const auto glb = make_glb({1001, 401}, false);
  run(state, "grid.glb", glb.data(), glb.size());
}
BENCHMARK(BM_GlbFloat)->Unit(benchmark::kMillisecond);

void BM_GlbQuantized(benchmark::State& state) {
  static const auto glb = make_glb({1001, 401}, true);
  run(state, "grid.glb", glb.data(), glb.size());
}
BENCHMARK(BM_GlbQuantized)->Unit(benchmark::kMillisecond);

void BM_GltfDataUri(benchmark::State& state) {
  static const auto text = make_gltf_data_uri({1001, 401});
  run(state, "grid.gltf", text.data(), text.size());
}
BENCHMARK(BM_GltfDataUri)->Unit(benchmark::kMillisecond);

void BM_GlbInstanced(benchmark::State& state) {
  static const auto glb = make_glb({21, 21}, false, 1000);  // 800 triangles x 1,000 nodes
  run(state, "instances.glb", glb.data(), glb.size());
}
BENCHMARK(BM_GlbInstanced)->Unit(benchmark::kMillisecond);

void BM_File(benchmark::State& state, const std::string& path) {
  size_t triangles = 0;
  for (auto _ : state) {
    geom::ImportResult r = geom::import_file(path);
    if (!r.ok) {
      state.SkipWithError(r.error.c_str());
      return;
    }
    triangles = r.scene.triangle_count();
  }
  state.counters["triangles"] = double(triangles);
  state.counters["tri/s"] = benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_CAPTURE(BM_File, engine_plain_glb,
                  std::string("/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_File, engine_draco, std::string("/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf"))
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
