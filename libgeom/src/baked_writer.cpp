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

// One entry of the table: a section's description, where it goes, its checksum.
struct Entry {
  baked::SectionType type;
  baked::Format format;
  uint32_t stride, item;
  uint64_t count, offset, size;
  uint32_t crc;
  std::string name;
};

// Whether section `i` (of `size` bytes) can be stored; `error` says why not.
bool check_section(size_t i, const BakedSection& s, uint64_t size, std::string& error) {
  using namespace baked;
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
  if (s.count > UINT64_MAX / s.stride || s.count * s.stride != size) {
    error = what + ": " + std::to_string(size) + " bytes are not count " + std::to_string(s.count) + " x stride " +
            std::to_string(s.stride);
    return false;
  }
  return true;
}

bool check_count(size_t n, uint32_t alignment, std::string& error) {
  using namespace baked;
  if (!host_is_little_endian()) {
    error = "the baked writer needs a little-endian host";
    return false;
  }
  if (alignment < kMinAlignment || alignment > kMaxAlignment || (alignment & (alignment - 1))) {
    error = "alignment " + std::to_string(alignment) + " is not a power of two in 16..4096";
    return false;
  }
  if (n > kMaxSections) {
    error = std::to_string(n) + " sections, over the limit of " + std::to_string(kMaxSections);
    return false;
  }
  return true;
}

