// Stanford PLY import: ascii, binary_little_endian, binary_big_endian.
//
// Header: `ply`, `format F 1.0`, `comment` / `obj_info` lines, then
// `element NAME COUNT` each followed by its `property TYPE NAME` or
// `property list COUNT_TYPE ITEM_TYPE NAME` lines, then `end_header` (other
// header lines are ignored with a warning). Header
// lines may end in LF, CRLF or CR alone (binary data starts right after the
// end_header line, whose line end is taken to be the one the `ply` line used).
// Scalar types: char uchar short ushort int uint float double and their
// int8 ... float64 aliases.
//
// Used: the first `vertex` element's x, y, z (any scalar type), the first
// `face` element's list `vertex_indices` (or `vertex_index`), polygons fanned
// from their first corner (fewer than 3 corners: skipped, one warning), and
// the first `tristrips` element's list `vertex_indices` (-1 restarts a strip;
// the degenerate triangles that stitch strips are dropped). Everything else
// is read past. Indices are 0-based and checked against the vertex count the
// header declares: "face 12: vertex index 40 out of range (8 vertices)".
//
// Hostile input: before an element is read, its count times the smallest
// size one entry can take (binary: the sum of its scalar sizes; ascii: 2
// bytes per property) is checked against the bytes left, and each list's
// length against the bytes left, so a header claiming billions of entries is
// refused before any allocation.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "importers.h"
#include "text_scan.h"

namespace geom::detail {
namespace {

enum class PlyType : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };
enum class Format : uint8_t { Ascii, LittleEndian, BigEndian };

bool parse_type(std::string_view s, PlyType& t) {
  static const struct {
    const char* a;
    const char* b;
    PlyType t;
  } names[] = {{"char", "int8", PlyType::I8},      {"uchar", "uint8", PlyType::U8},    {"short", "int16", PlyType::I16},
               {"ushort", "uint16", PlyType::U16}, {"int", "int32", PlyType::I32},     {"uint", "uint32", PlyType::U32},
               {"float", "float32", PlyType::F32}, {"double", "float64", PlyType::F64}};
  for (const auto& n : names)
    if (s == n.a || s == n.b) {
      t = n.t;
      return true;
    }
  return false;
}

size_t type_size(PlyType t) {
  static const size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[size_t(t)];
}

struct Property {
  std::string name;
  PlyType type = PlyType::F32;  // item type for lists
  bool list = false;
  PlyType count_type = PlyType::U8;  // lists only
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
  uint64_t header_line = 0;
};

// Reads one scalar at a time from the body, in any of the three formats.
struct Body {
  const unsigned char* p;
  const unsigned char* end;
  Format format;

  uint64_t left() const { return uint64_t(end - p); }

  bool read(PlyType t, double& v) {
    if (format == Format::Ascii) {
      const char* e = reinterpret_cast<const char*>(end);
      const char* c = skip_white(reinterpret_cast<const char*>(p), e);
      if (c >= e || !scan_double(c, e, v)) return false;
      p = reinterpret_cast<const unsigned char*>(c);
      // Integer types: a whole number within the type's range.
      static const double lo[] = {-128, 0, -32768, 0, -2147483648.0, 0};
      static const double hi[] = {127, 255, 32767, 65535, 2147483647.0, 4294967295.0};
      if (t != PlyType::F32 && t != PlyType::F64 && !(v == std::floor(v) && v >= lo[size_t(t)] && v <= hi[size_t(t)]))
        return false;
      return true;
    }
    const size_t n = type_size(t);
    if (left() < n) return false;
    unsigned char b[8];
    for (size_t i = 0; i < n; ++i) b[i] = format == Format::LittleEndian ? p[i] : p[n - 1 - i];
    p += n;
    // b now holds the value little-endian; assemble it portably.
    uint64_t u = 0;
    for (size_t i = 0; i < n; ++i) u |= uint64_t(b[i]) << (8 * i);
    switch (t) {
      case PlyType::I8:
        v = double(int8_t(uint8_t(u)));
        break;
      case PlyType::U8:
        v = double(uint8_t(u));
        break;
      case PlyType::I16:
        v = double(int16_t(uint16_t(u)));
        break;
      case PlyType::U16:
        v = double(uint16_t(u));
        break;
      case PlyType::I32:
        v = double(int32_t(uint32_t(u)));
        break;
      case PlyType::U32:
        v = double(uint32_t(u));
        break;
      case PlyType::F32: {
        uint32_t w = uint32_t(u);
        float f;
        std::memcpy(&f, &w, 4);
        v = f;
        break;
      }
      case PlyType::F64:
        std::memcpy(&v, &u, 8);
        break;
    }
    return true;
  }
};

// Header lines: split at LF, CRLF or CR.
struct HeaderLines {
  const char* p;
  const char* end;
  uint64_t line = 0;
  std::string_view eol;  // the line end the first line used

