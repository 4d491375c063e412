// STL import, binary and ASCII.
//
// Binary: an 80-byte header, a little-endian uint32 triangle count n, then n
// records of 50 bytes (normal, 3 corners as float32 xyz, a 16-bit attribute).
// ASCII: `solid name` ... `facet normal nx ny nz` `outer loop` `vertex x y z`
// x3 `endloop` `endfacet` ... `endsolid name`, keywords in any case, several
// solids in one file allowed.
//
// Which one: a file whose size is exactly 84 + 50 n is binary, even when its
// header begins with "solid" (many exporters write that). Otherwise a file
// that begins with "solid" and holds no NUL byte is ASCII (or, if it does not
// parse as ASCII and its count fits, binary with trailing bytes); anything
// else is binary, refused when shorter than its count says (trailing bytes
// only warn).
//
// STL shares no vertices: each triangle gets 3 fresh vertices (corner order
// kept, the stored normal ignored); geom::weld recovers the topology. A facet
// with more than 3 vertices is fanned, one with fewer skipped (one warning).
// TriangleSource::mesh stays kNone (STL has no meshes).
#include <cstdint>
#include <cstring>
#include <string>

#include "importers.h"
#include "text_scan.h"

namespace geom::detail {
namespace {

float load_le_f32(const unsigned char* b) {
  uint32_t u = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

bool import_binary(const ImportInput& in, uint64_t n, Scene& out, std::string& error) {
  const uint64_t need = 84 + 50 * n;
  if (need > in.size) {
    error = "binary STL header says " + std::to_string(n) + " triangles (" + std::to_string(need) +
            " bytes) but the file has " + std::to_string(in.size) + " bytes";
    return false;
  }
  if (need < in.size)
    out.warnings.push_back(in.name + ": " + std::to_string(in.size - need) +
                           " bytes after the last binary STL triangle ignored");
  const size_t base = out.vertex_count();
  if (base + 3 * n > 0xffffffffu) {
    error = "more than 4294967295 vertices";
    return false;
  }
  // Straight into the scene's arrays (sized once, no per-value push).
  const size_t p0 = out.positions.size(), i0 = out.indices.size();
  out.positions.resize(p0 + 9 * size_t(n));
  out.indices.resize(i0 + 3 * size_t(n));
  out.sources.resize(out.sources.size() + n);
  float* pos = out.positions.data() + p0;
  uint32_t* idx = out.indices.data() + i0;
  const unsigned char* rec = in.data + 84;
  for (uint64_t t = 0; t < n; ++t, rec += 50, pos += 9, idx += 3) {
    for (int k = 0; k < 9; ++k) pos[k] = load_le_f32(rec + 12 + 4 * k);
    for (int k = 0; k < 3; ++k) idx[k] = uint32_t(base + 3 * t + k);
  }
  return true;
}

// "line N: " for a position in the text.
std::string line_of(const ImportInput& in, const char* at) {
  uint64_t line = 1;
  for (const char* q = reinterpret_cast<const char*>(in.data); q < at; ++q)
    line += *q == '\n' || (*q == '\r' && !(q + 1 < at && q[1] == '\n'));
  return "line " + std::to_string(line) + ": ";
}

// The facet being read: its first three corners, the latest one after them.
struct AsciiFacet {
  float corner[3 * 3];
  float extra[3];
  size_t corners = 0;  // vertices seen in the current facet
  bool open = false;
  uint64_t bad = 0;  // facets with fewer than 3 vertices
};

// A `vertex x y z` line of the open facet; from the fourth corner on, the
// facet is fanned from its first corner as it comes.
bool read_vertex(const ImportInput& in, const char*& p, const char* end, AsciiFacet& f, Scene& out,
                 std::string& error) {
  float* xyz = f.corners < 3 ? f.corner + 3 * f.corners : f.extra;
  for (int k = 0; k < 3; ++k) {
    std::string_view tok = next_token(p, end);
    const char* q = tok.data();
    if (tok.empty() || !scan_float(q, tok.data() + tok.size(), xyz[k])) {
      error = line_of(in, tok.data()) + "bad vertex coordinate " + quote_token(tok);
      return false;
    }
  }
  if (f.corners >= 3) {  // a polygon facet: fan from its first corner
    if (f.corners == 3) {
      const size_t a = out.vertex_count();
      out.positions.insert(out.positions.end(), f.corner, f.corner + 9);
      out.indices.insert(out.indices.end(), {uint32_t(a), uint32_t(a + 1), uint32_t(a + 2)});
      out.sources.push_back(TriangleSource{});
    }
    const size_t v = out.vertex_count();
    out.positions.insert(out.positions.end(), xyz, xyz + 3);
    out.indices.insert(out.indices.end(), {uint32_t(v - f.corners), uint32_t(v - 1), uint32_t(v)});
    out.sources.push_back(TriangleSource{});
  }
  ++f.corners;
  return true;
}

// `endfacet`: a triangle facet is emitted here, one with fewer corners counted.
void close_facet(AsciiFacet& f, Scene& out) {
  f.open = false;
  if (f.corners == 3) {
    const size_t v = out.vertex_count();
    out.positions.insert(out.positions.end(), f.corner, f.corner + 9);
    out.indices.insert(out.indices.end(), {uint32_t(v), uint32_t(v + 1), uint32_t(v + 2)});
    out.sources.push_back(TriangleSource{});
  } else if (f.corners < 3) {
    ++f.bad;
  }
}

// One keyword of the ASCII grammar and what follows it on its line.
bool read_keyword(const ImportInput& in, std::string_view w, const char*& p, const char* end, AsciiFacet& f, Scene& out,
                  std::string& error) {
  if (token_is(w, "solid") || token_is(w, "endsolid")) {
    if (f.open) {
      error = line_of(in, w.data()) + "'" + std::string(w) + "' inside a facet";
      return false;
    }
    while (p < end && !is_eol(*p)) ++p;  // the name runs to the end of the line
  } else if (token_is(w, "facet")) {
    if (f.open) {
      error = line_of(in, w.data()) + "facet without endfacet";
      return false;
    }
    f.open = true;
    f.corners = 0;
    while (p < end && !is_eol(*p)) ++p;  // "normal nx ny nz" is ignored
  } else if (token_is(w, "vertex")) {
    if (!f.open) {
      error = line_of(in, w.data()) + "vertex outside a facet";
      return false;
    }
    return read_vertex(in, p, end, f, out, error);
  } else if (token_is(w, "endfacet")) {
    if (!f.open) {
      error = line_of(in, w.data()) + "endfacet without facet";
      return false;
    }
    close_facet(f, out);
  } else if (token_is(w, "outer") || token_is(w, "loop") || token_is(w, "endloop")) {
    // structure only
  } else {
    error = line_of(in, w.data()) + "unexpected " + quote_token(w) + " in ASCII STL";
    return false;
  }
  return true;
}

bool import_ascii(const ImportInput& in, Scene& out, std::string& error) {
  const char* p = reinterpret_cast<const char*>(in.data);
  const char* end = p + in.size;
  const size_t base = out.vertex_count();
  AsciiFacet f;
  for (;;) {
    std::string_view w = next_word(p, end);
    if (w.empty()) break;
    if (!read_keyword(in, w, p, end, f, out, error)) return false;
    if (out.vertex_count() - base > 0xffffffffu - 3) {
      error = "more than 4294967295 vertices";
      return false;
    }
  }
  if (f.open) {
    error = "file ends inside a facet";
    return false;
  }
  if (f.bad)
    out.warnings.push_back(in.name + ": " + std::to_string(f.bad) + " facets with fewer than 3 vertices skipped");
  return true;
}

bool begins_with_solid(const ImportInput& in) {
  const char* p = reinterpret_cast<const char*>(in.data);
  const char* end = p + in.size;
  p = skip_white(skip_utf8_bom(p, end), end);
  return end - p >= 5 && token_is(std::string_view(p, 5), "solid") && (end - p == 5 || is_white(p[5]));
}

}  // namespace

bool import_stl(const ImportInput& in, Scene& out, std::string& error) {
  uint64_t n = 0;
  if (in.size >= 84)
    n = uint64_t(in.data[80]) | uint64_t(in.data[81]) << 8 | uint64_t(in.data[82]) << 16 | uint64_t(in.data[83]) << 24;
  if (in.size >= 84 && 84 + 50 * n == in.size) return import_binary(in, n, out, error);
  // ASCII STL is text: a NUL byte anywhere means binary.
  if (begins_with_solid(in) && !std::memchr(in.data, 0, in.size)) {
    if (looks_like_utf16(in.data, in.size)) {
      error = "UTF-16 or UTF-32 text is not supported (save the STL as ASCII)";
      return false;
    }
    const size_t np = out.positions.size(), ni = out.indices.size(), ns = out.sources.size(), nw = out.warnings.size();
    if (import_ascii(in, out, error)) return true;
    // Not ASCII after all: a binary file whose header begins with "solid" and
    // that carries bytes after its records.
    if (in.size < 84 || 84 + 50 * n > in.size) return false;
    out.positions.resize(np), out.indices.resize(ni), out.sources.resize(ns), out.warnings.resize(nw);
    error.clear();
    return import_binary(in, n, out, error);
  }
  if (in.size < 84) {
    error = in.size == 0 ? "empty file"
                         : "too short for a binary STL (" + std::to_string(in.size) +
                               " bytes, the header alone is 84) and not ASCII STL";
    return false;
  }
  return import_binary(in, n, out, error);
}

}  // namespace geom::detail
