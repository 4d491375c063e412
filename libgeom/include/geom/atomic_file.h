// geom/atomic_file.h: write a whole file so that readers see either the old
// file or the complete new one, never a half-written one: the bytes go to a
// temporary file in the same directory, are flushed to disk, then renamed over
// the target. On any failure the temporary file is removed and nothing is left.
#pragma once
#include <cstddef>
#include <string>

namespace geom {

// Returns false with `error` set ("cannot create 'DIR/x.tmp': No such file or directory").
bool write_file_atomically(const std::string& path, const void* data, size_t size, std::string& error);

// The same, for a file that is the concatenation of `count` parts (written with
// one gathering writev per up to 1024 parts, no copy into one buffer).
struct FilePart {
  const void* data;
  size_t size;
};
bool write_file_atomically(const std::string& path, const FilePart* parts, size_t count, std::string& error);

inline bool write_file_atomically(const std::string& path, const std::string& text, std::string& error) {
  return write_file_atomically(path, text.data(), text.size(), error);
}

}  // namespace geom