  bool next(std::string_view& out) {
    if (p >= end) return false;
    const char* b = p;
    while (p < end && !is_eol(*p)) ++p;
    out = std::string_view(b, size_t(p - b));
    const char* e = p;
    if (p < end) {
      if (*p == '\r' && p + 1 < end && p[1] == '\n') ++p;
      ++p;
    }
    if (eol.empty()) eol = std::string_view(e, size_t(p - e));
    ++line;
    return true;
  }
};

// A value for a message: whole numbers without a fraction.
std::string show(double v) {
  if (std::fabs(v) < 1e15 && v == std::floor(v)) return std::to_string(int64_t(v));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string number_or_end(const Body& body) {
  const unsigned char* p = body.p;
  if (body.format == Format::Ascii)
    while (p < body.end && is_white(char(*p))) ++p;
  return p >= body.end ? "file ends early" : "bad value";
}

// One binary scalar at `p` as a double (`big`: big-endian).
double load_scalar(PlyType t, const unsigned char* p, bool big) {
  const size_t n = type_size(t);
  uint64_t u = 0;
  for (size_t i = 0; i < n; ++i) u |= uint64_t(p[big ? n - 1 - i : i]) << (8 * i);
  switch (t) {
    case PlyType::I8:
      return double(int8_t(uint8_t(u)));
    case PlyType::U8:
      return double(uint8_t(u));
    case PlyType::I16:
      return double(int16_t(uint16_t(u)));
    case PlyType::U16:
      return double(uint16_t(u));
    case PlyType::I32:
      return double(int32_t(uint32_t(u)));
    case PlyType::U32:
      return double(uint32_t(u));
    case PlyType::F32: {
      const uint32_t w = uint32_t(u);
      float f;
      std::memcpy(&f, &w, 4);
      return f;
    }
    case PlyType::F64: {
      double d;
      std::memcpy(&d, &u, 8);
      return d;
    }
  }
  return 0;
}

// The binary fast paths: a whole element read straight into the scene's
// arrays, with the general reader's results. False (having read nothing the
// caller keeps) on anything they do not take or anything wrong: the general
// reader then reads the element and says what is wrong.

// A vertex element of scalars only: its x, y, z (`role_of[i]`: 0 skip, 1..3 x..z).
bool fast_vertices(const Element& el, const std::vector<uint8_t>& role_of, Body& body, std::vector<float>& positions) {
  size_t record = 0, offset[3] = {0, 0, 0};
  PlyType type[3] = {PlyType::F32, PlyType::F32, PlyType::F32};
  for (size_t i = 0; i < el.props.size(); ++i) {
    if (el.props[i].list) return false;
    if (role_of[i]) offset[role_of[i] - 1] = record, type[role_of[i] - 1] = el.props[i].type;  // the last one wins
    record += type_size(el.props[i].type);
  }
  if (record == 0 || el.count > body.left() / record) return false;
  const bool big = body.format == Format::BigEndian;
  const size_t at = positions.size(), n = size_t(el.count);
  positions.resize(at + 3 * n);
  float* out = positions.data() + at;
  const unsigned char* p = body.p;
  const bool plain = !big && type[0] == PlyType::F32 && type[1] == PlyType::F32 && type[2] == PlyType::F32;
  if (plain && record == 12 && offset[0] == 0 && offset[1] == 4 && offset[2] == 8) {
    std::memcpy(out, p, 12 * n);
  } else {
    for (size_t k = 0; k < n; ++k, p += record, out += 3)
      for (int c = 0; c < 3; ++c) {
        if (plain)
          std::memcpy(out + c, p + offset[c], 4);
        else
          out[c] = to_float(load_scalar(type[c], p + offset[c], big));
      }
  }
  body.p += record * n;
  return true;
}

// A face element whose one property is the integer list of vertex indices:
// polygons fanned from their first corner, fewer than 3 corners counted in `short_faces`.
bool fast_faces(const Element& el, Body& body, size_t base, uint64_t vertex_count, Scene& out, uint64_t& short_faces) {
  if (el.props.size() != 1) return false;
  const Property& prop = el.props[0];
  if (!prop.list || (prop.type != PlyType::I32 && prop.type != PlyType::U32)) return false;
  const bool big = body.format == Format::BigEndian;
  const size_t cs = type_size(prop.count_type);
  const bool u8 = prop.count_type == PlyType::U8;
  std::vector<uint32_t>& ix = out.indices;
  const size_t first = ix.size();
  size_t at = first;
  ix.resize(first + 3 * size_t(std::min<uint64_t>(el.count, body.left() / (cs + 12))));
  std::vector<uint32_t> poly;
  const unsigned char* p = body.p;
  const unsigned char* const end = body.end;
  const uint32_t b = uint32_t(base);
  auto index = [&](const unsigned char* q, uint32_t& v) {
    uint32_t w;
    if (big)
      w = uint32_t(q[3]) | uint32_t(q[2]) << 8 | uint32_t(q[1]) << 16 | uint32_t(q[0]) << 24;
    else
      std::memcpy(&w, q, 4);
    const int64_t i = prop.type == PlyType::I32 ? int64_t(int32_t(w)) : int64_t(w);
    if (i < 0 || uint64_t(i) >= vertex_count) return false;
    v = b + uint32_t(i);
    return true;
  };
  for (uint64_t k = 0; k < el.count; ++k) {
    if (size_t(end - p) < cs) return false;
    const double nd = u8 ? double(*p) : load_scalar(prop.count_type, p, big);
    p += cs;
    if (nd < 0 || nd > double(size_t(end - p) / 4)) return false;
    const size_t n = size_t(nd);
    if (n == 3) {
      if (at + 3 > ix.size()) ix.resize(std::max(2 * ix.size(), at + 3));
      uint32_t* t = ix.data() + at;
      if (!index(p, t[0]) || !index(p + 4, t[1]) || !index(p + 8, t[2])) return false;
      p += 12, at += 3;
      continue;
    }
    poly.resize(n);
    for (size_t j = 0; j < n; ++j, p += 4)
      if (!index(p, poly[j])) return false;
    if (n < 3) {
      ++short_faces;
      continue;
    }
    if (at + 3 * (n - 2) > ix.size()) ix.resize(std::max(2 * ix.size(), at + 3 * (n - 2)));
    for (size_t j = 1; j + 1 < n; ++j, at += 3) ix[at] = poly[0], ix[at + 1] = poly[j], ix[at + 2] = poly[j + 1];
  }
  ix.resize(at);
  out.sources.resize(out.sources.size() + (at - first) / 3);  // TriangleSource{} each
  body.p = p;
  return true;
}

// ---------------------------------------------------------------------------
// The header.

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  const char* body_start = nullptr;  // the first byte after end_header's line
};

// The first line must be `ply`; otherwise says what the file looks like.
bool read_magic(const ImportInput& in, HeaderLines& h, std::string& error) {
  std::string_view line, first;
  if (h.next(line)) {
    const char* c = line.data();
    first = next_token(c, c + line.size());
  }
  if (first == "ply") return true;
  if (looks_like_utf16(in.data, in.size))
    error = "UTF-16 or UTF-32 text is not supported (save the PLY as ASCII)";
  else
    error = in.size == 0 ? "empty file" : "not a PLY file (starts with " + quote_token(first) + ", not 'ply')";
  return false;
}

// The rest of a `format F 1.0` line.
bool read_format_line(const char*& c, const char* e, const std::string& at, Format& format, std::string& error) {
  std::string_view f = next_token(c, e);
  if (f == "ascii")
    format = Format::Ascii;
  else if (f == "binary_little_endian")
    format = Format::LittleEndian;
  else if (f == "binary_big_endian")
    format = Format::BigEndian;
  else {
    error = at + "unknown format " + quote_token(f);
    return false;
  }
  return true;
}

// The rest of an `element NAME COUNT` line.
bool read_element_line(const char*& c, const char* e, const std::string& at, uint64_t line,
                       std::vector<Element>& elements, std::string& error) {
  Element el;
  el.name = std::string(next_token(c, e));
  std::string_view n = next_token(c, e);
  const char* q = n.data();
  int64_t count = -1;
  if (el.name.empty() || n.empty() || !scan_int(q, n.data() + n.size(), count) || count < 0) {
    error = at + "element needs a name and a count";
    return false;
  }
  el.count = uint64_t(count);
  el.header_line = line;
  elements.push_back(std::move(el));
  return true;
}

// The rest of a `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME` line.
bool read_property_line(const char*& c, const char* e, const std::string& at, std::vector<Element>& elements,
                        std::string& error) {
  if (elements.empty()) {
    error = at + "property before any element";
    return false;
  }
  Property prop;
  std::string_view t = next_token(c, e);
  if (t == "list") {
    prop.list = true;
    std::string_view ct = next_token(c, e);
    if (!parse_type(ct, prop.count_type) || prop.count_type == PlyType::F32 || prop.count_type == PlyType::F64) {
      error = at + "bad list count type " + quote_token(ct);
      return false;
    }
    t = next_token(c, e);
  }
  if (!parse_type(t, prop.type)) {
    error = at + "unknown property type " + quote_token(t);
    return false;
  }
  prop.name = std::string(next_token(c, e));
  if (prop.name.empty()) {
    error = at + "property without a name";
    return false;
  }
  elements.back().props.push_back(std::move(prop));
  return true;
}

// From the `ply` line to end_header: the format, the elements and where the body starts.
bool read_header(const ImportInput& in, Header& hdr, Scene& out, std::string& error) {
  const char* text = reinterpret_cast<const char*>(in.data);
  HeaderLines h{text, text + in.size, 0, std::string_view()};
  if (!read_magic(in, h, error)) return false;
  bool have_format = false, have_end = false;
  uint64_t unknown_lines = 0;
  std::string_view line;
  while (!have_end && h.next(line)) {
    const char* c = line.data();
    const char* e = c + line.size();
    std::string_view kw = next_token(c, e);
    const std::string at = "header line " + std::to_string(h.line) + ": ";
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      if (!read_format_line(c, e, at, hdr.format, error)) return false;
      have_format = true;
    } else if (kw == "element") {
      if (!read_element_line(c, e, at, h.line, hdr.elements, error)) return false;
    } else if (kw == "property") {
      if (!read_property_line(c, e, at, hdr.elements, error)) return false;
    } else if (kw == "end_header") {
      have_end = true;
    } else {
      ++unknown_lines;  // e.g. Blender 2.4's bare "Created by ..." line
    }
  }
  if (!have_end) {
    error = "header has no end_header line";
    return false;
  }
  if (!have_format) {
    error = "header has no format line";
    return false;
  }
  if (unknown_lines)
    out.warnings.push_back(in.name + ": " + std::to_string(unknown_lines) + " unknown PLY header lines ignored");
  // In binary files the body starts right after end_header's line end; with
  // CR-only headers a following '\n' byte is data, not part of the line end.
  hdr.body_start = h.p;
  if (hdr.format != Format::Ascii && h.eol == "\r" && hdr.body_start > text && hdr.body_start[-1] == '\n' &&
      hdr.body_start - 2 >= text && hdr.body_start[-2] == '\r')
    --hdr.body_start;
  return true;
}

