// Zip (.pk3) archive access through libzip (Debian's libzip-dev): Quake 3 data
// ships as zip archives, and a maintained library reads them better than we would.
#include "archive.h"

#include <zip.h>

#include <algorithm>
#include <cctype>

namespace geom::detail {
namespace {

struct ZipCloser {
  zip_t* z;
  ~ZipCloser() {
    if (z) zip_discard(z);
  }
};

zip_t* open_archive(const std::string& archive, std::string& error) {
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

}  // namespace

bool read_archive_member(const std::string& archive, const std::string& member, std::vector<unsigned char>& bytes,
                         uint64_t max_bytes, std::string& error) {
  ZipCloser z{open_archive(archive, error)};
  if (!z.z) return false;
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(z.z, member.c_str(), ZIP_FL_NOCASE, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) {
    error = "no member '" + member + "' in archive '" + archive + "'";
    return false;
  }
  if (max_bytes && st.size > max_bytes) {
    error = "member '" + member + "' is " + std::to_string(st.size) + " bytes, over the limit of " +
            std::to_string(max_bytes);
    return false;
  }
  if (st.size > (uint64_t(1) << 32)) {
    error = "member '" + member + "' claims " + std::to_string(st.size) + " bytes";
    return false;
  }
  zip_file_t* f = zip_fopen(z.z, member.c_str(), ZIP_FL_NOCASE);
  if (!f) {
    error = "cannot open member '" + member + "': " + zip_strerror(z.z);
    return false;
  }
  bytes.resize(size_t(st.size));
  zip_int64_t got = bytes.empty() ? 0 : zip_fread(f, bytes.data(), bytes.size());
  zip_fclose(f);
  if (got < 0 || uint64_t(got) != st.size) {
    error = "cannot read member '" + member + "' (corrupt archive?)";
    return false;
  }
  return true;
}

bool list_archive_members(const std::string& archive, const std::string& suffix, std::vector<std::string>& names,
                          std::string& error) {
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

}  // namespace geom::detail
