// Silhouette bake throughput, one core, against meshoptimizer's adjacency and
// an OpenMesh build in the same run.
//
// The table (BM_Bake*, BM_Shared*, BM_Meshopt*, BM_OpenMesh*, BM_Cli* on each mesh,
// then a summary of ratios and peak bytes per triangle, and the bake split into
// the part that does meshoptimizer's job and the rest): four meshes of the sizes the
// issue names, each procedural unless a real file is named in the environment
//   dragon     GEOM_BENCH_DRAGON     or the rippled seamed sphere at 872,520 triangles
//   armadillo  GEOM_BENCH_ARMADILLO  or the same sphere at 52,164
//   homer      GEOM_BENCH_HOMER      or the same sphere at 9,940
//   fan        a 320,000-triangle fan (one vertex of valence 320,001)
// (CGAL's armadillo.off and homer.off, from Debian's libcgal-demo data.tar.gz,
// are the real ones of those sizes.) Library: geom::bake_scene, everything a
// `.gbake` holds, no I/O. Meshoptimizer: meshopt_generateAdjacencyIndexBuffer
// on the same raw triangles (it remaps by position itself). OpenMesh: a
// TriMesh built from the welded triangles (the weld not timed). Shared: weld +
// topology + adjacency on the same raw triangles, the bake's share of work that
// meshoptimizer's call also does. CLI:
// `geombake bake FILE -o TMPFS -j 1` end to end, a child process, its wall
// time and peak resident set. Rates are over CPU time (the machine is
// shared); the CLI rows are wall time. Freed memory is kept across runs
// (geom::keep_memory_across_bakes, as `geombake bake` does for a batch), for
// every method alike; the peak rows are measured in a fresh child each.
//
// Before the table: what each rule saved, and the per-stage benchmarks on the
// 820,480-triangle sphere (BM_FacePlanes ... BM_MeshoptAdjacency).
//   build/bench/bench_bake [--benchmark_repetitions=5 --benchmark_report_aggregates_only=true]
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <meshoptimizer.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geom/adjacency.h"
#include "geom/bake.h"
#include "geom/esm_quads.h"
#include "geom/extrude.h"
#include "geom/face_planes.h"
#include "geom/import.h"
#include "geom/pipeline.h"
#include "geom/report.h"
#include "geom/shadow_volume.h"
#include "geom/topology.h"
#include "geom/weld.h"
#include "peers.h"

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
    auto b = geom::run_pipeline(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(),
                                m.triangle_count());
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
    geom::build_adjacency(adj.data(), w.weld.indices.data(), n, w.topology);
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

// Adjacency from the edge table (what the bake does), from welded indices
// alone, and weld + adjacency from the seamed input (what meshoptimizer's
// function does: it remaps by position itself).
void BM_Adjacency(benchmark::State& state) {
  const Welded& w = welded();
  const size_t n = big().triangle_count();
  std::vector<uint32_t> adj(geom::adjacency_index_count(n));
  for (auto _ : state) {
    geom::build_adjacency(adj.data(), w.weld.indices.data(), n, w.topology);
    benchmark::DoNotOptimize(adj.data());
  }
  tris_per_second(state);
}

void BM_AdjacencyIndicesOnly(benchmark::State& state) {
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
  const double point[4] = {2, 3, 1, 1};
  std::vector<geom::Light> lights = {geom::light_from_homogeneous(point)};
  lights[0].name = "point";
  auto b = geom::run_pipeline(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(),
                              m.triangle_count(), lights);
  std::printf("mesh: %zu triangles, %zu welded vertices\n%s", m.triangle_count(), b.weld.vertex_count(),
              geom::silhouette_report(b).c_str());
  std::printf("esm: %.1f%% of candidate edges emitted, %.2f bytes per emitted edge (%.2f for the records alone)\n",
              100.0 * b.esm.stats.emitted_edges / b.esm.stats.candidate_edges,
              double(b.esm.stats.bytes) / b.esm.stats.emitted_edges,
              double(b.esm.quads.size() * sizeof(geom::EsmQuad)) / b.esm.stats.emitted_edges);
}

// ---- The table: the four meshes, library and CLI, peers in the same run ----

struct Input {
  std::string name, file;  // file: what the CLI bakes
  geom::Scene scene;
  geom::WeldResult welded;  // for the OpenMesh build
  size_t triangles() const { return scene.triangle_count(); }
};

void sphere_scene(int n, geom::Scene& s) {
  const Mesh m = sphere(n);
  s.positions = m.positions;
  s.indices = m.indices;
}

