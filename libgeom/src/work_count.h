// Private: a per-thread count of the elementary steps of the stages whose cost
// could grow with vertex valences or edge face counts (topology's edge grouping
// and duplicate search, the half-edge summary on either path, adjacency), so a
// test can hold them linear by counting work at two sizes instead of timing.
// A step is one loop iteration or one comparison; OpenMesh's add_face is
// counted as the faces already around its three vertices (what its searches
// walk). One add per stage or per bucket: no cost on the hot loops.
#pragma once
#include <cstdint>

namespace geom::detail {

inline thread_local uint64_t work_steps = 0;

inline void count_work(uint64_t steps) { work_steps += steps; }

}  // namespace geom::detail
