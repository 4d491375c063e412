// geom/baked_reader.h: the baked container format, and a reader that trusts nothing.
//
// Self-contained: C++17 standard library only, no other geom header, so an
// engine can copy this one file and include it alone (CMake: geom::reader).
// It reads from memory; reading or mapping a file is geom/baked_file.h. Written by
// geom/baked_writer.h (`geombake bake`); listed and verified by `geombake inspect`.
//
// FORMAT (version 2.0). Every integer is little-endian. A file is
//
//   [header 64 B][section table: section_count x 64 B][zero padding][section 0]
//   [zero padding][section 1] ... [section n-1]      (the file ends at the last section's end)
//
// Header (offsets in bytes):
//    0 u8[8]  magic        89 47 42 4B 0D 0A 1A 0A   ("\x89GBK\r\n\x1a\n", PNG style: catches
//                                                    text-mode and 7-bit transfers)
//    8 u32    endian_tag   0x0A0B0C0D, stored as 0D 0C 0B 0A
//   12 u16    version_major  2: a reader refuses any other major version, older or newer
//   14 u16    version_minor  0: later minors only add section types (unknown ones are listed, not refused)
//   16 u32    header_size    64
//   20 u32    entry_size     64 (size of one section table entry)
//   24 u32    section_count  at most kMaxSections
//   28 u32    alignment      every section offset is a multiple of it: a power of two, 16..4096
//   32 u64    file_size      the exact size of the file
//   40 u8[20] reserved       written as zero
//   60 u32    header_crc     CRC-32C of header bytes [0, 60) followed by the whole section table
//
// Section table entry:
//    0 u32    type      SectionType (what the bytes mean)
//    4 u32    format    Format (the element type)
//    8 u32    stride    bytes per element; equals format_stride(format) unless that is 0
//   12 u32    item      which one among sections of the same type (the light index of a
//                       per-light volume); 0 otherwise
//   16 u64    count     number of elements
//   24 u64    offset    from the start of the file; a multiple of `alignment`
//   32 u64    size      bytes; exactly count * stride
//   40 u32    crc       CRC-32C of the section's `size` bytes
//   44 u32    reserved  written as zero
//   48 char[16] name    ASCII, printable, NUL-terminated and NUL-padded
//
// Sections lie in table order, at increasing offsets, without overlap, after the
// table. Every byte that is neither header, table nor section (alignment padding)
// must be zero. So every byte of a valid file is checked: header and table by
// header_crc, sections by their crc, padding by the zero rule, the length by
// file_size. One flipped byte anywhere, or any truncation, is refused.
//
// CHECKSUM: CRC-32C (Castagnoli; reflected polynomial 0x82F63B78, initial value
// 0xFFFFFFFF, final xor 0xFFFFFFFF; crc32c("123456789") = 0xE3069283), the one of
// iSCSI, ext4 and SSE4.2's crc32 instruction. crc32c() below computes it.
//
// SECTIONS written by `geombake bake` (geom/bake.h says what each holds; the
// records' structs are in geom/baked_records.h, standard library only like
// this file; their layouts are documented there, in geom/esm_quads.h and
// geom/shadow_volume.h). Every section's frame: "input", "local" or "-" (no
// coordinates: indices, counts, text).
//   type               format  stride  count            frame  upload as
//   Positions          F32x3   12      welded vertices  input  GL_ARRAY_BUFFER
//   Indices            U32     4       3 x triangles    -      GL_ELEMENT_ARRAY_BUFFER
//   WeldRemap          U32     4       source vertices  -      (source vertex -> welded vertex)
//   CasterHull         F64x4   32      planes           input  (nx, ny, nz, d), n unit, inside where n.p + d >= 0:
//                                                              the convex hull of the positions (at most 16
//                                                              supporting planes of it), for the focus
//                                                              (geom/focus.h FocusOptions::caster_hull)
//   FacePlanes         F32x4   16      triangles        input  (nx, ny, nz, d), n unit, n.p + d = 0
//   TopologyReport     Utf8    1       bytes            -      (JSON, keys of `geombake info --json`)
//   Frame              F64x3   24      1                input  (origin of the local frame: local = input - origin)
//   EsmQuads           Record  36      quads            local  GL_ARRAY_BUFFER, one instance per record
//   EsmPlanes          F32x4   16      planes           local  GL_TEXTURE_BUFFER (RGBA32F)
//   VolumeSides        Record  32      sides            local  GL_ARRAY_BUFFER, one instance per record
//   VolumeCaps         Record  40      caps             local  GL_ARRAY_BUFFER, one instance per record
//   VolumePlanes       F32x4   16      planes           local  GL_TEXTURE_BUFFER (RGBA32F)
//   AdjacencyIndices   U32     4       6 x triangles    -      GL_ELEMENT_ARRAY_BUFFER (GL_TRIANGLES_ADJACENCY
//                                                              over Positions)
//   Lights             F64x4   32      lights           input  ((x, y, z, w), w = 0 directional: u_light)
//   LightParams        Record  120     lights           input  LightRecord: the whole KHR_lights_punctual light
//                                                              (type, position, direction, range, colour,
//                                                              intensity, cone angles), same order as Lights
//   LightNames         Utf8    1       bytes            -      the lights' names (LightRecord's name_offset/size)
//   LightSides/Caps/Planes (item = light index): local, as VolumeSides/Caps/Planes, exact for that light
//   SilhouetteReport   Utf8    1       bytes            -      (JSON: what each rule saved, the lights; its
//                                                              "frame" and lights' "light" in input coordinates)
// Frames: "input" is the input file's coordinates and units (node transforms
// applied); "local" is the frame whose origin the Frame section holds, so a
// record drawn with the camera's matrix times a translation by that origin
// lands where the Positions drawn with the camera's matrix do; a light moves
// into it as (x - w ox, y - w oy, z - w oz, w).
//
// READER: Reader::open() validates, in this order: size, magic, endianness,
// version (a file of another major version, older or newer, is refused with
// both versions named: rebake it with the matching geombake), header and table bounds, header checksum, file size
// (truncation), alignment, then per section: name, format and stride, size = count x stride, alignment, order and
// overlap, bounds, zero padding, checksum; at last that the file ends with the last section. On success sections()
// gives zero-copy views into the caller's buffer (which must outlive them); on
// failure error() says what is wrong in one line. It never throws (beyond
// std::bad_alloc from the section vector, bounded by the table size), never
// reads outside the buffer, and never allocates more than the table claims
// (which the buffer must hold). Payload bytes are little-endian: on a
// big-endian host, swap them after reading.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace geom {
namespace baked {

inline constexpr unsigned char kMagic[8] = {0x89, 'G', 'B', 'K', 0x0D, 0x0A, 0x1A, 0x0A};
inline constexpr uint32_t kEndianTag = 0x0A0B0C0Du;
inline constexpr uint16_t kVersionMajor = 2;
inline constexpr uint16_t kVersionMinor = 0;
inline constexpr uint32_t kHeaderSize = 64;
inline constexpr uint32_t kEntrySize = 64;
inline constexpr uint32_t kNameSize = 16;  // including the terminating NUL
inline constexpr uint32_t kMaxSections = 1u << 16;
inline constexpr uint32_t kMinAlignment = 16;
inline constexpr uint32_t kMaxAlignment = 4096;
inline constexpr uint32_t kDefaultAlignment = 64;
inline constexpr uint32_t kHeaderCrcOffset = 60;

// What a section's bytes mean. Numbers are fixed forever; new ones may be added.
enum class SectionType : uint32_t {
  Positions = 1,         // F32x3 welded vertex positions
  Indices = 2,           // U32 welded triangle indices, 3 per triangle
  WeldRemap = 3,         // U32 per source vertex: its welded vertex
  FacePlanes = 4,        // F32x4 per triangle: unit normal and offset (0,0,0,0 if degenerate)
  TopologyReport = 5,    // Utf8 JSON text
  Frame = 6,             // F64x3, one: the origin of the local frame of the silhouette buffers
  SilhouetteReport = 7,  // Utf8 JSON text: what each rule saved, the lights
  CasterHull = 8,        // F64x4 planes (nx, ny, nz, d) of the positions' convex hull, input coordinates
  // Silhouette buffers: records and plane tables in the local frame (geom/bake.h).
  EsmQuads = 16,          // Record 36 B per quad (geom/esm_quads.h)
  EsmPlanes = 17,         // F32x4 plane table of the quads
  VolumeSides = 32,       // Record 32 B per side (geom/shadow_volume.h)
  VolumeCaps = 33,        // Record 40 B per cap
  VolumePlanes = 34,      // F32x4 plane table of sides and caps
  AdjacencyIndices = 48,  // U32, 6 per triangle (GL_TRIANGLES_ADJACENCY, geom/adjacency.h)
  Lights = 64,            // F64x4 per static light: (x, y, z, w) in input coordinates, w = 0 directional
  LightSides = 65,        // per light (item = its index in Lights): exact volume sides, Record 32 B
  LightCaps = 66,         // per light: exact volume caps, Record 40 B
  LightPlanes = 67,       // per light: F32x4 plane table
  LightParams = 68,       // Record 120 B per light (LightRecord, geom/baked_records.h), input coordinates
  LightNames = 69,        // Utf8: the lights' names, LightRecord::name_offset / name_size into it
};

// The element type of a section.
enum class Format : uint32_t {
  Bytes = 0,  // opaque bytes, stride 1
  U32 = 1,    // uint32
  F32 = 2,    // float
  F32x2 = 3,
  F32x3 = 4,
  F32x4 = 5,
  Utf8 = 6,    // text, stride 1
  Record = 7,  // a fixed-size record whose layout the section type defines; any stride > 0
  F64x3 = 8,   // double x 3
  F64x4 = 9,   // double x 4
};

// Bytes per element of a format; 0 for Record (the entry's stride decides).
inline constexpr uint32_t format_stride(Format f) {
  switch (f) {
    case Format::Bytes:
      return 1;
    case Format::U32:
      return 4;
    case Format::F32:
      return 4;
    case Format::F32x2:
      return 8;
    case Format::F32x3:
      return 12;
    case Format::F32x4:
      return 16;
    case Format::Utf8:
      return 1;
    case Format::Record:
      return 0;
    case Format::F64x3:
      return 24;
    case Format::F64x4:
      return 32;
  }
  return 0;
}

inline bool format_known(uint32_t f) { return f <= uint32_t(Format::F64x4); }

inline const char* format_name(Format f) {
  switch (f) {
    case Format::Bytes:
      return "bytes";
    case Format::U32:
      return "u32";
    case Format::F32:
      return "f32";
    case Format::F32x2:
      return "f32x2";
    case Format::F32x3:
      return "f32x3";
    case Format::F32x4:
      return "f32x4";
    case Format::Utf8:
      return "utf8";
    case Format::Record:
      return "record";
    case Format::F64x3:
      return "f64x3";
    case Format::F64x4:
      return "f64x4";
  }
  return "?";
}

inline const char* type_name(SectionType t) {
  switch (t) {
    case SectionType::Positions:
      return "positions";
    case SectionType::Indices:
      return "indices";
    case SectionType::WeldRemap:
      return "weld_remap";
    case SectionType::FacePlanes:
      return "face_planes";
    case SectionType::TopologyReport:
      return "topology_report";
    case SectionType::Frame:
      return "frame";
    case SectionType::SilhouetteReport:
      return "silhouette_report";
    case SectionType::EsmQuads:
      return "esm_quads";
    case SectionType::EsmPlanes:
      return "esm_planes";
    case SectionType::VolumeSides:
      return "volume_sides";
    case SectionType::VolumeCaps:
      return "volume_caps";
    case SectionType::VolumePlanes:
      return "volume_planes";
    case SectionType::AdjacencyIndices:
      return "adjacency_indices";
    case SectionType::Lights:
      return "lights";
    case SectionType::LightSides:
      return "light_sides";
    case SectionType::LightCaps:
      return "light_caps";
    case SectionType::LightPlanes:
      return "light_planes";
    case SectionType::CasterHull:
      return "caster_hull";
    case SectionType::LightParams:
      return "light_params";
    case SectionType::LightNames:
      return "light_names";
  }
  return "unknown";
}

// ---- CRC-32C ---------------------------------------------------------------

namespace detail {
struct Crc32cTables {
  uint32_t t[8][256];
};
inline constexpr Crc32cTables make_crc32c_tables() {
  Crc32cTables r{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
    r.t[0][i] = c;
  }
  for (int s = 1; s < 8; ++s)
    for (int i = 0; i < 256; ++i) r.t[s][i] = (r.t[s - 1][i] >> 8) ^ r.t[0][r.t[s - 1][i] & 0xffu];
  return r;
}
inline constexpr Crc32cTables kCrc32c = make_crc32c_tables();

inline uint16_t load_u16(const unsigned char* p) { return uint16_t(p[0] | (p[1] << 8)); }
inline uint32_t load_u32(const unsigned char* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
inline uint64_t load_u64(const unsigned char* p) { return uint64_t(load_u32(p)) | (uint64_t(load_u32(p + 4)) << 32); }
inline std::string hex32(uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%08x", v);
  return b;
}
}  // namespace detail

// CRC-32C of `size` bytes, continuing from `crc` (the value a previous call
// returned; 0 to start). Slicing-by-8, about 1-2 GB/s.
inline uint32_t crc32c(const void* data, size_t size, uint32_t crc = 0) {
  const auto& t = detail::kCrc32c.t;
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint32_t c = ~crc;
  while (size >= 8) {
    uint32_t lo = c ^ detail::load_u32(p);
    uint32_t hi = detail::load_u32(p + 4);
    c = t[7][lo & 0xff] ^ t[6][(lo >> 8) & 0xff] ^ t[5][(lo >> 16) & 0xff] ^ t[4][lo >> 24] ^ t[3][hi & 0xff] ^
        t[2][(hi >> 8) & 0xff] ^ t[1][(hi >> 16) & 0xff] ^ t[0][hi >> 24];
    p += 8;
    size -= 8;
  }
  while (size--) c = t[0][(c ^ *p++) & 0xff] ^ (c >> 8);
  return ~c;
}

// ---- Reader ----------------------------------------------------------------

// One section, as the table describes it, with a view of its bytes.
struct Section {
  SectionType type{};  // may hold a value this reader does not name (a later minor version)
  Format format{};
  uint32_t stride = 0;
  uint32_t item = 0;
  uint64_t count = 0;
  uint64_t offset = 0;
  uint64_t size = 0;
  uint32_t crc = 0;
  char name[kNameSize] = {};
  const unsigned char* data = nullptr;  // into the buffer given to Reader::open

