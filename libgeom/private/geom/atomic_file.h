// geom/atomic_file.h: write a whole file so that readers see either the old
// file or the complete new one, never a half-written one, and so that nothing
// but finished files is ever left in the target's folder.
//
// How: the bytes go to an unnamed file in the target's folder (O_TMPFILE), are
// flushed to disk, get a random name starting with kTempPrefix (linkat) and are
// renamed over the target, all in a few microseconds once the data is written.
// Where O_TMPFILE is missing the file is created under that random name with
// O_CREAT | O_EXCL | O_NOFOLLOW, so a planted file or symlink is never opened.
// The writer holds an flock() on its temporary file from before it has a name
// until after the rename, which is how remove_stale_temp_files() knows, in any
// process or container, that a temporary file's writer is gone.
// On any failure the temporary file is removed; after a SIGINT, SIGTERM or
// SIGHUP too once remove_temp_files_on_signal() is installed; after kill -9 or
// a power cut, the next remove_stale_temp_files() on that folder removes it.
#pragma once
#include <cstddef>
#include <string>

namespace geom {

// The name every temporary file starts with: DIR/.geomtmp-<16 hex digits>.
constexpr const char* kTempPrefix = ".geomtmp-";

// Returns false with `error` set ("cannot create a temporary file in 'DIR':
// No such file or directory", "'PATH' is a directory"). A target that exists
// and is neither a regular file nor a symlink (a directory, a device, a FIFO)
// is refused, never replaced. A symlink at the target is replaced, its target
// is left alone.
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

// The same in steps, for a file written piece by piece at any offsets (pwrite
// to fd()): open() makes the locked temporary file in the target's folder (the
// target checked as above), commit() flushes it and renames it over the target.
// Destroyed uncommitted (an error, an exception), the temporary file goes.
class AtomicFile {
 public:
  AtomicFile() = default;
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  bool open(const std::string& path, std::string& error);
  int fd() const { return fd_; }
  bool commit(std::string& error);

 private:
  std::string path_, dir_, name_;  // name_: the temporary file's, "" while unnamed
  int fd_ = -1, slot_ = -1;
  bool renamed_ = false;
};

// Removes the temporary files a killed writer left in `dir`: entries named
// kTempPrefix..., regular files (not symlinks) owned by this user, whose lock no
// process holds. Anything else is left alone. Returns how many were removed.
size_t remove_stale_temp_files(const std::string& dir);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the temporary
// files this process is writing, then end the process by the same signal.
// Call once, early, from a program's main thread.
void remove_temp_files_on_signal();

}  // namespace geom
