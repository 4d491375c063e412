// The error codes' names (geom/status.h) and the report of a broken
// precondition (geom/precondition.h).
#include "geom/status.h"

#include <cstdio>
#include <cstdlib>

#include "geom/precondition.h"

namespace geom {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::None:
      return "none";
    case ErrorCode::Malformed:
      return "malformed";
    case ErrorCode::IndexCount:
      return "index_count";
    case ErrorCode::IndexOutOfRange:
      return "index_out_of_range";
    case ErrorCode::NonFinite:
      return "non_finite";
    case ErrorCode::TooLarge:
      return "too_large";
    case ErrorCode::OutOfMemory:
      return "out_of_memory";
    case ErrorCode::Io:
      return "io";
  }
  return "unknown";
}

namespace detail {

void precondition_failed(const char* function, const std::string& message) {
  std::fprintf(stderr, "geom::%s: %s\n", function, message.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace detail
}  // namespace geom