  // The elements as T, zero-copy, when T's size is the stride and the bytes are
  // suitably aligned for T (always true for a buffer aligned to 16 bytes);
  // nullptr otherwise. Little-endian hosts only.
  template <class T>
  const T* as() const {
    if (sizeof(T) != stride || reinterpret_cast<uintptr_t>(data) % alignof(T) != 0) return nullptr;
    return reinterpret_cast<const T*>(data);
  }
};

class Reader {
 public:
  // Validates the whole file (see the top of this header). The buffer must stay
  // alive and unchanged while sections are used.
  bool open(const void* data, size_t size) {
    sections_.clear();
    error_.clear();
    if (!validate(static_cast<const unsigned char*>(data), size)) {
      sections_.clear();
      return false;
    }
    return true;
  }

  const std::string& error() const { return error_; }
  const std::vector<Section>& sections() const { return sections_; }
  uint16_t version_major() const { return version_major_; }
  uint16_t version_minor() const { return version_minor_; }
  uint32_t alignment() const { return alignment_; }
  uint64_t file_size() const { return file_size_; }
  uint32_t header_crc() const { return header_crc_; }

  // The first section of that type and item, or nullptr.
  const Section* find(SectionType type, uint32_t item = 0) const {
    for (const Section& s : sections_)
      if (s.type == type && s.item == item) return &s;
    return nullptr;
  }