// ---------------------------------------------------------------------------
// The body.

// What a property of the element being read is used for.
enum Role : uint8_t { Skip, X, Y, Z, Indices };

// The state of the body's read, across its elements.
struct BodyReader {
  BodyReader(const ImportInput& in_, Scene& out_, Body body_) : in(in_), out(out_), body(body_) {}
  const ImportInput& in;
  Scene& out;
  Body body;
  size_t base = 0;            // the scene's vertex count before this file
  uint64_t vertex_count = 0;  // the vertex element's count, what indices are checked against
  bool done_vertex = false, done_face = false, done_strips = false;
  uint64_t short_faces = 0;
  std::vector<uint32_t> poly;
};

// Refuses an element whose count cannot fit in the bytes left, before any allocation.
bool element_fits(const Element& el, const Body& body, std::string& error) {
  uint64_t min_bytes = 0;
  for (const Property& p : el.props)
    min_bytes += body.format == Format::Ascii ? 2 : type_size(p.list ? p.count_type : p.type);
  if (el.count > (body.left() + 1) / min_bytes) {
    error = "element '" + el.name + "' (header line " + std::to_string(el.header_line) + ") claims " +
            std::to_string(el.count) + " entries of at least " + std::to_string(min_bytes) + " bytes but only " +
            std::to_string(body.left()) + " bytes are left";
    return false;
  }
  return true;
}