// The header and table of a container of these entries, ending at `end`.
std::vector<unsigned char> head_of(const std::vector<Entry>& entries, uint32_t alignment, uint64_t end) {
  using namespace baked;
  const uint64_t table_end = kHeaderSize + uint64_t(entries.size()) * kEntrySize;
  std::vector<unsigned char> head(size_t(table_end), 0);
  unsigned char* h = head.data();
  std::memcpy(h, kMagic, 8);
  store_u32(h + 8, kEndianTag);
  store_u16(h + 12, kVersionMajor);
  store_u16(h + 14, kVersionMinor);
  store_u32(h + 16, kHeaderSize);
  store_u32(h + 20, kEntrySize);
  store_u32(h + 24, uint32_t(entries.size()));
  store_u32(h + 28, alignment);
  store_u64(h + 32, end);
  for (size_t i = 0; i < entries.size(); ++i) {
    const Entry& s = entries[i];
    unsigned char* e = h + kHeaderSize + i * kEntrySize;
    store_u32(e, uint32_t(s.type));
    store_u32(e + 4, uint32_t(s.format));
    store_u32(e + 8, s.stride);
    store_u32(e + 12, s.item);
    store_u64(e + 16, s.count);
    store_u64(e + 24, s.offset);
    store_u64(e + 32, s.size);
    store_u32(e + 40, s.crc);
    std::memcpy(e + 48, s.name.data(), s.name.size());
  }
  uint32_t crc = geom::crc32c(h, kHeaderCrcOffset);
  crc = geom::crc32c(h + kHeaderSize, size_t(table_end - kHeaderSize), crc);
  store_u32(h + kHeaderCrcOffset, crc);
  return head;
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
  if (!check_count(sections.size(), alignment, error)) return false;
  const uint64_t table_end = kHeaderSize + uint64_t(sections.size()) * kEntrySize;
  l.alignment = alignment;
  l.offsets.assign(sections.size(), 0);
  l.crcs.assign(sections.size(), 0);
  std::vector<Entry> entries;
  entries.reserve(sections.size());
  uint64_t end = table_end;
  for (size_t i = 0; i < sections.size(); ++i) {
    const BakedSection& s = sections[i];
    if (!check_section(i, s, s.size(), error)) return false;
    l.offsets[i] = align_up(end, alignment);
    end = l.offsets[i] + s.size();
  }
  for (size_t i = 0; i < sections.size(); ++i) {
    const BakedSection& s = sections[i];
    l.crcs[i] = geom::crc32c(s.data(), s.size());
    entries.push_back({s.type, s.format, s.stride, s.item, s.count, l.offsets[i], s.size(), l.crcs[i], s.name});
  }
  l.end = end;
  l.head = head_of(entries, alignment, end);
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

// ---- BakedFileWriter ----

struct BakedFileWriter::State {
  std::string path;
  int old_fd = -1;  // the file at `path`, while compared
  uint64_t old_size = 0;
  bool comparing = false;  // nothing written yet: every byte so far matches the old file
  AtomicFile file;
  bool opened = false;  // `file` open
  size_t count = 0;
  bool counted = false;
  uint64_t table_end = 0, at = 0;  // `at`: the end of the last section
  std::vector<Entry> entries;
  bool in_section = false;
  uint64_t offset = 0, size = 0, done = 0;  // the section being put
  bool sized = true;                        // false: its size is what write() gives (begin_records)
  uint32_t crc = 0;
  std::vector<unsigned char> buffer;  // for compares and copies
  bool failed = false;
  std::string error;

  ~State() {
    if (old_fd >= 0) ::close(old_fd);
  }
  bool fail(const std::string& what) {
    if (!failed) error = what;
    failed = true;
    return false;
  }
  bool fail_errno(const std::string& what) { return fail(what + ": " + std::strerror(errno)); }
  bool have_buffer() {
    if (buffer.empty()) buffer.resize(size_t(1) << 20);
    return true;
  }
  // Whether the old file holds `n` bytes at `pos` equal to `p` (zeros if p is null).
  bool old_holds(const unsigned char* p, uint64_t pos, uint64_t n) {
    have_buffer();
    while (n) {
      const size_t k = size_t(std::min<uint64_t>(n, buffer.size()));
      size_t got = 0;
      while (got < k) {
        const ssize_t r = ::pread(old_fd, buffer.data() + got, k - got, off_t(pos + got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        got += size_t(r);
      }
      if (p ? std::memcmp(buffer.data(), p, k) != 0
            : std::any_of(buffer.data(), buffer.data() + k, [](unsigned char c) { return c != 0; }))
        return false;
      if (p) p += k;
      pos += k, n -= k;
    }
    return true;
  }
  bool pwrite_all(const void* data, size_t n, uint64_t pos) {
    const char* p = static_cast<const char*>(data);
    while (n) {
      const ssize_t w = ::pwrite(file.fd(), p, std::min<size_t>(n, size_t(1) << 30), off_t(pos));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        if (w == 0) errno = EIO;
        return fail_errno("cannot write '" + path + "'");
      }
      p += w, pos += uint64_t(w), n -= size_t(w);
    }
    return true;
  }
  // From here on everything is written: the temporary file, holding the old
  // file's bytes from the table's end to `upto` (all of them compared equal).
  bool start_writing(uint64_t upto) {
    if (opened) return true;
    std::string e;
    if (!file.open(path, e)) return fail(e);
    opened = true;
    if (comparing) {
      have_buffer();
      for (uint64_t pos = table_end; pos < upto;) {
        const size_t k = size_t(std::min<uint64_t>(upto - pos, buffer.size()));
        const ssize_t r = ::pread(old_fd, buffer.data(), k, off_t(pos));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
          if (r == 0) errno = EIO;
          return fail_errno("cannot read '" + path + "'");
        }
        if (!pwrite_all(buffer.data(), size_t(r), pos)) return false;
        pos += uint64_t(r);
      }
      comparing = false;
      ::close(old_fd);
      old_fd = -1;
    }
    return true;
  }
};

BakedFileWriter::BakedFileWriter() : s_(new State) {}
BakedFileWriter::~BakedFileWriter() = default;

const std::string& BakedFileWriter::error() const { return s_->error; }

void BakedFileWriter::open(const std::string& path, bool keep_if_same) {
  State& s = *s_;
  s.path = path;
  if (!keep_if_same) return;
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return;
  }
  s.old_fd = fd;
  s.old_size = uint64_t(st.st_size);
  s.comparing = true;
}

bool BakedFileWriter::expect(size_t section_count) {
  State& s = *s_;
  if (s.failed) return false;
  if (s.counted) return s.fail("internal: the section count is given twice");
  std::string e;
  if (!check_count(section_count, baked::kDefaultAlignment, e)) return s.fail(e);
  s.counted = true;
  s.count = section_count;
  s.table_end = s.at = baked::kHeaderSize + uint64_t(section_count) * baked::kEntrySize;
  s.entries.reserve(section_count);
  return true;
}

