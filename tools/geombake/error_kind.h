// The class of an input's error, for pipelines that act on it without parsing
// English: the report's and --json's "error_kind". The list is fixed (a new
// kind is a new release, docs/build-step.md lists them):
//   not_found        the input (or a file it names, a glTF buffer) does not exist
//   not_regular      the input is a directory, device, FIFO or socket
//   unreadable       it exists but cannot be read (permissions, I/O error)
//   malformed        its bytes are not a valid file of its format
//   unsupported      a valid file of a kind or version the importers do not read
//   limit_triangles  more triangles than --max-triangles
//   limit_memory     more memory than --max-memory (or than the machine has)
//   timeout          longer than --timeout
//   write_failed     its output could not be written (or the stale one removed)
//   output_conflict  its output is also another input's output
#pragma once
#include <string>

namespace geombake {

enum class ErrorKind {
  None,
  NotFound,
  NotRegular,
  Unreadable,
  Malformed,
  Unsupported,
  LimitTriangles,
  LimitMemory,
  Timeout,
  WriteFailed,
  OutputConflict,
};

// "not_found", ...; "" for None.
const char* error_kind_name(ErrorKind kind);

// The kind of an import's `error` ("FILE: cause") for `input`: what the file
// system says of the input's files first (missing, not regular, unreadable),
// then the limits and the unsupported kinds the importers name, else malformed.
ErrorKind classify_import_error(const std::string& input, const std::string& error);

}  // namespace geombake