 private:
  bool fail(std::string message) {
    error_ = std::move(message);
    return false;
  }

  bool validate(const unsigned char* p, size_t size) {
    using detail::load_u16;
    using detail::load_u32;
    using detail::load_u64;
    using std::to_string;
    if (size == 0) return fail("empty file, not a geombake baked file");
    if (!p) return fail("no data");
    if (std::memcmp(p, kMagic, size < 8 ? size : 8) != 0) return fail("not a geombake baked file (bad magic)");
    if (size < kHeaderSize)
      return fail("truncated: " + to_string(size) + " bytes, shorter than the " + to_string(kHeaderSize) +
                  "-byte header");
    uint32_t tag = load_u32(p + 8);
    if (tag == 0x0D0C0B0Au) return fail("big-endian file; this format is little-endian");
    if (tag != kEndianTag) return fail("corrupt header: bad endianness tag " + detail::hex32(tag));
    version_major_ = load_u16(p + 12);
    version_minor_ = load_u16(p + 14);
    if (version_major_ != kVersionMajor) {
      const std::string file_version = to_string(version_major_) + "." + to_string(version_minor_);
      const std::string reader_version = to_string(kVersionMajor) + "." + to_string(kVersionMinor);
      return fail("unsupported version " + file_version + ": the file is " +
                  (version_major_ < kVersionMajor ? "older" : "newer") + " than this reader's version " +
                  reader_version + " (it reads " + to_string(kVersionMajor) +
                  ".x): bake it again with a geombake that "
                  "writes " +
                  reader_version);
    }
    uint32_t header_size = load_u32(p + 16), entry_size = load_u32(p + 20);
    uint32_t count = load_u32(p + 24);
    alignment_ = load_u32(p + 28);
    file_size_ = load_u64(p + 32);
    header_crc_ = load_u32(p + kHeaderCrcOffset);
    if (header_size != kHeaderSize) return fail("corrupt header: header size " + to_string(header_size));
    if (entry_size != kEntrySize) return fail("corrupt header: section entry size " + to_string(entry_size));
    if (count > kMaxSections) return fail("corrupt header: " + to_string(count) + " sections");
    const uint64_t table_end = uint64_t(kHeaderSize) + uint64_t(count) * kEntrySize;
    if (table_end > size)
      return fail("truncated: the section table ends at byte " + to_string(table_end) + ", the file has " +
                  to_string(size));
    uint32_t crc = crc32c(p, kHeaderCrcOffset);
    crc = crc32c(p + kHeaderSize, size_t(table_end - kHeaderSize), crc);
    if (crc != header_crc_)
      return fail("header checksum mismatch (stored " + detail::hex32(header_crc_) + ", computed " +
                  detail::hex32(crc) + "): corrupt header or section table");
    if (file_size_ > size)
      return fail("truncated: " + to_string(size) + " bytes, the header says " + to_string(file_size_));
    if (file_size_ < size)
      return fail(to_string(size - file_size_) + " bytes after the end (the header says " + to_string(file_size_) +
                  " bytes)");
    if (alignment_ < kMinAlignment || alignment_ > kMaxAlignment || (alignment_ & (alignment_ - 1)))
      return fail("corrupt header: alignment " + to_string(alignment_));

    sections_.reserve(count);
    uint64_t end = table_end;  // end of the previous section
    for (uint32_t i = 0; i < count; ++i) {
      const unsigned char* e = p + kHeaderSize + size_t(i) * kEntrySize;
      Section s;
      s.type = SectionType(load_u32(e));
      uint32_t format = load_u32(e + 4);
      s.stride = load_u32(e + 8);
      s.item = load_u32(e + 12);
      s.count = load_u64(e + 16);
      s.offset = load_u64(e + 24);
      s.size = load_u64(e + 32);
      s.crc = load_u32(e + 40);
      std::memcpy(s.name, e + 48, kNameSize);
      std::string what = "section " + to_string(i);
      if (std::memchr(s.name, 0, kNameSize) == nullptr) return fail(what + ": name is not NUL-terminated");
      for (size_t k = 0; k < kNameSize && s.name[k]; ++k)
        if (s.name[k] < 0x20 || s.name[k] > 0x7e) return fail(what + ": name has a non-printable character");
      for (size_t k = std::strlen(s.name); k < kNameSize; ++k)
        if (s.name[k] != 0) return fail(what + ": name padding is not zero");
      what += " '" + std::string(s.name) + "'";
      if (!format_known(format)) return fail(what + ": unknown element format " + to_string(format));
      s.format = Format(format);
      uint32_t want = format_stride(s.format);
      if (s.stride == 0 || (want != 0 && s.stride != want))
        return fail(what + ": stride " + to_string(s.stride) + " does not fit format " + format_name(s.format));
      if (s.count > UINT64_MAX / s.stride || s.count * s.stride != s.size)
        return fail(what + ": size " + to_string(s.size) + " is not count " + to_string(s.count) + " x stride " +
                    to_string(s.stride));
      if (s.offset % alignment_ != 0)
        return fail(what + ": offset " + to_string(s.offset) + " is not aligned to " + to_string(alignment_));
      if (s.offset < end) return fail(what + ": overlaps the section table or the section before it");
      if (s.offset > file_size_ || s.size > file_size_ - s.offset)
        return fail(what + ": bytes [" + to_string(s.offset) + ", " + to_string(s.offset + s.size) +
                    ") lie beyond the end of the file (" + to_string(file_size_) + " bytes)");
      for (uint64_t b = end; b < s.offset; ++b)
        if (p[b] != 0) return fail("nonzero padding byte at offset " + to_string(b));
      s.data = p + s.offset;
      uint32_t c = crc32c(s.data, size_t(s.size));
      if (c != s.crc)
        return fail(what + ": checksum mismatch (stored " + detail::hex32(s.crc) + ", computed " + detail::hex32(c) +
                    ")");
      end = s.offset + s.size;
      sections_.push_back(s);
    }
    if (end != file_size_)
      return fail(to_string(file_size_ - end) + " bytes after the last section (corrupt file size)");
    return true;
  }