void fan_scene(int n, geom::Scene& s) {
  s.positions = {0, 0, 0};
  for (int i = 0; i <= n; ++i)
    s.positions.insert(s.positions.end(), {float(std::cos(6.2 * i / n)), float(std::sin(6.2 * i / n)), 0.0f});
  for (int i = 0; i < n; ++i) s.indices.insert(s.indices.end(), {0u, uint32_t(i + 1), uint32_t(i + 2)});
}

// Binary little-endian PLY, for the CLI rows.
bool write_ply(const std::string& path, const geom::Scene& s) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fprintf(f,
               "ply\nformat binary_little_endian 1.0\nelement vertex %zu\nproperty float x\nproperty float y\n"
               "property float z\nelement face %zu\nproperty list uchar int vertex_indices\nend_header\n",
               s.vertex_count(), s.triangle_count());
  std::fwrite(s.positions.data(), 4, s.positions.size(), f);
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    unsigned char rec[13] = {3};
    std::memcpy(rec + 1, &s.indices[3 * t], 12);
    std::fwrite(rec, 1, 13, f);
  }
  return std::fclose(f) == 0;
}

std::string scratch_dir() {
  if (access("/dev/shm", W_OK) == 0) return "/dev/shm";
  const char* t = std::getenv("TMPDIR");
  return t ? t : "/tmp";
}

std::vector<std::unique_ptr<Input>>& inputs() {
  static std::vector<std::unique_ptr<Input>> all = [] {
    std::vector<std::unique_ptr<Input>> v;
    struct Slot {
      const char* name;
      const char* env;
      int sphere_n;
    };
    for (const Slot& slot : {Slot{"dragon", "GEOM_BENCH_DRAGON", 660}, Slot{"armadillo", "GEOM_BENCH_ARMADILLO", 161},
                             Slot{"homer", "GEOM_BENCH_HOMER", 70}, Slot{"fan", nullptr, 0}}) {
      auto in = std::make_unique<Input>();
      const char* path = slot.env ? std::getenv(slot.env) : nullptr;
      if (path && *path) {
        geom::ImportResult r = geom::import_file(path);
        if (!r.ok) {
          std::fprintf(stderr, "Error: %s\n", r.error.c_str());
          std::exit(1);
        }
        in->scene = std::move(r.scene);
        in->file = path;
        in->name = slot.name;
      } else {
        if (slot.sphere_n)
          sphere_scene(slot.sphere_n, in->scene);
        else
          fan_scene(320000, in->scene);
        in->name = std::string(slot.name) + (slot.sphere_n ? "-sized" : "");
        in->file = scratch_dir() + "/bench_bake_" + slot.name + "_" + std::to_string(getpid()) + ".ply";
        if (!write_ply(in->file, in->scene)) in->file.clear();
      }
      in->welded = geom::weld(geom::positions_of(in->scene.positions.data(), in->scene.vertex_count()),
                              in->scene.indices.data(), in->scene.indices.size());
      v.push_back(std::move(in));
    }
    return v;
  }();
  return all;
}

size_t run_bake(const Input& in) {
  geom::BakeResult r = geom::bake_scene(in.scene, in.name);
  return r.sections.size();
}

// The part of the bake that does meshoptimizer's job (weld by position, the
// edge table, each edge's opposite vertex): the bake's own pipeline with every
// later stage off, so weld + topology + adjacency run as the bake runs them.
size_t run_shared(const Input& in) {
  const geom::Scene& m = in.scene;
  geom::PipelineOptions po;
  po.face_planes = po.esm = po.volume = false;
  const geom::Pipeline p = geom::run_pipeline(geom::positions_of(m.positions.data(), m.vertex_count()),
                                              m.indices.data(), m.triangle_count(), {}, po);
  return p.adjacency.empty() ? 0 : p.adjacency[p.adjacency.size() / 2];
}

size_t run_meshopt(const Input& in) {
  const geom::Scene& m = in.scene;
  return geom_bench::meshopt_adjacency(m.positions.data(), m.vertex_count(), m.indices.data(), m.indices.size());
}

size_t run_openmesh(const Input& in) { return geom_bench::openmesh_trimesh(in.welded); }

// `geombake bake FILE -o OUT -j 1` in a child: wall seconds, CPU seconds, peak
// RSS. The children are forked by a small process started first thing in
// main() (a child forked from this one, with every input in memory, would
// count this process's pages in its peak until it execs).
struct Spawner {
  int request = -1, reply = -1;
};
Spawner& spawner() {
  static Spawner s;
  return s;
}

