// The check of an untrusted triangle soup (geom/validate.h): counts, sizes,
// index ranges, then finite coordinates of the vertices triangles use.
#include "geom/validate.h"

#include <cmath>
#include <limits>

namespace geom {
namespace {

Status failure(ErrorCode code, const std::string& name, const std::string& what) {
  Status s;
  s.code = code;
  s.error = name + ": " + what;
  return s;
}

inline bool finite(const Float3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

}  // namespace

Status validate_triangles(PositionSpan positions, const uint32_t* indices, size_t index_count,
                          const std::string& name) {
  const size_t vc = positions.size();
  if ((!positions.data && vc != 0) || (!indices && index_count != 0))
    return failure(ErrorCode::Malformed, name,
                   std::string(!indices && index_count ? "indices" : "positions") + " are null with a count of " +
                       std::to_string(!indices && index_count ? index_count : vc));
  if (index_count % 3 != 0)
    return failure(ErrorCode::IndexCount, name,
                   std::to_string(index_count) + " indices, not a multiple of 3 (3 per triangle)");
  const size_t tc = index_count / 3;
  if (tc > kMaxTriangles)
    return failure(
        ErrorCode::TooLarge, name,
        std::to_string(tc) + " triangles, over the most the core takes (" + std::to_string(kMaxTriangles) + ")");
  if (vc > kMaxVertices)
    return failure(
        ErrorCode::TooLarge, name,
        std::to_string(vc) + " vertices, over the most the core takes (" + std::to_string(kMaxVertices) + ")");
  const size_t max = std::numeric_limits<size_t>::max();
  if (vc > 1 && positions.stride > (max - sizeof(Float3)) / (vc - 1))
    return failure(ErrorCode::TooLarge, name,
                   std::to_string(vc) + " vertices " + std::to_string(positions.stride) +
                       " bytes apart: the span's size overflows");
  for (size_t i = 0; i < index_count; ++i)
    if (indices[i] >= vc)
      return failure(ErrorCode::IndexOutOfRange, name,
                     "triangle " + std::to_string(i / 3) + " uses vertex " + std::to_string(indices[i]) +
                         ", out of range (" + std::to_string(vc) + " vertices)");
  bool all_finite = true;  // then no triangle uses a non-finite vertex: one pass over the vertices, not the corners
  for (size_t v = 0; v < vc && all_finite; ++v) all_finite = finite(positions[v]);
  for (size_t i = 0; !all_finite && i < index_count; ++i)
    if (!finite(positions[indices[i]]))
      return failure(ErrorCode::NonFinite, name,
                     "triangle " + std::to_string(i / 3) + " uses vertex " + std::to_string(indices[i]) +
                         " with a non-finite coordinate");
  Status ok;
  ok.ok = true;
  return ok;
}

}  // namespace geom
