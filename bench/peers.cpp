// bench/peers.cpp: see peers.h.
#include "peers.h"

#include <malloc.h>
#include <meshoptimizer.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstdio>

#include "geom/process.h"
#include "geom/report.h"

namespace geom_bench {

size_t meshopt_adjacency(const float* positions, size_t vertex_count, const uint32_t* indices, size_t index_count,
                         std::vector<unsigned int>& adjacency) {
  adjacency.resize(index_count * 2);
  meshopt_generateAdjacencyIndexBuffer(adjacency.data(), indices, index_count, positions, vertex_count, 12);
  return adjacency.empty() ? 0 : adjacency[adjacency.size() / 2];
}

size_t meshopt_adjacency(const float* positions, size_t vertex_count, const uint32_t* indices, size_t index_count) {
  std::vector<unsigned int> adjacency;
  return meshopt_adjacency(positions, vertex_count, indices, index_count, adjacency);
}

size_t openmesh_trimesh(const geom::WeldResult& w) {
  using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> vh(w.vertex_count());
  for (size_t i = 0; i < vh.size(); ++i)
    vh[i] = mesh.add_vertex(TriMesh::Point(w.positions[3 * i], w.positions[3 * i + 1], w.positions[3 * i + 2]));
  for (size_t f = 0; f < w.indices.size(); f += 3)
    mesh.add_face(vh[w.indices[f]], vh[w.indices[f + 1]], vh[w.indices[f + 2]]);
  return mesh.n_faces();
}

namespace {

uint64_t resident_bytes() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long size = 0, resident = 0;
  const int got = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  return got == 2 ? resident * uint64_t(sysconf(_SC_PAGESIZE)) : 0;
}

}  // namespace

// In a child: freed heap handed back first (a reused resident block would hide
// the call's allocations), the peak reset through /proc/self/clear_refs.
double peak_extra_bytes(const std::function<size_t()>& op) {
  int fd[2];
  if (pipe(fd) != 0) return 0;
  const pid_t pid = fork();
  if (pid < 0) return close(fd[0]), close(fd[1]), 0;
  if (pid == 0) {
    close(fd[0]);
    double extra = 0;
    malloc_trim(0);
    FILE* c = std::fopen("/proc/self/clear_refs", "w");
    if (c && std::fputs("5", c) >= 0 && std::fclose(c) == 0) {
      const uint64_t base = resident_bytes();
      volatile size_t keep = op();
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

}  // namespace geom_bench