struct CliRun {
  double wall = 0, cpu = 0, peak = 0;
  int ok = 0;
};

CliRun spawn_cli(const char* input, const char* output) {
  CliRun r;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) return r;
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1), dup2(null, 2);
    execl(GEOMBAKE_EXE, GEOMBAKE_EXE, "bake", input, "-o", output, "-j", "1", (char*)nullptr);
    _exit(127);
  }
  int status = 0;
  rusage ru{};
  if (wait4(pid, &status, 0, &ru) != pid) return r;
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  r.peak = double(ru.ru_maxrss) * 1024.0;
  r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  unlink(output);
  return r;
}

// Requests: "INPUT\nOUTPUT\n"; replies: a CliRun.
void start_spawner() {
  int req[2], rep[2];
  if (pipe(req) != 0 || pipe(rep) != 0) return;
  const pid_t pid = fork();
  if (pid < 0) return;
  if (pid == 0) {
    close(req[1]), close(rep[0]);
    FILE* in = fdopen(req[0], "r");
    char a[4096], b[4096];
    while (in && std::fgets(a, sizeof a, in) && std::fgets(b, sizeof b, in)) {
      a[std::strcspn(a, "\n")] = 0, b[std::strcspn(b, "\n")] = 0;
      const CliRun r = spawn_cli(a, b);
      if (write(rep[1], &r, sizeof r) != ssize_t(sizeof r)) break;
    }
    _exit(0);
  }
  close(req[0]), close(rep[1]);
  spawner().request = req[1];
  spawner().reply = rep[0];
}

bool run_cli(const Input& in, double& wall, double& cpu, double& peak) {
  if (spawner().request < 0) return false;
  const std::string out = scratch_dir() + "/bench_bake_" + std::to_string(getpid()) + ".gbake";
  const std::string msg = in.file + "\n" + out + "\n";
  CliRun r;
  if (write(spawner().request, msg.data(), msg.size()) != ssize_t(msg.size()) ||
      read(spawner().reply, &r, sizeof r) != ssize_t(sizeof r))
    return false;
  wall = r.wall, cpu = r.cpu, peak = r.peak;
  return r.ok;
}

