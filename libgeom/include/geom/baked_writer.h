// geom/baked_writer.h: lay out sections in the baked container and write it atomically.
//
// The format is documented at the top of geom/baked_reader.h. serialize_baked()
// is a pure function of its input: the same sections give the same bytes (no
// timestamps, no pointers, every padding byte zero), so bakes are reproducible.
// write_baked() writes through geom/atomic_file.h (a temporary file in the
// destination's directory, fsync, rename; on any failure the temporary file is
// removed), so the destination is either the old file (or none) or the complete
// new one, never a half-written one.
// Nothing here throws: errors come back as one line ("what is wrong").
// The payload bytes are taken as they are: the caller gives them little-endian
// (native on every host the writer supports; a big-endian host is refused).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geom/baked_reader.h"

namespace geom {

// The payload is either `bytes` (owned) or, when `view` is set, the `view_size`
// bytes at `view`, inside a buffer that `keep` holds alive (a stage's own
// output, moved in: no copy). data() and size() give whichever it is.
struct BakedSection {
  baked::SectionType type = baked::SectionType::Positions;
  baked::Format format = baked::Format::Bytes;
  uint32_t stride = 1;  // bytes per element
  uint32_t item = 0;    // e.g. the light index of a per-light volume
  uint64_t count = 0;   // elements; size() must be count * stride
  std::string name;     // up to 15 printable ASCII characters
  std::vector<unsigned char> bytes;
  const unsigned char* view = nullptr;
  size_t view_size = 0;
  std::shared_ptr<const void> keep;

  const unsigned char* data() const { return view ? view : bytes.data(); }
  size_t size() const { return view ? view_size : bytes.size(); }
};

// A section of a typed array (T is float, uint32_t or a record of them):
// count = values.size() * sizeof(T) / stride.
template <class T>
BakedSection make_baked_section(baked::SectionType type, baked::Format format, uint32_t stride, std::string name,
                                const std::vector<T>& values, uint32_t item = 0) {
  BakedSection s;
  s.type = type;
  s.format = format;
  s.stride = stride;
  s.item = item;
  s.name = std::move(name);
  const unsigned char* p = reinterpret_cast<const unsigned char*>(values.data());
  s.bytes.assign(p, p + values.size() * sizeof(T));
  s.count = stride ? s.bytes.size() / stride : 0;
  return s;
}

// The same without a copy: the section views `values`, moved into it.
template <class T>
BakedSection make_baked_section(baked::SectionType type, baked::Format format, uint32_t stride, std::string name,
                                std::vector<T>&& values, uint32_t item = 0) {
  BakedSection s;
  s.type = type;
  s.format = format;
  s.stride = stride;
  s.item = item;
  s.name = std::move(name);
  auto kept = std::make_shared<const std::vector<T>>(std::move(values));
  s.view = reinterpret_cast<const unsigned char*>(kept->data());
  s.view_size = kept->size() * sizeof(T);
  s.keep = std::move(kept);
  s.count = stride ? s.view_size / stride : 0;
  return s;
}

// Lays the sections out in the given order (`alignment`: a power of two in
// 16..4096). False with `error` if a section is inconsistent (bad name, size
// not count x stride, stride not that of the format) or there are too many.
bool serialize_baked(const std::vector<BakedSection>& sections, std::vector<unsigned char>& out, std::string& error,
                     uint32_t alignment = baked::kDefaultAlignment);

// The layout of serialize_baked written straight from the sections' buffers
// (one gathering write, geom/atomic_file.h; no serialized copy), atomically.
// Each section's CRC-32C is computed once (geom/crc32c.h); when `crcs` is
// given it receives them, in section order, for a report. error: "what is wrong".
bool write_baked(const std::string& path, const std::vector<BakedSection>& sections, std::string& error,
                 std::vector<uint32_t>* crcs = nullptr);

// The same, unless the regular file at `path` already holds exactly those
// bytes: then it is left untouched (its mtime kept) and `unchanged` is set.
// The file is compared in pieces against the sections' own buffers (by the
// BakedFileWriter below, as a streamed bake does), so
// neither the new layout nor the old file is ever copied whole into memory.
bool write_baked_if_changed(const std::string& path, const std::vector<BakedSection>& sections, bool& unchanged,
                            std::string& error, std::vector<uint32_t>* crcs = nullptr);

// The layout of write_baked written section by section, each as soon as it is
// final, so that its buffer can be freed at once (geom/bake.h streams a bake
// so): the sections go to a temporary file (geom/atomic_file.h, created at the
// first byte to write) at their final offsets, the header and table with every
// CRC-32C last, then the file is renamed over `path`. With `keep_if_same` and
// a regular file at `path` (a symlink is replaced, never compared through),
// each section is compared with that file as it comes and nothing is written
// while they match; at the first difference the matching part is copied from
// it; if the whole file matches it is left untouched (its mtime kept). The
// same bytes as write_baked of the same sections. Destroyed before finish()
// (an error, a time-out), it leaves nothing behind. Not thread-safe.
class BakedFileWriter {
 public:
  BakedFileWriter();
  ~BakedFileWriter();
  BakedFileWriter(const BakedFileWriter&) = delete;
  BakedFileWriter& operator=(const BakedFileWriter&) = delete;

  void open(const std::string& path, bool keep_if_same);
  // The number of sections the file will hold: once, before the first.
  bool expect(size_t section_count);
  // The next section in file order, whole (its bytes are written or compared
  // now: the caller may free them on return) ...
  bool put(const BakedSection& section);
  // ... or in pieces: begin() with `size` bytes to come (the section's own
  // bytes are not read), then write() them in order, then end().
  bool begin(const BakedSection& section, uint64_t size);
  // ... or begin_records(): a section whose size is the bytes written before
  // end(), a whole number of `section.stride` (count and size are ignored).
  bool begin_records(const BakedSection& section);
  bool write(const void* data, size_t size);
  bool end();
  // Writes the header and table and renames the file over the target (or
  // leaves an identical target as it was: `unchanged`). `crcs`: every
  // section's CRC-32C, in order.
  bool finish(bool& unchanged, std::vector<uint32_t>* crcs = nullptr);
  // After a false from any call: what is wrong (every later call is false).
  const std::string& error() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace geom
