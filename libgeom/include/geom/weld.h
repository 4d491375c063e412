// geom/weld.h: merge vertices by position.
//
// Recovers the topology that UV and normal seams split: two source vertices
// with the same position become one welded vertex. tolerance == 0 compares the
// coordinates exactly (+0 and -0 are equal; a NaN coordinate never merges);
// tolerance > 0 merges a vertex into the first earlier representative within
// that Euclidean distance (greedy, in source order, so the result is
// deterministic; not transitive chains). The map back to the source is kept.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geom/span.h"

namespace geom {

struct WeldResult {
  std::vector<float> positions;   // xyz per welded vertex (its first source vertex's position)
  std::vector<uint32_t> remap;    // per source vertex: its welded vertex
  std::vector<uint32_t> indices;  // the input indices, remapped
  size_t vertex_count() const { return positions.size() / 3; }
};

// The most welded vertices a weld of `vertex_count` vertices makes (every
// vertex its own): the caller-owned output below takes 3 * weld_bound floats
// of positions.
inline size_t weld_bound(size_t vertex_count) { return vertex_count; }

// `indices` (3 per triangle) index `positions`. Precondition: every index <
// positions.size() (asserted, with this function's name, where NDEBUG is not
// defined; untrusted data: geom/validate.h first).
WeldResult weld(PositionSpan positions, const uint32_t* indices, size_t index_count, float tolerance = 0.0f);

// The same weld into caller-owned memory (meshoptimizer's style): writes the
// welded positions to `out_positions` (room for 3 * weld_bound(positions.size())
// floats), the remap to `out_remap` (positions.size()) and the remapped
// indices to `out_indices` (index_count; it may be `indices` itself), and
// returns the welded vertex count. The same bytes as weld's vectors. Scratch:
// a hash table of 2 to 4 uint32 per vertex (exact), a grid (tolerance).
size_t weld(float* out_positions, uint32_t* out_remap, uint32_t* out_indices, PositionSpan positions,
            const uint32_t* indices, size_t index_count, float tolerance = 0.0f);

}  // namespace geom
