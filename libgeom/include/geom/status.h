// geom/status.h: the library's one error style for untrusted data.
//
// Every entry point that takes data the caller cannot vouch for (a file, a
// triangle soup from outside) returns a Status or a result derived from it:
// `ok`, an ErrorCode a program can branch on, and `error`, one line for people
// of the form "NAME: what is wrong" (NAME: the file, or the name the caller
// gave). Nothing is thrown across the library's boundary for such data.
//
// Caller bugs on the trusted fast paths (an index out of range handed to
// weld or build_topology, an output buffer smaller than its *_bound) are not
// errors but broken preconditions: asserted, with the function's name in the
// message, in builds without NDEBUG (Debug, the sanitizer build), and not
// checked in release builds. validate_triangles (geom/validate.h) is the
// check to run first on untrusted triangles.
#pragma once
#include <cstdint>
#include <string>

namespace geom {

enum class ErrorCode : uint8_t {
  None = 0,         // success (ok is true)
  Malformed,        // the data break their format's rules (a file's syntax, a section's layout, an unknown type)
  IndexCount,       // an index count that is not a multiple of 3
  IndexOutOfRange,  // an index at or past the vertex count
  NonFinite,        // a NaN or infinite coordinate (a position, a light)
  TooLarge,         // counts past what 32-bit indices address, sizes that overflow, a caller's limit
  OutOfMemory,      // an allocation failed
  Io,               // a file could not be read or written
};

// "none", "malformed", "index_count", "index_out_of_range", "non_finite",
// "too_large", "out_of_memory", "io": stable names for logs and JSON.
const char* error_code_name(ErrorCode code);

struct Status {
  bool ok = false;
  ErrorCode code = ErrorCode::None;  // None exactly when ok
  std::string error;                 // "NAME: what is wrong" when !ok
};

}  // namespace geom
