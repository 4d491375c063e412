// file_kind.h (private): what a file that is not a regular one is, in the
// words of the error messages (import.cpp, atomic_file.cpp).
#pragma once
#include <sys/stat.h>

#include <string>

namespace geom::detail {

inline std::string file_kind(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

}  // namespace geom::detail
