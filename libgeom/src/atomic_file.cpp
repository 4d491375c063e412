// Atomic whole-file writes (geom/atomic_file.h): an unnamed (O_TMPFILE) or
// exclusively created temporary file under a random name, locked, flushed,
// renamed over the target; stale temporary files found by their free lock.
#include "geom/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

#include "file_kind.h"

namespace geom {
namespace {

// The temporary files this process has given a name and not yet renamed, for
// the signal handler (which may only call async-signal-safe functions).
constexpr int kSlots = 256;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a path
  char path[4096];
};
Slot g_slots[kSlots];

int claim_slot(const std::string& path) {
  if (path.size() >= sizeof(Slot::path)) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2);
      return i;
    }
  }
  return -1;  // more writers at once than slots: this one is not removed on a signal
}
void release_slot(int i) {
  if (i >= 0) g_slots[i].state.store(0);
}

// A temporary name being created (its slot claimed, the file not yet made or
// linked) by how many threads; after a fatal signal none starts (g_dying).
// The handler waits for those under way before it removes the named files, so
// a file made while it runs cannot outlive the process; a creating thread
// blocks the fatal signals meanwhile, so the handler never runs on it.
std::atomic<int> g_creating{0};
std::atomic<int> g_dying{0};

// Blocks the fatal signals in this thread and counts it as creating; false
// (nothing to undo but the mask: end() still) if the process is dying.
struct Creating {
  sigset_t old;
  bool ok = false;
  Creating() {
    sigset_t fatal;
    sigemptyset(&fatal);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&fatal, sig);
    pthread_sigmask(SIG_BLOCK, &fatal, &old);
    g_creating.fetch_add(1);
    ok = g_dying.load() == 0;
  }
  ~Creating() {
    g_creating.fetch_sub(1);
    pthread_sigmask(SIG_SETMASK, &old, nullptr);
  }
};

extern "C" void on_fatal_signal(int sig) {
  g_dying.store(1);
  for (long spin = 0; g_creating.load() > 0 && spin < 2000000000L; ++spin) {
  }
  for (Slot& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

std::string random_name(const std::string& dir) {
  unsigned char b[8];
  if (::getrandom(b, sizeof b, GRND_NONBLOCK) != ssize_t(sizeof b)) {
    std::random_device rd;
    for (unsigned char& c : b) c = static_cast<unsigned char>(rd());
  }
  char hex[17];
  for (int i = 0; i < 8; ++i) std::snprintf(hex + 2 * i, 3, "%02x", b[i]);
  return dir + "/" + kTempPrefix + hex;
}

// Writes the parts in order, gathered in batches of at most kBatch iovecs (no
// copy into one buffer); a short write resumes inside the part where it stopped.
bool write_parts(int fd, const FilePart* parts, size_t count) {
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
      if (w == 0) errno = EIO;
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
  return true;
}

// Creates a locked temporary file in `dir`: unnamed if it can (name left
// empty), else under a fresh random name, its signal slot in `slot` (kept:
// no moment when the named file is in no slot). -1 with errno set on failure.
int create_temp(const std::string& dir, std::string& name, int& slot_out) {
  name.clear();
  slot_out = -1;
  static const bool no_tmpfile = std::getenv("GEOM_NO_O_TMPFILE") != nullptr;  // tests the fallback
  if (!no_tmpfile) {
    int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
    if (fd >= 0) {
      if (::flock(fd, LOCK_EX) == 0) return fd;
      ::close(fd);
    } else if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) {
      return -1;  // the folder itself is the problem (missing, read-only, not ours)
    }
  }
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string candidate = random_name(dir);
    const Creating creating;
    if (!creating.ok) {
      errno = EINTR;
      return -1;
    }
    int slot = claim_slot(candidate);
    int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) {
      release_slot(slot);
      if (errno == EEXIST) continue;
      return -1;
    }
    // Locked, and still ours under that name (a sweeper may have taken it
    // between the open and the lock): else try another name.
    struct stat a, b;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::fstat(fd, &a) == 0 && ::lstat(candidate.c_str(), &b) == 0 &&
        a.st_dev == b.st_dev && a.st_ino == b.st_ino) {
      name = candidate;
      slot_out = slot;
      return fd;
    }
    ::close(fd);
    release_slot(slot);
  }
  errno = EEXIST;
  return -1;
}

}  // namespace

