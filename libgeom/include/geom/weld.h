// geom/weld.h: merge vertices by position.
//
// Recovers the topology that UV and normal seams split: two source vertices
// with the same position become one welded vertex. tolerance == 0 compares the
// coordinates exactly (+0 and -0 are equal; a NaN coordinate never merges);
// tolerance > 0 merges a vertex into the first earlier representative within
// that Euclidean distance (greedy, in source order, so the result is
// deterministic; not transitive chains). The map back to the source is kept.
#pragma once
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

// `indices` (3 per triangle) index `positions`; out-of-range indices are a caller bug.
WeldResult weld(PositionSpan positions, const uint32_t* indices, size_t index_count, float tolerance = 0.0f);

}  // namespace geom
