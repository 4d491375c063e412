// geom/validate.h: the check of an untrusted triangle soup before the core
// runs on it ("safe to use for untrusted input" is this function, then the
// pipeline; the core's own functions assert their preconditions instead).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "geom/span.h"
#include "geom/status.h"

namespace geom {

// The most triangles the core takes: every face slot (3 per triangle) is
// addressed by a uint32 with one value kept for "none" (geom/topology.h).
constexpr size_t kMaxTriangles = (size_t(0xffffffffu) - 1) / 3;
// The most vertices: welded vertex ids are uint32, 0xffffffff means "none".
constexpr size_t kMaxVertices = size_t(0xffffffffu) - 1;

// Checks, in this order, and returns the first failure as a Status whose
// error is "NAME: what is wrong" (NAME = `name`):
//   Malformed        positions or indices null while their count is not 0
//   IndexCount       index_count not a multiple of 3
//   TooLarge         more than kMaxTriangles triangles or kMaxVertices
//                    vertices, or a position span whose last byte
//                    (stride * (count - 1) + 12) overflows
//   IndexOutOfRange  "triangle T uses vertex V, out of range (N vertices)"
//   NonFinite        "triangle T uses vertex V with a non-finite coordinate"
//                    (a vertex no triangle uses may hold anything)
// On success {ok = true, ErrorCode::None, ""}: weld (geom/weld.h),
// build_topology and run_pipeline (geom/pipeline.h) may then run on the same
// data with no precondition broken. Reads every index once and every vertex
// at most once; allocates nothing (but the message).
Status validate_triangles(PositionSpan positions, const uint32_t* indices, size_t index_count,
                          const std::string& name = "triangles");

}  // namespace geom