bool write_file_atomically(const std::string& path, const void* data, size_t size, std::string& error) {
  const FilePart part{data, size};
  return write_file_atomically(path, &part, 1, error);
}

AtomicFile::~AtomicFile() {
  if (!renamed_ && !name_.empty()) ::unlink(name_.c_str());
  release_slot(slot_);
  if (fd_ >= 0) ::close(fd_);  // the lock goes with it, after the rename
}

bool AtomicFile::open(const std::string& path, std::string& error) {
  if (path.empty()) {
    error = "the output path is empty";
    return false;
  }
  if (path.back() == '/') {
    error = "'" + path + "' names a directory, not a file";
    return false;
  }
  struct stat st;
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode)) {
    error = "'" + path + "' is " + detail::file_kind(st.st_mode) + ", not a regular file: not replaced";
    return false;
  }
  const size_t slash = path.find_last_of('/');
  path_ = path;
  dir_ = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  fd_ = create_temp(dir_, name_, slot_);
  if (fd_ < 0) {
    error = "cannot create a temporary file in '" + dir_ + "': " + std::strerror(errno);
    return false;
  }
  return true;
}

bool AtomicFile::commit(std::string& error) {
  auto fail = [&](const std::string& what) {
    error = what + ": " + std::strerror(errno);
    return false;
  };
  if (fd_ < 0) {
    errno = EBADF;
    return fail("cannot write '" + path_ + "'");
  }
  if (::fsync(fd_) != 0) return fail("cannot flush '" + path_ + "'");
  if (name_.empty()) {  // give the unnamed file a random name, then rename it
    const std::string proc = "/proc/self/fd/" + std::to_string(fd_);
    for (int attempt = 0; attempt < 100 && name_.empty(); ++attempt) {
      std::string candidate = random_name(dir_);
      const Creating creating;
      if (!creating.ok) {
        errno = EINTR;
        return fail("cannot name the temporary file in '" + dir_ + "'");
      }
      slot_ = claim_slot(candidate);
      if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, candidate.c_str(), AT_SYMLINK_FOLLOW) == 0) {
        name_ = candidate;
      } else {
        const int e = errno;
        release_slot(slot_);
        slot_ = -1;
        if (e != EEXIST) {
          errno = e;
          return fail("cannot name the temporary file in '" + dir_ + "'");
        }
      }
    }
    if (name_.empty()) return fail("cannot name the temporary file in '" + dir_ + "'");
  }
  if (std::rename(name_.c_str(), path_.c_str()) != 0)
    return fail("cannot rename the temporary file to '" + path_ + "'");
  renamed_ = true;
  int dfd = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);  // the rename itself on disk; best effort
    ::close(dfd);
  }
  return true;
}

bool write_file_atomically(const std::string& path, const FilePart* parts, size_t count, std::string& error) {
  AtomicFile file;
  if (!file.open(path, error)) return false;
  if (!write_parts(file.fd(), parts, count)) {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    return false;
  }
  return file.commit(error);
}

size_t remove_stale_temp_files(const std::string& dir) {
  int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return 0;
  DIR* d = ::fdopendir(dfd);
  if (!d) {
    ::close(dfd);
    return 0;
  }
  size_t removed = 0;
  const size_t prefix = std::strlen(kTempPrefix);
  while (struct dirent* e = ::readdir(d)) {
    if (std::strncmp(e->d_name, kTempPrefix, prefix) != 0) continue;
    int fd = ::openat(dfd, e->d_name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;  // a symlink (ELOOP) or unreadable: not provably ours
    struct stat a, b;
    if (::fstat(fd, &a) == 0 && S_ISREG(a.st_mode) && a.st_uid == ::geteuid() &&
        ::flock(fd, LOCK_EX | LOCK_NB) == 0 &&  // no writer holds it: its writer is gone
        ::fstatat(dfd, e->d_name, &b, AT_SYMLINK_NOFOLLOW) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino &&
        ::unlinkat(dfd, e->d_name, 0) == 0)
      ++removed;
    ::close(fd);
  }
  ::closedir(d);
  return removed;
}

void remove_temp_files_on_signal() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old;
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // nohup: stay ignored
    ::sigaction(sig, &sa, nullptr);
  }
}

}  // namespace geom
