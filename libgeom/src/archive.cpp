// Zip (.pk3) archive access through libzip (Debian's libzip-dev): Quake 3 data
// ships as zip archives, and a maintained library reads them better than we would.
#include <sys/stat.h>
#include <zip.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>

#include "file_read.h"
#include "geom/import.h"

namespace geom::detail {
namespace {

struct ZipCloser {
  zip_t* z;
  ~ZipCloser() {
    if (z) zip_discard(z);
  }
};

// zip_open on a FIFO would block, on a device read forever: regular files only.
bool regular_archive(const std::string& archive, struct stat& st, std::string& error) {
  if (::stat(archive.c_str(), &st) != 0) {
    error = "cannot open archive '" + archive + "': " + std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = "archive '" + archive + "' is not a regular file: not read";
    return false;
  }
  return true;
}

zip_t* open_archive(const std::string& archive, std::string& error) {
  struct stat st;
  if (!regular_archive(archive, st, error)) return nullptr;
  int code = 0;
  zip_t* z = zip_open(archive.c_str(), ZIP_RDONLY, &code);
  if (!z) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, code);
    error = "cannot open archive '" + archive + "': " + zip_error_strerror(&ze);
    zip_error_fini(&ze);
  }
  return z;
}

bool ends_with_nocase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                    [](char a, char b) { return std::tolower((unsigned char)a) == std::tolower((unsigned char)b); });
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Open archives, kept between reads so that N members of one archive cost one
// parse of its central directory, not N (N inputs from one .pk3 were O(N^2)).
// An entry is reopened when the file changes (device, inode, size or mtime).
// A zip_t serves one reader at a time, so an entry keeps a pool of handles on
// the file: each read takes a free one (or opens one more) and inflates
// outside any lock, so the threads of a batch over one .pk3 decompress its
// members at once (with one handle under a lock, -j 2 over OpenArena's 50
// maps ran at 1.5x -j 1: half the time is inflating).
struct OpenArchive {
  std::mutex mutex;          // guards `free`
  std::vector<zip_t*> free;  // handles no reader holds
  std::string path;
  struct stat st {};
  std::unordered_map<std::string, zip_uint64_t> by_lower_name;  // case-insensitive lookup, O(1); read-only once made
  ~OpenArchive() {
    for (zip_t* z : free) zip_discard(z);
  }
};
// One handle of an entry's pool, given back when the read is done.
struct PooledHandle {
  std::shared_ptr<OpenArchive> archive;
  zip_t* z = nullptr;
  ~PooledHandle() {
    if (!z) return;
    std::lock_guard<std::mutex> lock(archive->mutex);
    archive->free.push_back(z);
  }
};
std::mutex g_cache_mutex;
std::map<std::string, std::shared_ptr<OpenArchive>> g_cache;

std::shared_ptr<OpenArchive> cached_archive(const std::string& archive, std::string& error) {
  struct stat st;
  if (!regular_archive(archive, st, error)) return nullptr;
  std::lock_guard<std::mutex> lock(g_cache_mutex);
  auto it = g_cache.find(archive);
  if (it != g_cache.end() && it->second->st.st_dev == st.st_dev && it->second->st.st_ino == st.st_ino &&
      it->second->st.st_size == st.st_size && it->second->st.st_mtim.tv_sec == st.st_mtim.tv_sec &&
      it->second->st.st_mtim.tv_nsec == st.st_mtim.tv_nsec)
    return it->second;
  auto a = std::make_shared<OpenArchive>();
  zip_t* z = open_archive(archive, error);
  if (!z) return nullptr;
  a->free.push_back(z);
  a->path = archive;
  a->st = st;
  const zip_int64_t n = zip_get_num_entries(z, 0);
  for (zip_int64_t i = 0; i < n; ++i)
    if (const char* name = zip_get_name(z, zip_uint64_t(i), 0))
      a->by_lower_name.emplace(lower(name), zip_uint64_t(i));  // the first of equal names wins, as libzip's
  if (g_cache.size() >= 16) g_cache.clear();  // bounded: the handles in use stay alive through their shared_ptr
  g_cache[archive] = a;
  return a;
}

}  // namespace
}  // namespace geom::detail

namespace geom {

bool read_archive_member(const std::string& archive, const std::string& member, std::vector<unsigned char>& bytes,
                         uint64_t max_bytes, std::string& error) {
  using namespace detail;
  PooledHandle h;
  h.archive = cached_archive(archive, error);
  if (!h.archive) return false;
  OpenArchive* a = h.archive.get();
  {
    std::lock_guard<std::mutex> lock(a->mutex);
    if (!a->free.empty()) h.z = a->free.back(), a->free.pop_back();
  }
  if (!h.z && !(h.z = open_archive(a->path, error))) return false;  // another reader holds every handle
  zip_t* const z = h.z;
  zip_int64_t index = zip_name_locate(z, member.c_str(), 0);  // the exact name first
  if (index < 0) {
    auto it = a->by_lower_name.find(lower(member));
    if (it != a->by_lower_name.end()) index = zip_int64_t(it->second);
  }
  zip_stat_t st;
  zip_stat_init(&st);
  if (index < 0 || zip_stat_index(z, zip_uint64_t(index), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) {
    error = "no member '" + member + "' in archive '" + archive + "'";
    return false;
  }
  if (max_bytes && st.size > max_bytes) {
    error = "member '" + member + "' is " + std::to_string(st.size) + " bytes, over the limit of " +
            std::to_string(max_bytes);
    return false;
  }
  const uint64_t memory = detail::physical_memory_bytes();
  if (st.size > (uint64_t(1) << 32) || (memory && st.size > memory)) {
    error = "member '" + member + "' claims " + std::to_string(st.size) + " bytes";
    return false;
  }
  zip_file_t* f = zip_fopen_index(z, zip_uint64_t(index), 0);
  if (!f) {
    error = "cannot open member '" + member + "': " + zip_strerror(z);
    return false;
  }
  // Read in steps, so that a header claiming more than the data holds costs
  // only what is there.
  bytes.clear();
  zip_int64_t got = 0;
  while (bytes.size() < st.size) {
    const size_t at = bytes.size(), step = size_t(std::min<uint64_t>(st.size - at, uint64_t(16) << 20));
    bytes.resize(at + step);
    got = zip_fread(f, bytes.data() + at, step);
    if (got <= 0) {
      bytes.resize(at);
      break;
    }
    bytes.resize(at + size_t(got));
  }
  zip_fclose(f);
  if (got < 0 || bytes.size() != st.size) {
    error = "cannot read member '" + member + "' (corrupt archive: " + std::to_string(bytes.size()) + " of " +
            std::to_string(st.size) + " bytes)";
    return false;
  }
  return true;
}

bool list_archive_members(const std::string& archive, const std::string& suffix, std::vector<std::string>& names,
                          std::string& error) {
  using namespace detail;
  ZipCloser z{open_archive(archive, error)};
  if (!z.z) return false;
  zip_int64_t n = zip_get_num_entries(z.z, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* name = zip_get_name(z.z, zip_uint64_t(i), 0);
    if (name && ends_with_nocase(name, suffix)) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return true;
}

}  // namespace geom