// Each property's role; returns the roles found (bits 0-2: x, y, z; bit 3: the index list).
int assign_roles(const Element& el, bool is_vertex, bool is_list_element, std::vector<Role>& roles) {
  roles.assign(el.props.size(), Skip);
  int found = 0;
  for (size_t i = 0; i < el.props.size(); ++i) {
    const Property& p = el.props[i];
    if (is_vertex && !p.list && (p.name == "x" || p.name == "y" || p.name == "z")) {
      roles[i] = p.name == "x" ? X : p.name == "y" ? Y : Z;
      found |= 1 << (roles[i] - X);
    }
    if (is_list_element && p.list && (p.name == "vertex_indices" || p.name == "vertex_index") && !(found & 8)) {
      roles[i] = Indices;
      found |= 8;
    }
  }
  return found;
}

// The binary fast path of a vertex or face element; false (nothing kept, the
// body where it was) where the general reader must read it.
bool read_fast(BodyReader& r, const Element& el, const std::vector<Role>& roles, bool is_vertex) {
  Scene& out = r.out;
  const size_t np = out.positions.size(), ni = out.indices.size(), ns = out.sources.size();
  const unsigned char* start = r.body.p;
  uint64_t shorts = 0;
  std::vector<uint8_t> role_of(roles.size(), 0);
  for (size_t i = 0; i < roles.size(); ++i) role_of[i] = roles[i] >= X && roles[i] <= Z ? uint8_t(roles[i]) : 0;
  if (is_vertex ? fast_vertices(el, role_of, r.body, out.positions)
                : fast_faces(el, r.body, r.base, r.vertex_count, out, shorts)) {
    r.short_faces += shorts;
    return true;
  }
  out.positions.resize(np), out.indices.resize(ni), out.sources.resize(ns);  // the general reader says why
  r.body.p = start;
  return false;
}

