// The baked container's writer: the layout of geom/baked_reader.h's format.
#include "geom/baked_writer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>

#include "geom/atomic_file.h"
#include "geom/crc32c.h"

namespace geom {
namespace {

void store_u16(unsigned char* p, uint16_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}
void store_u32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
void store_u64(unsigned char* p, uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = uint8_t(v >> (8 * i));
}
uint64_t align_up(uint64_t v, uint64_t a) { return (v + a - 1) & ~(a - 1); }

bool host_is_little_endian() {
  const uint32_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

// The header and table of the container (the checksums of every section in
// it), and where each section goes. False with `error` on a bad section.
struct Layout {
  std::vector<unsigned char> head;  // header + table
  std::vector<uint64_t> offsets;
  std::vector<uint32_t> crcs;
  uint64_t end = 0;
  uint32_t alignment = 0;
};

bool lay_out(const std::vector<BakedSection>& sections, uint32_t alignment, Layout& l, std::string& error) {
  using namespace baked;
  if (!host_is_little_endian()) {
    error = "the baked writer needs a little-endian host";
    return false;
  }
  if (alignment < kMinAlignment || alignment > kMaxAlignment || (alignment & (alignment - 1))) {
    error = "alignment " + std::to_string(alignment) + " is not a power of two in 16..4096";
    return false;
  }
  if (sections.size() > kMaxSections) {
    error = std::to_string(sections.size()) + " sections, over the limit of " + std::to_string(kMaxSections);
    return false;
  }
  const uint64_t table_end = kHeaderSize + uint64_t(sections.size()) * kEntrySize;
  l.alignment = alignment;
  l.offsets.assign(sections.size(), 0);
  l.crcs.assign(sections.size(), 0);
  uint64_t end = table_end;
  for (size_t i = 0; i < sections.size(); ++i) {
    const BakedSection& s = sections[i];
    std::string what = "section " + std::to_string(i) + " '" + s.name + "'";
    if (s.name.size() >= kNameSize) {
      error = what + ": name longer than " + std::to_string(kNameSize - 1) + " characters";
      return false;
    }
    for (char c : s.name)
      if (c < 0x20 || c > 0x7e) {
        error = what + ": name has a non-printable character";
        return false;
      }
    uint32_t want = format_stride(s.format);
    if (!format_known(uint32_t(s.format)) || s.stride == 0 || (want && s.stride != want)) {
      error = what + ": stride " + std::to_string(s.stride) + " does not fit format " + format_name(s.format);
      return false;
    }
    if (s.count > UINT64_MAX / s.stride || s.count * s.stride != s.size()) {
      error = what + ": " + std::to_string(s.size()) + " bytes are not count " + std::to_string(s.count) +
              " x stride " + std::to_string(s.stride);
      return false;
    }
    l.offsets[i] = align_up(end, alignment);
    end = l.offsets[i] + s.size();
  }
  l.end = end;
  l.head.assign(size_t(table_end), 0);
  unsigned char* h = l.head.data();
  std::memcpy(h, kMagic, 8);
  store_u32(h + 8, kEndianTag);
  store_u16(h + 12, kVersionMajor);
  store_u16(h + 14, kVersionMinor);
  store_u32(h + 16, kHeaderSize);
  store_u32(h + 20, kEntrySize);
  store_u32(h + 24, uint32_t(sections.size()));
  store_u32(h + 28, alignment);
  store_u64(h + 32, end);
  for (size_t i = 0; i < sections.size(); ++i) {
    const BakedSection& s = sections[i];
    unsigned char* e = h + kHeaderSize + i * kEntrySize;
    l.crcs[i] = geom::crc32c(s.data(), s.size());
    store_u32(e, uint32_t(s.type));
    store_u32(e + 4, uint32_t(s.format));
    store_u32(e + 8, s.stride);
    store_u32(e + 12, s.item);
    store_u64(e + 16, s.count);
    store_u64(e + 24, l.offsets[i]);
    store_u64(e + 32, s.size());
    store_u32(e + 40, l.crcs[i]);
    std::memcpy(e + 48, s.name.data(), s.name.size());
  }
  uint32_t crc = geom::crc32c(h, kHeaderCrcOffset);
  crc = geom::crc32c(h + kHeaderSize, size_t(table_end - kHeaderSize), crc);
  store_u32(h + kHeaderCrcOffset, crc);
  return true;
}

}  // namespace

bool serialize_baked(const std::vector<BakedSection>& sections, std::vector<unsigned char>& out, std::string& error,
                     uint32_t alignment) {
  out.clear();
  Layout l;
  if (!lay_out(sections, alignment, l, error)) return false;
  out.assign(size_t(l.end), 0);  // every padding byte zero
  std::memcpy(out.data(), l.head.data(), l.head.size());
  for (size_t i = 0; i < sections.size(); ++i)
    if (sections[i].size()) std::memcpy(out.data() + l.offsets[i], sections[i].data(), sections[i].size());
  return true;
}

namespace {

// The file of write_baked as the pieces of one gathering write: header and
// table, then each section's own buffer behind its zero padding.
bool parts_of(const std::vector<BakedSection>& sections, Layout& l, std::vector<FilePart>& parts, std::string& error) {
  static const unsigned char kZeros[baked::kMaxAlignment] = {};
  try {
    if (!lay_out(sections, baked::kDefaultAlignment, l, error)) return false;
    parts.reserve(2 * sections.size() + 1);
    parts.push_back({l.head.data(), l.head.size()});
    uint64_t at = l.head.size();
    for (size_t i = 0; i < sections.size(); ++i) {
      if (l.offsets[i] > at) parts.push_back({kZeros, size_t(l.offsets[i] - at)});
      parts.push_back({sections[i].data(), sections[i].size()});
      at = l.offsets[i] + sections[i].size();
    }
  } catch (const std::bad_alloc&) {
    error = "out of memory laying out the baked file";
    return false;
  }
  return true;
}

// Whether the regular file at `path` holds exactly the concatenated parts,
// read in pieces (never a whole copy of either in memory).
bool holds(const std::string& path, const std::vector<FilePart>& parts, uint64_t size) {
  std::vector<unsigned char> buffer;
  try {
    buffer.resize(size_t(std::min<uint64_t>(size, uint64_t(1) << 20)) + 1);
  } catch (const std::bad_alloc&) {
    return false;  // then it is written
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st {};
  bool same = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && uint64_t(st.st_size) == size;
  for (size_t p = 0; same && p < parts.size(); ++p) {
    const unsigned char* want = static_cast<const unsigned char*>(parts[p].data);
    for (size_t done = 0; same && done < parts[p].size;) {
      const size_t n = std::min(buffer.size(), parts[p].size - done);
      size_t got = 0;
      while (got < n) {
        const ssize_t r = ::read(fd, buffer.data() + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += size_t(r);
      }
      same = got == n && std::memcmp(buffer.data(), want + done, n) == 0;
      done += n;
    }
  }
  ::close(fd);
  return same;
}

}  // namespace

bool write_baked(const std::string& path, const std::vector<BakedSection>& sections, std::string& error,
                 std::vector<uint32_t>* crcs) {
  Layout l;
  std::vector<FilePart> parts;
  if (!parts_of(sections, l, parts, error)) return false;
  if (!write_file_atomically(path, parts.data(), parts.size(), error)) return false;
  if (crcs) *crcs = std::move(l.crcs);
  return true;
}

bool write_baked_if_changed(const std::string& path, const std::vector<BakedSection>& sections, bool& unchanged,
                            std::string& error, std::vector<uint32_t>* crcs) {
  unchanged = false;
  Layout l;
  std::vector<FilePart> parts;
  if (!parts_of(sections, l, parts, error)) return false;
  if (holds(path, parts, l.end)) {
    unchanged = true;
  } else if (!write_file_atomically(path, parts.data(), parts.size(), error)) {
    return false;
  }
  if (crcs) *crcs = std::move(l.crcs);
  return true;
}

}  // namespace geom
