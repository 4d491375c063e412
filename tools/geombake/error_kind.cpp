// Error kinds (error_kind.h).
#include "geombake/error_kind.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "geom/import.h"

namespace geombake {

const char* error_kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::None:
      return "";
    case ErrorKind::NotFound:
      return "not_found";
    case ErrorKind::NotRegular:
      return "not_regular";
    case ErrorKind::Unreadable:
      return "unreadable";
    case ErrorKind::Malformed:
      return "malformed";
    case ErrorKind::Unsupported:
      return "unsupported";
    case ErrorKind::LimitTriangles:
      return "limit_triangles";
    case ErrorKind::LimitMemory:
      return "limit_memory";
    case ErrorKind::Timeout:
      return "timeout";
    case ErrorKind::WriteFailed:
      return "write_failed";
    case ErrorKind::OutputConflict:
      return "output_conflict";
  }
  return "";
}

namespace {

bool has(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }

// What the file system says of `path`: None if it is a readable regular file.
ErrorKind file_kind(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return errno == ENOENT || errno == ENOTDIR ? ErrorKind::NotFound : ErrorKind::Unreadable;
  if (!S_ISREG(st.st_mode)) return ErrorKind::NotRegular;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return ErrorKind::Unreadable;
  ::close(fd);
  return ErrorKind::None;
}

}  // namespace

ErrorKind classify_import_error(const std::string& input, const std::string& error) {
  for (const std::string& file : geom::input_dependencies(input)) {
    const ErrorKind k = file_kind(file);
    if (k != ErrorKind::None) return k;
  }
  if (has(error, "triangles, over the limit of")) return ErrorKind::LimitTriangles;
  if (has(error, "(--max-memory)") || has(error, "bytes, over the limit of")) return ErrorKind::LimitMemory;
  if (has(error, "not supported") || has(error, "unsupported") || has(error, "unknown file type") ||
      has(error, "no .bsp map inside") || has(error, "an archive: name a member"))
    return ErrorKind::Unsupported;
  return ErrorKind::Malformed;
}

}  // namespace geombake
