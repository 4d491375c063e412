// tools/geombench/bake_throughput.h: the toolkit's silhouette bake against the
// peer libraries on the same triangles, so that its throughput reads as a
// ratio to code an engine already has:
//   bake      geom::bake_scene from the raw (seamed) triangles: everything a
//             .gbake holds (weld, topology and its report, face planes, ESM
//             quads, generic shadow volume, adjacency, the sections), no I/O
//   meshopt   meshopt_generateAdjacencyIndexBuffer on the same raw triangles
//             (it remaps by position itself): adjacency only
//   openmesh  an OpenMesh TriMesh (half-edges) built from the welded triangles
//             (the weld not timed: OpenMesh needs shared vertices)
// on the rippled UV sphere of scenes.h at each `sphere_n` (70: 9,940 triangles,
// homer-sized; 158: 50,244, armadillo-sized; 633: 802,620, dragon-sized) and,
// when `fan_triangles` > 0, a fan of that many triangles around one vertex
// (the high-valence case). Time: CPU seconds of this thread per call (the
// machine may be shared: wall time would count other processes' turns), the
// median of `repetitions`, each as many calls as fill 30 ms, the three methods
// in turn; one core, freed memory kept across runs
// (geom::keep_memory_across_bakes, as `geombake bake` does), for every method
// alike. Peak memory: each operation once in a forked child, the rise of
// the child's peak resident set (VmHWM, reset through /proc/self/clear_refs)
// above its resident set once the input is built and freed heap memory is
// handed back (malloc_trim); 0 where Linux refuses.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace geombench {

struct BakeRow {
  std::string method;  // "bake", "meshopt", "openmesh"
  uint64_t triangles = 0;
  double seconds = 0;
  double triangles_per_second = 0;
  double peak_bytes = 0;  // extra peak memory of one run
};

std::vector<BakeRow> bake_throughput(const std::vector<int>& sphere_n, int repetitions, int fan_triangles = 0);

}  // namespace geombench
