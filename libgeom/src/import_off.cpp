// Object File Format (OFF, Geomview) import, ASCII.
//
//   [ST][C][N][4][n]OFF      keyword (may be absent: the file then starts with the counts)
//   [dim]                    only with the n prefix: the space dimension
//   nv nf ne                 counts (ne, the edge count, is read and ignored)
//   x y z [...]              nv vertex lines; the first 3 coordinates are used
//                            (4OFF: x/w y/w z/w), normals, colours and texture
//                            coordinates after them are ignored
//   k i0 i1 ... [colour]     nf face lines, 0-based indices; polygons are fanned
//                            from i0, faces with k < 3 are skipped (one warning)
//
// `#` starts a comment to the end of the line, anywhere. Vertex and face
// records are read one per line (colour fields vary in length), so a record
// must start on a new line. "OFF BINARY" is refused. The counts are checked
// against the bytes left before anything is allocated: every vertex takes at
// least 6 bytes ("0 0 0\n") and every face 2, so a header claiming billions of
// vertices (assimp's invalid/OutOfMemory.off) is refused at once.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "importers.h"
#include "text_scan.h"

namespace geom::detail {
namespace {

// Cursor over the text that treats `#...` as white space.
struct OffText {
  const char* p;
  const char* end;
  uint64_t line = 1;

