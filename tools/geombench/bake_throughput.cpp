// tools/geombench/bake_throughput.cpp: see bake_throughput.h.
#include "bake_throughput.h"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "geom/bake.h"
#include "geom/report.h"
#include "geom/weld.h"
#include "peers.h"
#include "scenes.h"

namespace geombench {
namespace {

struct Input {
  geom::Scene raw;
  geom::WeldResult welded;
};

// One run of `method`; returns a value that depends on the output (kept alive).
size_t run(const std::string& method, const Input& in) {
  const geom::Scene& m = in.raw;
  if (method == "bake") return geom::bake_scene(m, "mesh").sections.size();
  if (method == "meshopt")
    return geom_bench::meshopt_adjacency(m.positions.data(), m.vertex_count(), m.indices.data(), m.indices.size());
  return geom_bench::openmesh_trimesh(in.welded);
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

std::vector<BakeRow> bake_throughput(const std::vector<int>& sphere_n, int repetitions, int fan_triangles) {
  geom::keep_memory_across_bakes();
  std::vector<BakeRow> rows;
  std::vector<int> meshes = sphere_n;
  if (fan_triangles > 0) meshes.push_back(-fan_triangles);
  for (int n : meshes) {
    Input in;
    const float centre[3] = {0, 0, 0};
    if (n > 0) {
      add_sphere(in.raw, n, 1, centre);
    } else {  // a fan: one vertex in every triangle
      in.raw.positions = {0, 0, 0};
      for (int i = 0; i <= -n; ++i)
        in.raw.positions.insert(in.raw.positions.end(),
                                {float(std::cos(6.2 * i / -n)), float(std::sin(6.2 * i / -n)), 0.0f});
      for (int i = 0; i < -n; ++i) in.raw.indices.insert(in.raw.indices.end(), {0u, uint32_t(i + 1), uint32_t(i + 2)});
    }
    in.welded = geom::weld(geom::positions_of(in.raw.positions.data(), in.raw.vertex_count()), in.raw.indices.data(),
                           in.raw.indices.size());
    // The three methods in turn, repetition by repetition (a drift in the
    // machine's speed reaches them alike); each repetition runs a method until
    // it has spent 30 ms of this thread's CPU time: its time per call.
    const char* methods[3] = {"bake", "meshopt", "openmesh"};
    double peak[3];  // first: the child starts from the least reused heap
    for (int m = 0; m < 3; ++m) peak[m] = geom_bench::peak_extra_bytes([&] { return run(methods[m], in); });
    std::vector<double> per_call[3];
    for (int k = 0; k < std::max(1, repetitions); ++k)
      for (int m = 0; m < 3; ++m) {
        const double c0 = thread_cpu_seconds();
        double spent = 0;
        int calls = 0;
        do {
          volatile size_t keep = run(methods[m], in);
          (void)keep;
          ++calls;
          spent = thread_cpu_seconds() - c0;
        } while (spent < 0.03);
        per_call[m].push_back(spent / calls);
      }
    for (int m = 0; m < 3; ++m) {
      BakeRow r;
      r.method = methods[m];
      r.triangles = in.raw.triangle_count();
      r.peak_bytes = peak[m];
      std::sort(per_call[m].begin(), per_call[m].end());
      r.seconds = per_call[m][per_call[m].size() / 2];
      r.triangles_per_second = r.seconds > 0 ? double(r.triangles) / r.seconds : 0;
      rows.push_back(r);
    }
  }
  return rows;
}

}  // namespace geombench
