// Per-frame cost of the focus body and light matrix (geom/focus.h), for each
// light type and method, and the split between its stages (counters, in
// microseconds per frame): setup, receivers (V n S n L clips), hull (CGAL
// convex hull of R and the light), clip (the hull cut by S and L), faces
// (H's faces for the output: a second CGAL hull and the coplanar merge) and
// matrix. Goal: under 50 microseconds per light per frame on one core.
//
// Medians: build/bench/bench_focus --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
// (BM_FocusCasters: a frame with static casters, their hull per frame or precomputed, against none)
//
// The frame: a camera walking over a 200 x 20 x 200 scene, looking slightly
// down; the light above and to the side. Every iteration moves the camera a
// little (a new frame, as in a walkthrough), over 64 poses.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
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

// Static shadow casters: a town of 48 boxes (seeded) standing on the ground of
// the scene box, 384 corner points. S is the box cut by their convex hull,
// computed every frame from the points (FocusOptions::casters: CGAL's 3D
// hull per call) or once beforehand (FocusOptions::caster_hull, as a baked
// file's caster_hull section holds it). Arg 0: no casters, 1: points, 2: the
// precomputed hull; the goal is a frame with the precomputed hull at most 2x
// one without casters.
std::vector<float> town() {
  std::vector<float> xyz;
  std::mt19937 rng(48);
  std::uniform_real_distribution<double> at(-90, 90), size(2, 10), height(3, 18);
  for (int b = 0; b < 48; ++b) {
    const double x = at(rng), z = at(rng), w = size(rng), d = size(rng), h = height(rng);
    for (int c = 0; c < 8; ++c)
      xyz.insert(xyz.end(), {float(x + (c & 1 ? w : 0)), float(c & 2 ? h : 0), float(z + (c & 4 ? d : 0))});
  }
  return xyz;
}

void BM_FocusCasters(benchmark::State& state) {
  Scenario s = make(int(state.range(0)));
  const std::vector<float> points = town();
  std::vector<double> hull;
  focus_caster_hull(positions_of(points.data(), points.size() / 3), hull);
  FocusOptions opt;  // psm
  opt.faces = state.range(2) != 0;
  FocusStageTimes t;
  opt.stage_times = &t;
  if (state.range(1) == 1) opt.casters = positions_of(points.data(), points.size() / 3);
  if (state.range(1) == 2) opt.caster_hull = StridedSpan<FocusPlane>(hull.data(), hull.size() / 4, 32);
  FocusResult r;
  size_t i = 0;
  for (auto _ : state) {
    compute_focus(s.cameras[i++ % s.cameras.size()], s.light, s.box, opt, r);
    benchmark::DoNotOptimize(r.matrix[0]);
  }
  const double n = double(state.iterations()) / 1e6;  // -> microseconds per frame
  state.counters["setup_us"] = t.setup / n;
  state.counters["receivers_us"] = t.receivers / n;
  state.counters["hull_us"] = t.hull / n;
  state.counters["clip_us"] = t.clip / n;
  state.counters["faces_us"] = t.faces / n;
  state.counters["matrix_us"] = t.matrix / n;
  static const char* kCasters[3] = {"no casters", "casters: hull per frame", "casters: precomputed hull"};
  state.counters["hull_planes"] = double(hull.size() / 4);
  state.SetLabel(std::string(kLights[state.range(0)]) + " psm" + (opt.faces ? " +faces, " : " matrix only, ") +
                 kCasters[state.range(1)]);
}
BENCHMARK(BM_FocusCasters)->ArgsProduct({{0, 1, 2}, {0, 1, 2}, {1, 0}})->Unit(benchmark::kMicrosecond);

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
