// tools/geombench/bake_throughput.cpp: see bake_throughput.h.
#include "bake_throughput.h"

#include <malloc.h>
#include <meshoptimizer.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "geom/bake.h"
#include "geom/weld.h"
#include "peak_rss.h"  // libgeom/src
#include "scenes.h"

namespace geombench {
namespace {

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

struct Input {
  geom::Scene raw;
  geom::WeldResult welded;
};

// One run of `method`; returns a value that depends on the output (kept alive).
size_t run(const std::string& method, const Input& in) {
  const geom::Scene& m = in.raw;
  if (method == "bake") return geom::bake_scene(m, "mesh").sections.size();
  if (method == "meshopt") {
    std::vector<unsigned int> adj(m.indices.size() * 2);
    meshopt_generateAdjacencyIndexBuffer(adj.data(), m.indices.data(), m.indices.size(), m.positions.data(),
                                         m.vertex_count(), 12);
    return adj[adj.size() / 2];
  }
  const geom::WeldResult& w = in.welded;
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> vh(w.vertex_count());
  for (size_t i = 0; i < vh.size(); ++i)
    vh[i] = mesh.add_vertex(TriMesh::Point(w.positions[3 * i], w.positions[3 * i + 1], w.positions[3 * i + 2]));
  for (size_t f = 0; f < w.indices.size(); f += 3)
    mesh.add_face(vh[w.indices[f]], vh[w.indices[f + 1]], vh[w.indices[f + 2]]);
  return mesh.n_faces();
}

uint64_t current_rss() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long size = 0, resident = 0;
  const int got = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  return got == 2 ? resident * uint64_t(sysconf(_SC_PAGESIZE)) : 0;
}

// The extra peak memory of one run, measured in a child process.
double peak_extra(const std::string& method, const Input& in) {
  int fd[2];
  if (pipe(fd) != 0) return 0;
  const pid_t pid = fork();
  if (pid < 0) return close(fd[0]), close(fd[1]), 0;
  if (pid == 0) {
    close(fd[0]);
    double extra = 0;
    malloc_trim(0);  // hand freed heap back: a reused resident block would hide the run's allocations
    FILE* c = std::fopen("/proc/self/clear_refs", "w");
    const bool reset = c && std::fputs("5", c) >= 0 && std::fclose(c) == 0;
    if (reset) {
      const uint64_t base = current_rss();
      volatile size_t keep = run(method, in);
      (void)keep;
      const uint64_t peak = geom::peak_rss_bytes();
      extra = peak > base ? double(peak - base) : 0.0;
    }
    ssize_t ignored = write(fd[1], &extra, sizeof extra);
    (void)ignored;
    _exit(0);
  }
  close(fd[1]);
  double extra = 0;
  if (read(fd[0], &extra, sizeof extra) != ssize_t(sizeof extra)) extra = 0;
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return extra;
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
      r.peak_bytes = peak_extra(method, in);  // first: the child starts from the least reused heap
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