// A polygon fanned from its first corner; fewer than 3 corners counted.
void emit_polygon(const std::vector<uint32_t>& poly, Scene& out, uint64_t& short_faces) {
  if (poly.size() < 3) ++short_faces;
  for (size_t j = 1; j + 1 < poly.size(); ++j) {
    out.indices.insert(out.indices.end(), {poly[0], poly[j], poly[j + 1]});
    out.sources.push_back(TriangleSource{});
  }
}

// A triangle strip: a window of 3, alternating winding, restarted at -1
// (0xffffffff); the degenerate triangles that stitch strips are dropped.
void emit_strip(const std::vector<uint32_t>& poly, Scene& out) {
  size_t start = 0;
  for (size_t j = 0; j < poly.size(); ++j) {
    if (poly[j] == 0xffffffffu) {
      start = j + 1;
      continue;
    }
    if (j < start + 2) continue;
    uint32_t a = poly[j - 2], b = poly[j - 1], c = poly[j];
    if ((j - start) % 2 == 1) std::swap(a, b);
    if (a == b || b == c || a == c) continue;
    out.indices.insert(out.indices.end(), {a, b, c});
    out.sources.push_back(TriangleSource{});
  }
}

// "vertex 12: ", "face 3: ", or "element 'NAME' entry 5: ".
std::string entry_where(const char* what, const Element& el, uint64_t k) {
  return (what ? std::string(what) : "element '" + el.name + "' entry ") + std::to_string(k) + ": ";
}

// One list property of entry k: its items read past, or, for the index list,
// checked and emitted as a polygon or a strip.
bool read_list(BodyReader& r, const Element& el, const char* what, uint64_t k, const Property& p, Role role,
               bool is_face, bool is_strips, std::string& error) {
  Body& body = r.body;
  double v, nd;
  if (!body.read(p.count_type, nd) || nd < 0) {
    error = entry_where(what, el, k) + number_or_end(body) + " for the length of list '" + p.name + "'";
    return false;
  }
  const uint64_t n = uint64_t(nd);
  const uint64_t item_bytes = body.format == Format::Ascii ? 1 : type_size(p.type);
  if (n > (body.left() + 1) / item_bytes) {
    error = entry_where(what, el, k) + "list '" + p.name + "' claims " + std::to_string(n) + " items but only " +
            std::to_string(body.left()) + " bytes are left";
    return false;
  }
  if (role != Indices) {
    for (uint64_t j = 0; j < n; ++j)
      if (!body.read(p.type, v)) {
        error = entry_where(what, el, k) + number_or_end(body) + " in list '" + p.name + "'";
        return false;
      }
    return true;
  }
  r.poly.clear();
  for (uint64_t j = 0; j < n; ++j) {
    if (!body.read(p.type, v)) {
      error = entry_where(what, el, k) + number_or_end(body) + " in list '" + p.name + "'";
      return false;
    }
    if (is_strips && v == -1) {
      r.poly.push_back(0xffffffffu);  // restart
      continue;
    }
    if (!(v >= 0 && v < double(r.vertex_count) && v == std::floor(v))) {
      error = entry_where(what, el, k) + "vertex index " + show(v) + " out of range (" +
              std::to_string(r.vertex_count) + " vertices)";
      return false;
    }
    r.poly.push_back(uint32_t(r.base + uint64_t(v)));
  }
  if (is_face)
    emit_polygon(r.poly, r.out, r.short_faces);
  else
    emit_strip(r.poly, r.out);
  return true;
}

