// bench/peers.h: the peers the bake is measured against, in one place for
// bench_bake, bench_topology and geombench's bake table.
//   meshopt_adjacency:  meshoptimizer's meshopt_generateAdjacencyIndexBuffer on
//                       raw triangles (it remaps by position itself);
//   openmesh_trimesh:   an OpenMesh TriMesh built from welded triangles;
//   peak_extra_bytes:   the extra peak resident memory of one call, measured
//                       in a forked child (0 where Linux refuses).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geom/weld.h"

namespace geom_bench {

// Fills `adjacency` (6 per triangle); returns one of its entries (kept alive).
size_t meshopt_adjacency(const float* positions, size_t vertex_count, const uint32_t* indices, size_t index_count,
                         std::vector<unsigned int>& adjacency);
size_t meshopt_adjacency(const float* positions, size_t vertex_count, const uint32_t* indices, size_t index_count);

// Returns the TriMesh's face count.
size_t openmesh_trimesh(const geom::WeldResult& welded);

double peak_extra_bytes(const std::function<size_t()>& op);

}  // namespace geom_bench
