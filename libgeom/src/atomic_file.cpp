// Atomic whole-file writes (geom/atomic_file.h): temp file, fsync, rename.
#include "geom/atomic_file.h"

#include <fcntl.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace geom {

bool write_file_atomically(const std::string& path, const void* data, size_t size, std::string& error) {
  const FilePart part{data, size};
  return write_file_atomically(path, &part, 1, error);
}

bool write_file_atomically(const std::string& path, const FilePart* parts, size_t count, std::string& error) {
  std::string tmp = path + ".tmp" + std::to_string(::getpid());
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = "cannot create '" + tmp + "': " + std::strerror(errno);
    return false;
  }
  // Gather the parts in batches of at most kBatch iovecs; a short write
  // resumes inside the part where it stopped.
  constexpr size_t kBatch = 1024;
  iovec iov[kBatch];
  size_t next = 0, skip = 0;  // the first part not yet fully written, and its bytes already written
  while (next < count) {
    size_t n = 0;
    for (size_t i = next; i < count && n < kBatch; ++i) {
      const size_t off = i == next ? skip : 0;
      if (parts[i].size == off) continue;
      iov[n].iov_base = const_cast<char*>(static_cast<const char*>(parts[i].data) + off);
      iov[n].iov_len = parts[i].size - off;
      ++n;
    }
    if (n == 0) break;
    ssize_t w = ::writev(fd, iov, int(n));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      error = "cannot write '" + tmp + "': " + std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      return false;
    }
    size_t done = size_t(w);
    while (next < count && done >= parts[next].size - skip) {
      done -= parts[next].size - skip;
      skip = 0;
      ++next;
    }
    skip += done;
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    error = "cannot flush '" + tmp + "': " + std::strerror(errno);
    ::unlink(tmp.c_str());
    return false;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = "cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(errno);
    ::unlink(tmp.c_str());
    return false;
  }
  return true;
}

}  // namespace geom
