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
#include <string>
#include <vector>

#include "geom/baked_reader.h"

namespace geom {

struct BakedSection {
  baked::SectionType type = baked::SectionType::Positions;
  baked::Format format = baked::Format::Bytes;
  uint32_t stride = 1;  // bytes per element
  uint32_t item = 0;    // e.g. the light index of a per-light volume
  uint64_t count = 0;   // elements; bytes.size() must be count * stride
  std::string name;     // up to 15 printable ASCII characters
  std::vector<unsigned char> bytes;
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

// Lays the sections out in the given order (`alignment`: a power of two in
// 16..4096). False with `error` if a section is inconsistent (bad name, size
// not count x stride, stride not that of the format) or there are too many.
bool serialize_baked(const std::vector<BakedSection>& sections, std::vector<unsigned char>& out, std::string& error,
                     uint32_t alignment = baked::kDefaultAlignment);

// serialize_baked, then the atomic write. error: "what is wrong".
bool write_baked(const std::string& path, const std::vector<BakedSection>& sections, std::string& error);

}  // namespace geom