struct Summary {
  std::vector<double> bake, shared, meshopt, openmesh;  // triangles per CPU second, one per repetition
  double bake_peak = 0, shared_peak = 0, meshopt_peak = 0, openmesh_peak = 0, cli_peak = 0;
  std::vector<double> cli_wall, cli_cpu;
};
std::map<std::string, Summary>& summary() {
  static std::map<std::string, Summary> s;
  return s;
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

void library_row(benchmark::State& state, Input* in, size_t (*op)(const Input&), std::vector<double> Summary::*rate,
                 double Summary::*peak) {
  const double c0 = thread_cpu_seconds();
  for (auto _ : state) benchmark::DoNotOptimize(op(*in));
  const double cpu = thread_cpu_seconds() - c0;
  state.counters["tris/s"] = benchmark::Counter(double(in->triangles()), benchmark::Counter::kIsIterationInvariantRate);
  Summary& s = summary()[in->name];
  if (s.*peak == 0) s.*peak = geom_bench::peak_extra_bytes([op, in] { return op(*in); });
  state.counters["peak B/tri"] = s.*peak / double(in->triangles());
  (s.*rate).push_back(double(in->triangles()) * double(state.iterations()) / std::max(1e-9, cpu));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void cli_row(benchmark::State& state, Input* in) {
  Summary& s = summary()[in->name];
  for (auto _ : state) {
    double wall = 0, cpu = 0, peak = 0;
    if (in->file.empty() || !run_cli(*in, wall, cpu, peak)) {
      state.SkipWithError("geombake bake failed");
      return;
    }
    state.SetIterationTime(wall);
    s.cli_wall.push_back(wall);
    s.cli_cpu.push_back(cpu);
    s.cli_peak = std::max(s.cli_peak, peak);
  }
  state.counters["cpu s"] = median(s.cli_cpu);
  state.counters["peak B/tri"] = s.cli_peak / double(in->triangles());
  state.counters["tris/s"] = double(in->triangles()) / median(s.cli_wall);
}

void register_table() {
  for (auto& p : inputs()) {
    Input* in = p.get();
    benchmark::RegisterBenchmark(("BM_Bake/" + in->name).c_str(), [in](benchmark::State& st) {
      library_row(st, in, run_bake, &Summary::bake, &Summary::bake_peak);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_Shared/" + in->name).c_str(), [in](benchmark::State& st) {
      library_row(st, in, run_shared, &Summary::shared, &Summary::shared_peak);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_Meshopt/" + in->name).c_str(), [in](benchmark::State& st) {
      library_row(st, in, run_meshopt, &Summary::meshopt, &Summary::meshopt_peak);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_OpenMesh/" + in->name).c_str(), [in](benchmark::State& st) {
      library_row(st, in, run_openmesh, &Summary::openmesh, &Summary::openmesh_peak);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_Cli/" + in->name).c_str(), [in](benchmark::State& st) { cli_row(st, in); })
        ->Unit(benchmark::kMillisecond)
        ->UseManualTime()
        ->Iterations(3);
  }
}

// The ratios, from the rates of this run (CPU time), per mesh.
void print_table() {
  std::printf("\n%-16s %10s %9s %9s %9s %8s %8s %9s %9s %9s %8s %8s\n", "mesh", "triangles", "bake M/s", "meshopt",
              "openmesh", "x mo", "x om", "bake B/t", "mo B/t", "cli s", "cli cpu", "cli B/t");
  for (auto& p : inputs()) {
    const Summary& s = summary()[p->name];
    const double n = double(p->triangles()), bake = median(s.bake), mo = median(s.meshopt), om = median(s.openmesh);
    std::printf("%-16s %10zu %9.2f %9.2f %9.2f %8.2f %8.2f %9.0f %9.0f %9.3f %8.3f %8.0f\n", p->name.c_str(),
                p->triangles(), bake * 1e-6, mo * 1e-6, om * 1e-6, mo > 0 ? bake / mo : 0, om > 0 ? bake / om : 0,
                s.bake_peak / n, s.meshopt_peak / n, median(s.cli_wall), median(s.cli_cpu), s.cli_peak / n);
  }
  std::printf(
      "(bake M/s, meshopt, openmesh: million triangles per CPU second, median of the repetitions; x mo, x om: bake "
      "over the peer;\n"
      " B/t: extra peak bytes per input triangle of one library call; cli s, cli cpu: median wall and CPU seconds\n"
      " of geombake bake -j 1 to %s; cli B/t: its whole peak resident set per input triangle)\n",
      scratch_dir().c_str());
  // Where the bake's time goes against meshoptimizer's: the shared part (what
  // meshoptimizer's call also does) and the rest (planes, ESM quads, volume,
  // half-edge summary, report, sections), in CPU nanoseconds per triangle.
  std::printf("\n%-16s %10s %10s %8s %10s %10s %10s %10s\n", "mesh", "shared M/s", "meshopt", "x mo", "shared ns/t",
              "rest ns/t", "mo ns/t", "shared B/t");
  for (auto& p : inputs()) {
    const Summary& s = summary()[p->name];
    const double bake = median(s.bake), sh = median(s.shared), mo = median(s.meshopt);
    if (!(bake > 0 && sh > 0 && mo > 0)) continue;
    std::printf("%-16s %10.2f %10.2f %8.2f %10.1f %10.1f %10.1f %10.0f\n", p->name.c_str(), sh * 1e-6, mo * 1e-6,
                sh / mo, 1e9 / sh, 1e9 / bake - 1e9 / sh, 1e9 / mo, s.shared_peak / double(p->triangles()));
  }
  std::printf(
      "(shared: weld + topology + adjacency, as the bake runs them: meshoptimizer's job; rest: the whole bake's "
      "time less the shared part's;\n shared B/t: its extra peak bytes per input triangle; the whole bake reaches 1.0x "
      "meshoptimizer only where shared + rest <= mo)\n");
}

}  // namespace

BENCHMARK(BM_BakeAll)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuffersFromTopology)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FacePlanes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EsmQuads)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShadowVolume)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LightVolume)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Adjacency)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdjacencyIndicesOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshoptAdjacencyWelded)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WeldAdjacency)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeshoptAdjacency)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  start_spawner();  // before any input exists: see run_cli
  // As geombake bake does: freed memory kept, so repeated bakes reuse their
  // pages as a batch's inputs do (the peers' runs get the same allocator).
  const bool kept = geom::keep_memory_across_bakes();
  std::printf("freed memory kept across runs: %s\n", kept ? "yes" : "no");
  print_savings();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_table();
  benchmark::RunSpecifiedBenchmarks();
  print_table();
  for (auto& p : inputs())
    if (p->file.find("/bench_bake_") != std::string::npos) unlink(p->file.c_str());
  benchmark::Shutdown();
  return 0;
}
