// tools/geombench/bake_throughput.cpp: see bake_throughput.h.
#include "bake_throughput.h"

#include <chrono>
#include <cmath>

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
    for (const char* method : {"bake", "meshopt", "openmesh"}) {
      BakeRow r;
      r.method = method;
      r.triangles = in.raw.triangle_count();
      r.peak_bytes = geom_bench::peak_extra_bytes(
          [&] { return run(method, in); });  // first: the child starts from the least reused heap
      r.seconds = 1e30;
      for (int k = 0; k < std::max(1, repetitions); ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        volatile size_t keep = run(method, in);
        (void)keep;
        r.seconds = std::min(r.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
      r.triangles_per_second = r.seconds > 0 ? double(r.triangles) / r.seconds : 0;
      rows.push_back(r);
    }
  }
  return rows;
}

}  // namespace geombench
