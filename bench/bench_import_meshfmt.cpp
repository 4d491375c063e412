// Import speed of the text and binary mesh formats on a generated grid of
// 800,000 triangles (401 x 1001 vertices): OBJ (plain and v/vt/vn corners),
// ASCII and binary PLY, OFF, binary and ASCII STL, all parsed from memory
// through geom::import_memory (the dispatcher's validation included).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "geom/import.h"

namespace {

constexpr int kW = 1001, kH = 401;  // (kW-1)*(kH-1)*2 = 800,000 triangles

float height(int x, int y) { return 0.001f * float((x * 7 + y * 13) % 101); }

template <class F>
void for_each_triangle(F f) {
  for (int y = 0; y + 1 < kH; ++y)
    for (int x = 0; x + 1 < kW; ++x) {
      int a = y * kW + x, b = a + 1, c = a + kW, d = c + 1;
      f(a, b, d);
      f(a, d, c);
    }
}

std::string make_obj(bool corners) {
  std::string s;
  char buf[128];
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      s.append(buf, size_t(std::snprintf(buf, sizeof buf, "v %.6f %.6f %.6f\n", x * 0.01, y * 0.01, height(x, y))));
      if (corners) s += "vt 0.5 0.5\nvn 0 0 1\n";
    }
  for_each_triangle([&](int a, int b, int c) {
    if (corners)
      s.append(buf, size_t(std::snprintf(buf, sizeof buf, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a + 1, a + 1, a + 1, b + 1,
                                         b + 1, b + 1, c + 1, c + 1, c + 1)));
    else
      s.append(buf, size_t(std::snprintf(buf, sizeof buf, "f %d %d %d\n", a + 1, b + 1, c + 1)));
  });
  return s;
}

std::string make_off() {
  std::string s = "OFF\n" + std::to_string(kW * kH) + " 800000 0\n";
  char buf[128];
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      s.append(buf, size_t(std::snprintf(buf, sizeof buf, "%.6f %.6f %.6f\n", x * 0.01, y * 0.01, height(x, y))));
  for_each_triangle(
      [&](int a, int b, int c) { s.append(buf, size_t(std::snprintf(buf, sizeof buf, "3 %d %d %d\n", a, b, c))); });
  return s;
}

std::string make_ply(bool binary) {
  std::string s = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") + " 1.0\nelement vertex " +
                  std::to_string(kW * kH) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face 800000\n"
                  "property list uchar int vertex_indices\nend_header\n";
  char buf[128];
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      float p[3] = {x * 0.01f, y * 0.01f, height(x, y)};
      if (binary)
        s.append(reinterpret_cast<const char*>(p), 12);
      else
        s.append(buf, size_t(std::snprintf(buf, sizeof buf, "%.6f %.6f %.6f\n", p[0], p[1], p[2])));
    }
  for_each_triangle([&](int a, int b, int c) {
    if (binary) {
      s += char(3);
      int i[3] = {a, b, c};
      s.append(reinterpret_cast<const char*>(i), 12);
    } else {
      s.append(buf, size_t(std::snprintf(buf, sizeof buf, "3 %d %d %d\n", a, b, c)));
    }
  });
  return s;
}

std::string make_stl(bool binary) {
  std::string s = binary ? std::string(80, ' ') : "solid grid\n";
  if (binary) {
    uint32_t n = 800000;
    s.append(reinterpret_cast<const char*>(&n), 4);
  }
  char buf[256];
  auto pos = [](int i, float* p) {
    int x = i % kW, y = i / kW;
    p[0] = x * 0.01f, p[1] = y * 0.01f, p[2] = height(x, y);
  };
  for_each_triangle([&](int a, int b, int c) {
    float p[12] = {0, 0, 1};
    pos(a, p + 3), pos(b, p + 6), pos(c, p + 9);
    if (binary) {
      s.append(reinterpret_cast<const char*>(p), 48);
      s += std::string(2, '\0');
    } else {
      s.append(buf, size_t(std::snprintf(buf, sizeof buf,
                                         "facet normal 0 0 1\nouter loop\nvertex %.6f %.6f %.6f\nvertex %.6f %.6f "
                                         "%.6f\nvertex %.6f %.6f %.6f\nendloop\nendfacet\n",
                                         p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11])));
    }
  });
  if (!binary) s += "endsolid grid\n";
  return s;
}

void run(benchmark::State& state, const std::string& name, const std::string& bytes) {
  for (auto _ : state) {
    geom::ImportResult r = geom::import_memory(name, bytes.data(), bytes.size());
    if (!r.ok || r.scene.triangle_count() != 800000) {
      state.SkipWithError(r.error.c_str());
      break;
    }
    benchmark::DoNotOptimize(r.scene.indices.data());
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes.size()));
  state.counters["triangles/s"] =
      benchmark::Counter(800000.0 * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["MB"] = double(bytes.size()) / 1e6;
}

void BM_Obj(benchmark::State& s) {
  static const std::string b = make_obj(false);
  run(s, "grid.obj", b);
}
void BM_ObjCorners(benchmark::State& s) {
  static const std::string b = make_obj(true);
  run(s, "grid.obj", b);
}
void BM_Off(benchmark::State& s) {
  static const std::string b = make_off();
  run(s, "grid.off", b);
}
void BM_PlyAscii(benchmark::State& s) {
  static const std::string b = make_ply(false);
  run(s, "grid.ply", b);
}
void BM_PlyBinary(benchmark::State& s) {
  static const std::string b = make_ply(true);
  run(s, "grid.ply", b);
}
void BM_StlAscii(benchmark::State& s) {
  static const std::string b = make_stl(false);
  run(s, "grid.stl", b);
}
void BM_StlBinary(benchmark::State& s) {
  static const std::string b = make_stl(true);
  run(s, "grid.stl", b);
}

BENCHMARK(BM_Obj)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ObjCorners)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Off)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlyAscii)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlyBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StlAscii)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StlBinary)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
