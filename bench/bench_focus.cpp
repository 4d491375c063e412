// Per-frame cost of the focus body and light matrix (geom/focus.h), for each
// light type and method, and the split between its stages (counters, in
// microseconds per frame): setup, receivers (V n S n L clips), hull (CGAL
// convex hull of R and the light), clip (the hull cut by S and L), faces
// (H's faces for the output: a second CGAL hull and the coplanar merge) and
// matrix. Goal: under 50 microseconds per light per frame on one core.
//
// Medians: build/bench/bench_focus --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
//
// The frame: a camera walking over a 200 x 20 x 200 scene, looking slightly
// down; the light above and to the side. Every iteration moves the camera a
// little (a new frame, as in a walkthrough), over 64 poses.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "geom/focus.h"

using namespace geom;

namespace {

struct Scenario {
  std::vector<CameraMatrices> cameras;
  Light light;
  FocusBox box{{-100, 0, -100}, {100, 20, 100}};
};

Scenario make(int type) {
  Scenario s;
  for (int i = 0; i < 64; ++i) {
    double a = i * 0.1;
    double eye[3] = {60 * std::cos(a), 3, 60 * std::sin(a)};
    double target[3] = {eye[0] - 10 * std::sin(a), 1.5, eye[2] + 10 * std::cos(a)};
    double up[3] = {0, 1, 0};
    s.cameras.push_back(camera_look_at(eye, target, up, 60, 16.0 / 9.0, 0.1, 500));
  }
  s.light.type = LightType(type);
  double pos[3] = {30, 60, 20}, dir[3] = {-0.4, -1, -0.3};
  for (int k = 0; k < 3; ++k) s.light.position[k] = pos[k], s.light.direction[k] = dir[k];
  s.light.outer_cone = 0.8;
  return s;
}

const char* kLights[3] = {"directional", "point", "spot"};

void BM_Focus(benchmark::State& state) {
  Scenario s = make(int(state.range(0)));
  FocusOptions opt;
  opt.method = FocusMethod(state.range(1));
  opt.faces = state.range(2) != 0;
  FocusResult r;
  size_t i = 0;
  for (auto _ : state) {
    compute_focus(s.cameras[i++ % s.cameras.size()], s.light, s.box, opt, r);
    benchmark::DoNotOptimize(r.matrix[0]);
  }
  state.SetLabel(std::string(kLights[state.range(0)]) + " " + focus_method_name(opt.method) +
                 (opt.faces ? " +faces" : " matrix only"));
}
BENCHMARK(BM_Focus)->ArgsProduct({{0, 1, 2}, {0, 1, 2}, {1, 0}})->Unit(benchmark::kMicrosecond);

void BM_FocusStages(benchmark::State& state) {
  Scenario s = make(int(state.range(0)));
  FocusStageTimes t;
  FocusOptions opt;  // psm
  opt.stage_times = &t;
  FocusResult r;
  size_t i = 0;
  for (auto _ : state) {
    compute_focus(s.cameras[i++ % s.cameras.size()], s.light, s.box, opt, r);
    benchmark::DoNotOptimize(r.matrix[0]);
  }
  double n = double(state.iterations()) / 1e6;  // -> microseconds per frame
  state.counters["setup_us"] = t.setup / n;
  state.counters["receivers_us"] = t.receivers / n;
  state.counters["hull_us"] = t.hull / n;
  state.counters["clip_us"] = t.clip / n;
  state.counters["faces_us"] = t.faces / n;
  state.counters["matrix_us"] = t.matrix / n;
  state.SetLabel(std::string(kLights[state.range(0)]) + " psm");
}
BENCHMARK(BM_FocusStages)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

void BM_CubeFaces(benchmark::State& state) {
  double pos[3] = {1, 2, 3}, m[6][16];
  for (auto _ : state) {
    focus_cube_faces(pos, 0.05, 100, m);
    benchmark::DoNotOptimize(m[5][15]);
  }
}
BENCHMARK(BM_CubeFaces);

}  // namespace

BENCHMARK_MAIN();
