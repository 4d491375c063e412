// libgeom's one whole-file read (file_read.h).
#include "file_read.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "file_kind.h"

namespace geom::detail {

uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

namespace {

// The checks and the read of read_whole_file into the memory `place(size)` gives (null: none).
template <class Place>
bool read_into(const std::string& path, uint64_t max_bytes, std::string& error, Place place) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    error = std::string("cannot open file: ") + std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = file_kind(st.st_mode) + ", not a regular file: not read";
    return false;
  }
  int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    error = std::string("cannot open file: ") + std::strerror(errno);
    return false;
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    error = "not a regular file: not read";
    return false;
  }
  const uint64_t size = uint64_t(st.st_size);
  if (max_bytes && size > max_bytes) {
    error = "file is " + std::to_string(size) + " bytes, over the limit of " + std::to_string(max_bytes);
    return false;
  }
  const uint64_t memory = physical_memory_bytes();
  if (memory && size > memory) {
    error = "file is " + std::to_string(size) + " bytes, more than this machine's memory (" + std::to_string(memory) +
            " bytes)";
    return false;
  }
  unsigned char* at = place(size_t(size));
  if (!at && size) {
    error = "out of memory reading " + std::to_string(size) + " bytes";
    return false;
  }
  size_t got = 0;
  while (got < size) {
    ssize_t n = ::read(fd, at + got, std::min<size_t>(size - got, size_t(1) << 30));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += size_t(n);
  }
  if (got != size) {
    error = "cannot read file (it shrank while being read?)";
    return false;
  }
  return true;
}

}  // namespace

bool read_whole_file(const std::string& path, std::vector<unsigned char>& bytes, uint64_t max_bytes,
                     std::string& error) {
  return read_into(path, max_bytes, error, [&](size_t size) {
    bytes.resize(size);
    return bytes.data();
  });
}

FileBytes::~FileBytes() { clear(); }

void FileBytes::clear() {
  if (map_) ::munmap(map_, map_size_);
  map_ = nullptr, map_size_ = 0;
  heap_.clear();
  heap_.shrink_to_fit();
  data_ = nullptr, size_ = 0;
}

bool FileBytes::place(size_t size) {
  clear();
  size_ = size;
  if (size >= kMapAt) {
    // Populated at once (one call, not a fault per page): every byte is about to be read into.
    void* m = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (m == MAP_FAILED) return false;
    map_ = m, map_size_ = size;
    data_ = static_cast<unsigned char*>(m);
  } else {
    heap_.resize(size);
    data_ = heap_.data();
  }
  return true;
}

bool read_whole_file(const std::string& path, FileBytes& bytes, uint64_t max_bytes, std::string& error) {
  return read_into(path, max_bytes, error,
                   [&](size_t size) { return bytes.place(size) ? const_cast<unsigned char*>(bytes.data()) : nullptr; });
}

}  // namespace geom::detail