  void skip_white_and_comments() {
    while (p < end) {
      if (*p == '#') {
        while (p < end && !is_eol(*p)) ++p;
      } else if (is_eol(*p)) {
        if (*p == '\r' && p + 1 < end && p[1] == '\n') ++p;
        ++p;
        ++line;
      } else if (is_space(*p)) {
        ++p;
      } else {
        return;
      }
    }
  }
  // The next token, possibly on a later line.
  std::string_view word() {
    skip_white_and_comments();
    const char* b = p;
    while (p < end && !is_white(*p) && *p != '#') ++p;
    return std::string_view(b, size_t(p - b));
  }
  // The next token on the current line only (empty at the line's end or a comment).
  std::string_view field() {
    p = skip_spaces(p, end);
    const char* b = p;
    while (p < end && !is_white(*p) && *p != '#') ++p;
    return std::string_view(b, size_t(p - b));
  }
  void skip_rest_of_line() {
    while (p < end && !is_eol(*p)) ++p;
  }
  std::string at() const { return "line " + std::to_string(line) + ": "; }
};

bool token_uint(std::string_view tok, uint64_t& v) {
  const char* q = tok.data();
  int64_t i;
  if (tok.empty() || !scan_int(q, q + tok.size(), i) || i < 0) return false;
  v = uint64_t(i);
  return true;
}

// Keyword: [ST][C][N][4][n]OFF, or none (the text then starts with the
// counts, and is left where it was).
bool read_keyword(OffText& t, bool& four, bool& ndim, std::string& error) {
  const char* save = t.p;
  uint64_t save_line = t.line;
  std::string_view kw = t.word();
  if (kw.empty()) {
    error = "empty file (no OFF header)";
    return false;
  }
  if (kw.size() >= 3 && kw.substr(kw.size() - 3) == "OFF") {
    std::string_view prefix = kw.substr(0, kw.size() - 3);
    if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
    if (!prefix.empty() && prefix[0] == 'C') prefix.remove_prefix(1);
    if (!prefix.empty() && prefix[0] == 'N') prefix.remove_prefix(1);
    if (!prefix.empty() && prefix[0] == '4') four = true, prefix.remove_prefix(1);
    if (!prefix.empty() && prefix[0] == 'n') ndim = true, prefix.remove_prefix(1);
    if (!prefix.empty()) {
      error = "unknown OFF keyword " + quote_token(kw);
      return false;
    }
    const char* peek = t.p;
    uint64_t peek_line = t.line;
    if (token_is(t.field(), "binary")) {
      error = "binary OFF is not supported";
      return false;
    }
    t.p = peek, t.line = peek_line;
    return true;
  }
  uint64_t dummy;
  if (!token_uint(kw, dummy)) {
    error = "not an OFF file (starts with " + quote_token(kw) + ")";
    return false;
  }
  t.p = save, t.line = save_line;  // no keyword: the counts come first
  return true;
}

// The counts line (the edge count optional), checked against the bytes left
// and the scene's vertex limit before anything is allocated.
bool read_counts(OffText& t, const Scene& out, uint64_t& nv, uint64_t& nf, std::string& error) {
  uint64_t ne = 0;
  std::string_view tv = t.word(), tf = t.word();
  if (!token_uint(tv, nv) || !token_uint(tf, nf)) {
    error = t.at() + "expected the vertex and face counts, found " + quote_token(tv) + " " + quote_token(tf);
    return false;
  }
  const char* peek = t.p;
  std::string_view te = t.field();
  if (!te.empty() && !token_uint(te, ne)) t.p = peek;
  const uint64_t left = uint64_t(t.end - t.p);
  if (nv > left / 6 + 1 || nf > left / 2 + 1 || nv * 6 + nf * 2 > left + 8) {
    error = "header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces, but only " +
            std::to_string(left) + " bytes follow";
    return false;
  }
  if (out.vertex_count() + nv > 0xffffffffu) {
    error = "more than 4294967295 vertices";
    return false;
  }
  return true;
}

// nv vertex lines of `dim` coordinates; the first 3 are used (4OFF: over the last).
bool read_vertices(OffText& t, uint64_t nv, uint64_t dim, bool four, Scene& out, std::string& error) {
  out.positions.reserve(out.positions.size() + 3 * nv);
  for (uint64_t v = 0; v < nv; ++v) {
    t.skip_white_and_comments();
    double c[65];  // dim <= 64, +1 for 4OFF
    for (uint64_t k = 0; k < dim; ++k) {
      std::string_view tok = t.field();
      const char* q = tok.data();
      if (tok.empty()) {
        error = t.at() + "vertex " + std::to_string(v) + " needs " + std::to_string(dim) + " coordinates";
        return false;
      }
      if (!scan_double(q, tok.data() + tok.size(), c[k])) {
        error = t.at() + "bad number " + quote_token(tok);
        return false;
      }
    }
    double w = four ? c[dim - 1] : 1.0;
    for (int k = 0; k < 3; ++k) out.positions.push_back(to_float(c[k] / w));
    t.skip_rest_of_line();
  }
  return true;
}

// Face f's line: its vertex count k and indices into `poly` (offset by `base`).
bool read_face(OffText& t, uint64_t f, uint64_t nf, uint64_t nv, size_t base, uint64_t& k, std::vector<uint32_t>& poly,
               std::string& error) {
  t.skip_white_and_comments();
  std::string_view tok = t.field();
  if (tok.empty()) {
    error = "file ends before face " + std::to_string(f) + " of " + std::to_string(nf);
    return false;
  }
  if (!token_uint(tok, k)) {
    error = t.at() + "face " + std::to_string(f) + ": bad vertex count " + quote_token(tok);
    return false;
  }
  if (k > uint64_t(t.end - t.p)) {
    error = t.at() + "face " + std::to_string(f) + " claims " + std::to_string(k) + " vertices";
    return false;
  }
  poly.clear();
  for (uint64_t i = 0; i < k; ++i) {
    uint64_t idx;
    std::string_view it = t.field();
    if (it.empty() || !token_uint(it, idx)) {
      error = t.at() + "face " + std::to_string(f) + ": " +
              (it.empty() ? std::string("expected ") + std::to_string(k) + " vertex indices"
                          : "bad vertex index " + quote_token(it));
      return false;
    }
    if (idx >= nv) {
      error = t.at() + "face " + std::to_string(f) + ": vertex index " + std::to_string(idx) + " out of range (" +
              std::to_string(nv) + " vertices)";
      return false;
    }
    poly.push_back(uint32_t(base + idx));
  }
  t.skip_rest_of_line();
  return true;
}

}  // namespace

bool import_off(const ImportInput& in, Scene& out, std::string& error) {
  if (looks_like_utf16(in.data, in.size)) {
    error = "UTF-16 or UTF-32 text is not supported (save the OFF as ASCII)";
    return false;
  }
  const char* begin = reinterpret_cast<const char*>(in.data);
  OffText t{skip_utf8_bom(begin, begin + in.size), begin + in.size};
  bool four = false, ndim = false;
  if (!read_keyword(t, four, ndim, error)) return false;
  uint64_t dim = 3;
  if (ndim) {
    std::string_view tok = t.word();
    if (!token_uint(tok, dim) || dim < 3 || dim > 64) {
      error = t.at() + "nOFF dimension must be 3 to 64, not " + quote_token(tok);
      return false;
    }
  }
  if (four) ++dim;
  uint64_t nv = 0, nf = 0;
  if (!read_counts(t, out, nv, nf, error)) return false;
  const size_t base = out.vertex_count();
  if (!read_vertices(t, nv, dim, four, out, error)) return false;

  uint64_t short_faces = 0;
  std::vector<uint32_t> poly;
  for (uint64_t f = 0; f < nf; ++f) {
    uint64_t k = 0;
    if (!read_face(t, f, nf, nv, base, k, poly, error)) return false;
    if (k < 3) {
      ++short_faces;
      continue;
    }
    for (size_t i = 1; i + 1 < poly.size(); ++i) {
      out.indices.insert(out.indices.end(), {poly[0], poly[i], poly[i + 1]});
      out.sources.push_back(TriangleSource{});
    }
  }
  if (short_faces)
    out.warnings.push_back(in.name + ": " + std::to_string(short_faces) + " faces with fewer than 3 vertices skipped");
  return true;
}

}  // namespace geom::detail