  std::vector<Section> sections_;
  std::string error_;
  uint16_t version_major_ = 0, version_minor_ = 0;
  uint32_t alignment_ = 0;
  uint64_t file_size_ = 0;
  uint32_t header_crc_ = 0;
};

// ---- Float validation ------------------------------------------------------
//
// Reader::open() checks the container (every byte is what the writer wrote);
// validate_floats() checks what the floats say, for a consumer that hands them
// to a float pipeline (GL, a ray tracer): a file can be intact and still hold a
// NaN or a coordinate of 1e30 (a hostile or buggy writer). It refuses, naming
// the section and the element:
//   - any non-finite float in a float section (f32, f32xN, f64x3, f64x4) or in
//     the float fields of the records (esm_quads, volume_/light_sides,
//     volume_/light_caps: their points; light_params: every double);
//   - a coordinate (positions, frame, record points, a point light's position)
//     whose magnitude is over kMaxCoordinate;
//   - a plane (face_planes, caster_hull, esm_planes, volume_/light_planes) whose normal has
//     a component over 1 + 1e-3 or whose offset is over 2 x kMaxCoordinate;
//   - a light (lights: x, y, z, w) whose w is neither 0 (directional) nor 1
//     (point, as the writer stores it), that is directional with a direction
//     shorter than kMinDirection or longer than kMaxCoordinate, or a point
//     whose position is over kMaxCoordinate.
// Sections of types this reader does not name are checked for finiteness only.
//
// The limit: every coordinate within 1e15 keeps a product of two coordinates
// (cross products, plane offsets, squared lengths: up to 1e30) far inside a
// float's range (3.4e38), leaves room for the projection matrices' sums, and
// keeps a ray from a surface point to a light (up to 2e15 long) within what
// Embree accepts (1.8e18, its ray validity check).
inline constexpr double kMaxCoordinate = 1e15;
inline constexpr double kMinDirection = 1e-15;  // a directional light's shortest direction

namespace detail {
inline double load_float(const unsigned char* p, bool f64) {
  if (f64) {
    double d;
    std::memcpy(&d, p, 8);
    return d;
  }
  float f;
  std::memcpy(&f, p, 4);
  return double(f);
}

// How to check one section: floats per element, where they start, what limit.
struct FloatLayout {
  uint32_t floats = 0;  // float values per element (0: nothing to check)
  uint32_t first = 0;   // byte offset of the first within the element
  bool f64 = false;
  enum Kind { Finite, Coordinates, Planes, Lights } kind = Finite;
};

inline FloatLayout float_layout(const Section& s) {
  FloatLayout l;
  switch (s.format) {
    case Format::F32:
      l.floats = 1;
      break;
    case Format::F32x2:
      l.floats = 2;
      break;
    case Format::F32x3:
      l.floats = 3;
      break;
    case Format::F32x4:
      l.floats = 4;
      break;
    case Format::F64x3:
      l.floats = 3, l.f64 = true;
      break;
    case Format::F64x4:
      l.floats = 4, l.f64 = true;
      break;
    case Format::Record:  // the records' floats (geom/baked_records.h)
      if (s.type == SectionType::EsmQuads || s.type == SectionType::VolumeSides || s.type == SectionType::LightSides)
        l.floats = 6, l.kind = FloatLayout::Coordinates;
      if (s.type == SectionType::VolumeCaps || s.type == SectionType::LightCaps)
        l.floats = 9, l.kind = FloatLayout::Coordinates;
      if (s.type == SectionType::LightParams)  // LightRecord: 13 doubles after 16 bytes of integers
        l.floats = 13, l.first = 16, l.f64 = true;
      if (l.first + uint64_t(l.floats) * (l.f64 ? 8 : 4) > s.stride) l.floats = 0;  // too short: not this layout
      return l;
    default:
      return l;
  }
  switch (s.type) {
    case SectionType::Positions:
    case SectionType::Frame:
      l.kind = FloatLayout::Coordinates;
      break;
    case SectionType::FacePlanes:
    case SectionType::CasterHull:
    case SectionType::EsmPlanes:
    case SectionType::VolumePlanes:
    case SectionType::LightPlanes:
      l.kind = l.floats == 4 ? FloatLayout::Planes : FloatLayout::Finite;
      break;
    case SectionType::Lights:
      l.kind = l.floats == 4 ? FloatLayout::Lights : FloatLayout::Finite;
      break;
    default:
      break;
  }
  return l;
}

// The problem with element values v[0..n), or "" when there is none.
inline std::string float_problem(const double* v, uint32_t n, FloatLayout::Kind kind) {
  char b[160];
  for (uint32_t k = 0; k < n; ++k)
    if (!std::isfinite(v[k])) return std::snprintf(b, sizeof b, "component %u is %g", k, v[k]), b;
  const double limit = kMaxCoordinate;
  if (kind == FloatLayout::Coordinates)
    for (uint32_t k = 0; k < n; ++k)
      if (std::fabs(v[k]) > limit)
        return std::snprintf(b, sizeof b, "component %u is %g, over the coordinate limit %g", k, v[k], limit), b;
  if (kind == FloatLayout::Planes) {
    for (uint32_t k = 0; k < 3; ++k)
      if (std::fabs(v[k]) > 1.001)
        return std::snprintf(b, sizeof b, "plane normal component %u is %g, not within a unit normal", k, v[k]), b;
    if (std::fabs(v[3]) > 2 * limit)
      return std::snprintf(b, sizeof b, "plane offset %g is over the limit %g", v[3], 2 * limit), b;
  }
  if (kind == FloatLayout::Lights) {
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (v[3] == 0 && !(length >= kMinDirection && length <= limit))
      return std::snprintf(b, sizeof b, "directional light direction of length %g, not within [%g, %g]", length,
                           kMinDirection, limit),
             b;
    if (v[3] != 0 && v[3] != 1)
      return std::snprintf(b, sizeof b, "light w is %g, neither 0 (directional) nor 1 (point)", v[3]), b;
    for (uint32_t k = 0; v[3] == 1 && k < 3; ++k)
      if (std::fabs(v[k]) > limit)
        return std::snprintf(b, sizeof b, "point light coordinate %u is %g, over the coordinate limit %g", k, v[k],
                             limit),
               b;
  }
  return "";
}
}  // namespace detail

// Checks the floats of one section (see above). False with `error`: "section
// I 'NAME' (TYPE): element E: PROBLEM".
inline bool validate_section_floats(const Section& s, size_t index, std::string& error) {
  const detail::FloatLayout l = detail::float_layout(s);
  if (l.floats == 0 || !s.data) return true;
  const uint32_t width = l.f64 ? 8 : 4;
  double v[16];
  for (uint64_t e = 0; e < s.count; ++e) {
    const unsigned char* p = s.data + e * s.stride + l.first;
    for (uint32_t k = 0; k < l.floats; ++k) v[k] = detail::load_float(p + size_t(k) * width, l.f64);
    const std::string problem = detail::float_problem(v, l.floats, l.kind);
    if (!problem.empty()) {
      error = "section " + std::to_string(index) + " '" + s.name + "' (" + type_name(s.type) + "): element " +
              std::to_string(e) + ": " + problem;
      return false;
    }
  }
  return true;
}

// Checks the floats of every section of an opened reader.
inline bool validate_floats(const Reader& reader, std::string& error) {
  for (size_t i = 0; i < reader.sections().size(); ++i)
    if (!validate_section_floats(reader.sections()[i], i, error)) return false;
  return true;
}

}  // namespace baked
}  // namespace geom
