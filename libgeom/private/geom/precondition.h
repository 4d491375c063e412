// geom/precondition.h (private): preconditions of the trusted fast paths.
//
// GEOM_PRECONDITION(cond, message) checks a caller's promise (an index in
// range, a buffer as large as its *_bound, a topology of these triangles) in
// builds without NDEBUG (Debug and the sanitizer build): when it fails it
// prints "geom::FUNCTION: message" to stderr and aborts. `message` is a
// std::string expression built only when the check fails. With NDEBUG
// (Release) GEOM_PRECONDITIONS is 0 and neither is evaluated: the condition is
// still compiled, so it cannot rot, and then dropped as dead code.
// Untrusted data is checked by validate_triangles (geom/validate.h), which
// returns a Status instead.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#ifndef GEOM_PRECONDITIONS
#ifdef NDEBUG
#define GEOM_PRECONDITIONS 0
#else
#define GEOM_PRECONDITIONS 1
#endif
#endif

namespace geom::detail {
// Prints "geom::FUNCTION: MESSAGE" and a newline to stderr, then aborts.
[[noreturn]] void precondition_failed(const char* function, const std::string& message);

// The first of `count` indices at or past `vertex_count`, or `count`.
inline size_t first_out_of_range(const uint32_t* indices, size_t count, size_t vertex_count) {
  size_t i = 0;
  while (i < count && indices[i] < vertex_count) ++i;
  return i;
}
// "indices[I] = V, expected < N (the vertex count)".
inline std::string out_of_range_message(const uint32_t* indices, size_t i, size_t vertex_count) {
  return "indices[" + std::to_string(i) + "] = " + std::to_string(indices[i]) + ", expected < " +
         std::to_string(vertex_count) + " (the vertex count)";
}
}  // namespace geom::detail

// Precondition: each of the `count` indices < `vertex_count` (one pass over
// them, only where preconditions are checked).
#define GEOM_PRECONDITION_INDICES(indices, count, vertex_count)                                        \
  do {                                                                                                 \
    if (GEOM_PRECONDITIONS) {                                                                          \
      const size_t geom_bad_ = ::geom::detail::first_out_of_range((indices), (count), (vertex_count)); \
      if (geom_bad_ != size_t(count))                                                                  \
        ::geom::detail::precondition_failed(                                                           \
            __func__, ::geom::detail::out_of_range_message((indices), geom_bad_, (vertex_count)));     \
    }                                                                                                  \
  } while (0)

#define GEOM_PRECONDITION(cond, message)                                                         \
  do {                                                                                           \
    if (GEOM_PRECONDITIONS && !(cond)) ::geom::detail::precondition_failed(__func__, (message)); \
  } while (0)
