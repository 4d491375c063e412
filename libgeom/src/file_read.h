// Private: libgeom's one whole-file read, used by every reader of the library
// (import_file, input_dependencies, a glTF's external buffers; archive members
// are read through libzip, archive.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace geom::detail {

// Reads a regular file whole. Anything else (a FIFO, a device, a directory) is
// refused by name before it is opened, and again by its descriptor after (it
// may have been swapped in between); a file larger than max_bytes (0 = no
// limit), or than this machine's memory, is refused before anything is
// allocated. False with `error` saying what is wrong (no file name: the caller
// prefixes it, "FILE: what is wrong").
bool read_whole_file(const std::string& path, std::vector<unsigned char>& bytes, uint64_t max_bytes,
                     std::string& error);

// A file's bytes; from kMapAt bytes on in a mapping of their own, not in the
// heap: once freed their pages go back to the system at once instead of
// leaving a hole in a kept heap (geom/bake.h keep_memory_across_bakes) that
// the bake's larger buffers do not fit in but that stays resident through its
// peak.
class FileBytes {
 public:
  static constexpr size_t kMapAt = size_t(1) << 20;
  FileBytes() = default;
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  const unsigned char* data() const { return data_; }
  size_t size() const { return size_; }
  void clear();
  bool place(size_t size);  // `size` bytes to fill (their old contents gone); false: no memory

 private:
  std::vector<unsigned char> heap_;
  void* map_ = nullptr;
  size_t map_size_ = 0;
  unsigned char* data_ = nullptr;
  size_t size_ = 0;
};
bool read_whole_file(const std::string& path, FileBytes& bytes, uint64_t max_bytes, std::string& error);

// This machine's physical memory in bytes (0 if unknown): no input or archive
// member larger than it is read.
uint64_t physical_memory_bytes();

}  // namespace geom::detail
