// geom/baked_file.h: a baked file read into memory or mapped, then validated
// by geom/baked_reader.h's Reader. C++17 standard library (<filesystem>,
// <cstdio>) and, for File::map(), POSIX mmap where it exists: an engine that
// reads the bytes its own way includes geom/baked_reader.h alone.
#pragma once
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "geom/baked_reader.h"

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define GEOM_BAKED_READER_HAS_MMAP 1
#else
#define GEOM_BAKED_READER_HAS_MMAP 0
#endif

namespace geom {
namespace baked {

namespace detail {
// read_baked_file(): a regular file, its first 64 bytes checked first.
inline bool read_regular_file(const std::string& path, std::vector<unsigned char>& bytes, std::string& error,
                              uint64_t max_bytes) {
  bytes.clear();
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) {
    error = "cannot open file";
    return false;
  }
  if (!std::filesystem::is_regular_file(st)) {
    error = "not a regular file (a directory, FIFO or device): not read";
    return false;
  }
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) {
    error = "cannot read file";
    return false;
  }
  if (size > max_bytes) {
    error = "file is " + std::to_string(size) + " bytes, over the limit of " + std::to_string(max_bytes);
    return false;
  }
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    error = "cannot open file";
    return false;
  }
  unsigned char head[kHeaderSize];
  const size_t got_head = std::fread(head, 1, sizeof head, f);
  std::string problem;
  if (got_head == 0)
    problem = "empty file, not a geombake baked file";
  else if (std::memcmp(head, kMagic, got_head < 8 ? got_head : 8) != 0)
    problem = "not a geombake baked file (bad magic)";
  else if (got_head >= 40 && detail::load_u64(head + 32) != size)
    problem = "the header says " + std::to_string(detail::load_u64(head + 32)) + " bytes, the file has " +
              std::to_string(size) + " (truncated or not a baked file)";
  if (!problem.empty()) {
    std::fclose(f);
    error = problem;
    return false;
  }
  bytes.resize(size_t(size));
  if (got_head) std::memcpy(bytes.data(), head, got_head);  // an empty file: bytes.data() may be null
  size_t got = got_head + (size > got_head ? std::fread(bytes.data() + got_head, 1, bytes.size() - got_head, f) : 0);
  std::fclose(f);
  if (got != bytes.size()) {
    bytes.clear();
    error = "cannot read file";
    return false;
  }
  return true;
}
}  // namespace detail

// Reads a whole baked file into `bytes` (refusing files over max_bytes); false
// with `error` ("cannot open file", ...) on failure. Only a regular file is
// opened: a FIFO, a device or a directory is refused by name. Its first 64
// bytes are read and checked (magic, and the file size its header gives)
// before the rest is allocated and read, so an 8 GB file that is not baked
// costs 64 bytes.
inline bool read_baked_file(const std::string& path, std::vector<unsigned char>& bytes, std::string& error,
                            uint64_t max_bytes = uint64_t(1) << 34) {
  return detail::read_regular_file(path, bytes, error, max_bytes);
}

// A baked file loaded into memory (or mapped) and validated: owns the bytes, views them.
//   geom::baked::File f;
//   if (!f.load("mesh.gbake")) { puts(f.error().c_str()); return; }
//   const geom::baked::Section* pos = f.reader().find(geom::baked::SectionType::Positions);
//   glBufferData(GL_ARRAY_BUFFER, pos->size, pos->data, GL_STATIC_DRAW);
class File {
 public:
  // Reads the file (read_baked_file) and validates it. error() is "PATH: what is wrong" on failure.
  bool load(const std::string& path) {
    release();
    std::string error;
    if (!read_baked_file(path, bytes_, error)) {
      error_ = path + ": " + error;
      return false;
    }
    return validate(path, bytes_.data(), bytes_.size());
  }
#if GEOM_BAKED_READER_HAS_MMAP
  // As load(), but maps the file read-only instead of copying it (POSIX only:
  // the one place this header uses more than the C++ standard library). The
  // file must not be truncated while it is mapped.
  bool map(const std::string& path) {
    release();
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    struct stat st;
    if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      if (fd >= 0) ::close(fd);
      error_ = path + (fd < 0 ? ": cannot open file" : ": not a regular file (a directory, FIFO or device): not read");
      return false;
    }
    const size_t size = size_t(st.st_size);
    void* m = size ? ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0) : MAP_FAILED;
    ::close(fd);
    if (m == MAP_FAILED) {
      error_ = path + (size ? ": cannot map file" : ": empty file, not a geombake baked file");
      return false;
    }
    map_ = static_cast<const unsigned char*>(m);
    map_size_ = size;
    return validate(path, map_, map_size_);
  }
#endif
  const std::string& error() const { return error_; }
  const Reader& reader() const { return reader_; }
  // The bytes of a load()ed file (empty after map(): use data() and size()).
  const std::vector<unsigned char>& bytes() const { return bytes_; }
  const unsigned char* data() const { return map_ ? map_ : bytes_.data(); }
  size_t size() const { return map_ ? map_size_ : bytes_.size(); }

 private:
  bool validate(const std::string& path, const unsigned char* data, size_t size) {
    if (!reader_.open(data, size)) {
      error_ = path + ": " + reader_.error();
      release();
      return false;
    }
    error_.clear();
    return true;
  }
  void release() {
#if GEOM_BAKED_READER_HAS_MMAP
    if (map_) ::munmap(const_cast<unsigned char*>(map_), map_size_);
#endif
    map_ = nullptr;
    map_size_ = 0;
    bytes_.clear();
  }
  std::vector<unsigned char> bytes_;  // moved-from or copied File objects would dangle: not copyable
  const unsigned char* map_ = nullptr;
  size_t map_size_ = 0;
  Reader reader_;
  std::string error_;

 public:
  File() = default;
  ~File() { release(); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
};

}  // namespace baked
}  // namespace geom