bool BakedFileWriter::begin(const BakedSection& section, uint64_t size) {
  State& s = *s_;
  if (s.failed) return false;
  if (!s.counted || s.in_section || s.entries.size() >= s.count)
    return s.fail("internal: section " + std::to_string(s.entries.size()) + " '" + section.name +
                  "' is not one of the " + std::to_string(s.count) + " expected");
  std::string e;
  if (!check_section(s.entries.size(), section, size, e)) return s.fail(e);
  s.offset = align_up(s.at, baked::kDefaultAlignment);
  if (s.comparing && !s.old_holds(nullptr, s.at, s.offset - s.at) && !s.start_writing(s.at)) return false;
  s.entries.push_back(
      {section.type, section.format, section.stride, section.item, section.count, s.offset, size, 0, section.name});
  s.in_section = true;
  s.size = size;
  s.done = 0;
  s.crc = 0;
  return true;
}

bool BakedFileWriter::begin_records(const BakedSection& section) {
  BakedSection first = section;
  first.count = 0;
  if (!begin(first, 0)) return false;
  State& s = *s_;
  s.sized = false;
  s.size = UINT64_MAX;
  return true;
}

bool BakedFileWriter::write(const void* data, size_t size) {
  State& s = *s_;
  if (s.failed) return false;
  if (!s.in_section || size > s.size - s.done) return s.fail("internal: more bytes than the section has");
  if (size == 0) return true;
  // In pieces that stay in the cache between the checksum and the write (a
  // large section read twice from memory otherwise).
  constexpr size_t kPiece = size_t(256) << 10;
  for (const unsigned char* p = static_cast<const unsigned char*>(data); size > 0;) {
    const size_t n = std::min(size, kPiece);
    s.crc = geom::crc32c(p, n, s.crc);
    const uint64_t pos = s.offset + s.done;
    if (s.comparing && !s.old_holds(p, pos, n) && !s.start_writing(pos)) return false;
    if (!s.comparing && !s.start_writing(pos)) return false;
    if (!s.comparing && !s.pwrite_all(p, n, pos)) return false;
    s.done += n, p += n, size -= n;
  }
  return true;
}

bool BakedFileWriter::end() {
  State& s = *s_;
  if (s.failed) return false;
  if (!s.in_section || (s.sized && s.done != s.size)) return s.fail("internal: fewer bytes than the section has");
  Entry& e = s.entries.back();
  if (!s.sized) {
    if (s.done % e.stride) return s.fail("internal: section '" + e.name + "' ends inside a record");
    e.count = s.done / e.stride;
    e.size = s.size = s.done;
    s.sized = true;
  }
  e.crc = s.crc;
  s.at = s.offset + s.size;
  s.in_section = false;
  return true;
}

bool BakedFileWriter::put(const BakedSection& section) {
  return begin(section, section.size()) && write(section.data(), section.size()) && end();
}

bool BakedFileWriter::finish(bool& unchanged, std::vector<uint32_t>* crcs) {
  State& s = *s_;
  unchanged = false;
  if (s.failed) return false;
  if (!s.counted || s.in_section || s.entries.size() != s.count)
    return s.fail("internal: " + std::to_string(s.entries.size()) + " sections of the " + std::to_string(s.count) +
                  " expected");
  std::vector<unsigned char> head;
  try {
    head = head_of(s.entries, baked::kDefaultAlignment, s.at);
  } catch (const std::bad_alloc&) {
    return s.fail("out of memory laying out the baked file");
  }
  if (s.comparing && s.old_size == s.at && s.old_holds(head.data(), 0, head.size())) {
    unchanged = true;
  } else {
    if (!s.start_writing(s.at) || !s.pwrite_all(head.data(), head.size(), 0)) return false;
    if (::ftruncate(s.file.fd(), off_t(s.at)) != 0) return s.fail_errno("cannot write '" + s.path + "'");
    std::string e;
    if (!s.file.commit(e)) return s.fail(e);
  }
  if (crcs) {
    crcs->clear();
    for (const Entry& e : s.entries) crcs->push_back(e.crc);
  }
  return true;
}

// The streaming writer's comparison with the file already there serves the
// whole-vector form too: nothing written while every byte matches.
bool write_baked_if_changed(const std::string& path, const std::vector<BakedSection>& sections, bool& unchanged,
                            std::string& error, std::vector<uint32_t>* crcs) {
  unchanged = false;
  BakedFileWriter w;
  w.open(path, true);
  bool ok = w.expect(sections.size());
  for (size_t i = 0; ok && i < sections.size(); ++i) ok = w.put(sections[i]);
  ok = ok && w.finish(unchanged, crcs);
  if (!ok) error = w.error();
  return ok;
}

}  // namespace geom