// The general reader: every entry of the element, value by value, in any format.
bool read_entries(BodyReader& r, const Element& el, const std::vector<Role>& roles, bool is_vertex, bool is_face,
                  bool is_strips, std::string& error) {
  const char* what = is_vertex ? "vertex " : is_face ? "face " : is_strips ? "strip " : nullptr;
  for (uint64_t k = 0; k < el.count; ++k) {
    float xyz[3] = {0, 0, 0};
    for (size_t i = 0; i < el.props.size(); ++i) {
      const Property& p = el.props[i];
      if (p.list) {
        if (!read_list(r, el, what, k, p, roles[i], is_face, is_strips, error)) return false;
        continue;
      }
      double v;
      if (!r.body.read(p.type, v)) {
        error = entry_where(what, el, k) + number_or_end(r.body) + " for property '" + p.name + "'";
        return false;
      }
      if (roles[i] >= X && roles[i] <= Z) xyz[roles[i] - X] = to_float(v);
    }
    if (is_vertex) r.out.positions.insert(r.out.positions.end(), xyz, xyz + 3);
  }
  return true;
}

// One element: the first `vertex`, `face` and `tristrips` are read into the
// scene, any other is read past.
bool read_element(BodyReader& r, const Element& el, std::string& error) {
  if (el.count == 0) return true;
  if (el.props.empty()) return true;  // nothing to read, however many entries
  if (!element_fits(el, r.body, error)) return false;
  const bool is_vertex = el.name == "vertex" && !r.done_vertex;
  const bool is_face = el.name == "face" && !r.done_face;
  const bool is_strips = el.name == "tristrips" && !r.done_strips;
  std::vector<Role> roles;
  const int found = assign_roles(el, is_vertex, is_face || is_strips, roles);
  if (is_vertex) {
    if (found != 7) {
      error = "vertex element has no x, y and z properties";
      return false;
    }
    r.out.positions.reserve(r.out.positions.size() + 3 * el.count);
    r.done_vertex = true;
  }
  if ((is_face || is_strips) && !(found & 8)) {
    r.out.warnings.push_back(r.in.name + ": element '" + el.name + "' has no list property vertex_indices; skipped");
  }
  if (is_face && (found & 8)) {
    r.out.indices.reserve(r.out.indices.size() + 3 * std::min<uint64_t>(el.count, r.body.left() / 4));
    r.done_face = true;
  }
  if (is_strips && (found & 8)) r.done_strips = true;
  if (r.body.format != Format::Ascii && (is_vertex || (is_face && (found & 8))) && read_fast(r, el, roles, is_vertex))
    return true;
  return read_entries(r, el, roles, is_vertex, is_face, is_strips, error);
}
}  // namespace

bool import_ply(const ImportInput& in, Scene& out, std::string& error) {
  Header hdr;
  if (!read_header(in, hdr, out, error)) return false;
  BodyReader r(in, out, Body{reinterpret_cast<const unsigned char*>(hdr.body_start), in.data + in.size, hdr.format});
  r.base = out.vertex_count();
  for (const Element& el : hdr.elements)
    if (el.name == "vertex") {
      r.vertex_count = el.count;
      break;
    }
  if (r.base + r.vertex_count > 0xffffffffu) {
    error = "more than 4294967295 vertices";
    return false;
  }
  for (const Element& el : hdr.elements)
    if (!read_element(r, el, error)) return false;
  if (!r.done_face && !r.done_strips)
    out.warnings.push_back(in.name + ": no face element: no triangles (a point cloud?)");
  if (r.short_faces)
    out.warnings.push_back(in.name + ": " + std::to_string(r.short_faces) +
                           " faces with fewer than 3 vertices skipped");
  return true;
}

}  // namespace geom::detail
