// Wavefront OBJ import: positions and faces only.
//
// Reads `v x y z [w] [r g b]` (anything after x y z ignored) and `f` with
// corners `v`, `v/vt`, `v//vn`, `v/vt/vn` (only v is used). Indices are
// 1-based; negative ones count back from the last `v` read so far (-1 = the
// latest). A polygon of n corners becomes n-2 triangles fanned from its first
// corner; a face with fewer than 3 corners is skipped (one warning). `o` and
// `g` start a new TriangleSource::mesh: a counter numbered densely from 0 in
// the order groups first receive a face (faces before any `o`/`g` are a group). `l`
// and `p` (lines, points) are skipped with one warning giving their count.
// Every other OBJ statement (vt, vn, usemtl, mtllib, s, comments...) is
// ignored; `#` starts a comment, also after a statement. A file with no face
// and a line that is no OBJ statement ("hello", random bytes) is refused: it
// is not a mesh, and an empty bake would hide the mistake.
//
// Text: LF, CRLF or CR-only line ends, a missing final newline, a UTF-8
// byte-order mark, and `\` at the end of a line joining it with the next.
// UTF-16 / UTF-32 files are refused. Errors name the physical line:
// "line 12: face index 40 out of range (8 vertices)".
//
// Positive indices may refer to vertices defined later in the file (some
// exporters write faces first): they, and index 0, are checked once the file
// is read, and the error names the first line with a bad one.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "importers.h"
#include "text_scan.h"

namespace geom::detail {
namespace {

// The statements of the OBJ format (geometry, grouping, display, free-form),
// and the few that common exporters add: a file with none of its triangles
// and a line starting otherwise is not an OBJ file.
bool is_obj_statement(std::string_view key) {
  static const char* const kKeys[] = {
      "v",    "vt",         "vn",        "vp",     "f",      "fo",     "l",   "p",    "o",     "g",        "s",
      "mg",   "usemtl",     "mtllib",    "usemap", "maplib", "cstype", "deg", "bmat", "step",  "curv",     "curv2",
      "surf", "parm",       "trim",      "hole",   "scrv",   "sp",     "end", "con",  "bevel", "c_interp", "d_interp",
      "lod",  "shadow_obj", "trace_obj", "ctech",  "stech",  "call",   "csh", "res",  "vc"};
  for (const char* k : kKeys)
    if (key == k) return true;
  return false;
}

struct LineReader {
  const char* p;
  const char* end;
  uint64_t next_line = 1;  // physical number of the next line
  std::string joined;      // scratch for lines continued with '\'

  // The next logical line (without its EOL) and its first physical line number.
  bool next(std::string_view& line, uint64_t& number) {
    if (p >= end) return false;
    number = next_line;
    joined.clear();
    bool continued = false;
    for (;;) {
      const char* b = p;
      while (p < end && !is_eol(*p)) ++p;
      const char* e = p;
      const bool had_eol = p < end;
      if (had_eol) {  // consume one line end: "\r\n", "\n" or "\r"
        if (*p == '\r' && p + 1 < end && p[1] == '\n') ++p;
        ++p;
      }
      ++next_line;
      // A '\' as the last non-blank character before a line end continues the line.
      const char* t = e;
      while (t > b && is_space(t[-1])) --t;
      const bool cont = had_eol && t > b && t[-1] == '\\';
      if (!cont && !continued) {
        line = std::string_view(b, size_t(e - b));
        return true;
      }
      joined.append(b, cont ? t - 1 : e);
      if (!cont) break;
      joined.push_back(' ');
      continued = true;
    }
    line = joined;
    return true;
  }
};

std::string at_line(uint64_t n) { return "line " + std::to_string(n) + ": "; }

// The state of one file's statements, appended to `out` as they are read.
struct ObjParser {
  Scene& out;
  size_t base;  // the vertices `out` held before this file
  size_t base_indices;
  uint64_t vertex_count = 0;
  uint32_t mesh = 0, next_mesh = 0;
  bool new_group = true;
  uint64_t lines_points = 0, short_faces = 0;
  uint64_t unknown_line = 0;  // the first line whose statement is not OBJ
  std::string unknown_key;
  // (line, index) of each index 0 and each index beyond the vertices read so
  // far; checked, in file order, once the vertex count is known.
  std::vector<std::pair<uint64_t, int64_t>> suspects;
  std::vector<int64_t> corners;

  explicit ObjParser(Scene& scene) : out(scene), base(scene.vertex_count()), base_indices(scene.indices.size()) {}

  // `v x y z ...`: the first three numbers.
  bool vertex(const char* p, const char* e, uint64_t number, std::string& error) {
    float xyz[3];
    for (float& c : xyz) {
      std::string_view tok = next_token(p, e);
      const char* q = tok.data();
      if (tok.empty()) {
        error = at_line(number) + "vertex needs 3 coordinates";
        return false;
      }
      if (!scan_float(q, tok.data() + tok.size(), c)) {
        error = at_line(number) + "bad number " + quote_token(tok);
        return false;
      }
    }
    out.positions.insert(out.positions.end(), xyz, xyz + 3);
    ++vertex_count;
    return true;
  }

  // One face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` into `corners`, 0-based.
  bool corner(std::string_view tok, uint64_t number, std::string& error) {
    const char* q = tok.data();
    int64_t idx = 0;
    if (!scan_int(q, tok.data() + tok.size(), idx, "/")) {
      error = at_line(number) + "bad face corner " + quote_token(tok);
      return false;
    }
    const char* rest = q;  // after the vertex index: "/vt/vn" forms only
    for (int slashes = 0; rest < tok.data() + tok.size(); ++rest) {
      const char c = *rest;
      if (!((c >= '0' && c <= '9') || c == '-' || c == '+' || (c == '/' && ++slashes <= 2))) {
        error = at_line(number) + "bad face corner " + quote_token(tok);
        return false;
      }
    }
    if (idx < 0) {
      if (uint64_t(-(idx + 1)) >= vertex_count) {
        error = at_line(number) + "face index " + std::to_string(idx) + " out of range (" +
                std::to_string(vertex_count) + " vertices before it)";
        return false;
      }
      idx = int64_t(vertex_count) + idx;  // 0-based
    } else {
      if (uint64_t(idx) > vertex_count || idx == 0) suspects.push_back({number, idx});
      idx -= 1;
    }
    corners.push_back(idx);
    return true;
  }

  // `f c0 c1 c2 ...`: a fan of n-2 triangles from the first corner, in the current group.
  bool face(const char* p, const char* e, uint64_t number, std::string& error) {
    corners.clear();
    for (std::string_view tok = next_token(p, e); !tok.empty(); tok = next_token(p, e))
      if (!corner(tok, number, error)) return false;
    if (corners.size() < 3) {
      ++short_faces;
      return true;
    }
    if (new_group) {
      mesh = next_mesh++;
      new_group = false;
    }
    TriangleSource src;
    src.mesh = mesh;
    for (size_t i = 1; i + 1 < corners.size(); ++i) {
      out.indices.push_back(uint32_t(base + uint64_t(corners[0])));
      out.indices.push_back(uint32_t(base + uint64_t(corners[i])));
      out.indices.push_back(uint32_t(base + uint64_t(corners[i + 1])));
      out.sources.push_back(src);
    }
    return true;
  }

  // One logical line.
  bool statement(std::string_view line, uint64_t number, std::string& error) {
    const char* p = line.data();
    const char* e = p + line.size();
    std::string_view key = next_token(p, e);
    if (key.empty() || key[0] == '#') return true;
    if (const void* hash = std::memchr(p, '#', size_t(e - p))) e = static_cast<const char*>(hash);  // trailing comment
    if (key == "v") return vertex(p, e, number, error);
    if (key == "f") return face(p, e, number, error);
    if (key == "o" || key == "g") {
      new_group = true;
    } else if (key == "l" || key == "p") {
      ++lines_points;
    } else if (!unknown_line && !is_obj_statement(key)) {
      unknown_line = number;
      unknown_key = quote_token(key);
    }
    return true;
  }

  // What can only be judged once the file is read: forward indices, a file that
  // is no mesh, the index range; then the warnings.
  bool finish(const std::string& name, std::string& error) {
    for (const auto& [line_number, idx] : suspects) {
      if (idx == 0) {
        error = at_line(line_number) + "face index 0 is invalid (OBJ indices start at 1)";
        return false;
      }
      if (uint64_t(idx) > vertex_count) {
        error = at_line(line_number) + "face index " + std::to_string(idx) + " out of range (" +
                std::to_string(vertex_count) + " vertices)";
        return false;
      }
    }
    if (out.indices.size() == base_indices && unknown_line) {  // no triangle, and text that is not OBJ
      error = at_line(unknown_line) + unknown_key + " is not an OBJ statement, and the file has no face: not a mesh";
      return false;
    }
    if (base + vertex_count > 0xffffffffu) {
      error = "more than 4294967295 vertices";
      return false;
    }
    if (lines_points)
      out.warnings.push_back(name + ": " + std::to_string(lines_points) +
                             " line and point statements (l, p) skipped; only faces are imported");
    if (short_faces)
      out.warnings.push_back(name + ": " + std::to_string(short_faces) + " faces with fewer than 3 corners skipped");
    return true;
  }
};

}  // namespace

bool import_obj(const ImportInput& in, Scene& out, std::string& error) {
  if (looks_like_utf16(in.data, in.size)) {
    error = "UTF-16 or UTF-32 text is not supported (save the OBJ as UTF-8 or ASCII)";
    return false;
  }
  const char* begin = reinterpret_cast<const char*>(in.data);
  LineReader reader{skip_utf8_bom(begin, begin + in.size), begin + in.size, 1, std::string()};
  ObjParser parser(out);
  std::string_view line;
  uint64_t number = 0;
  while (reader.next(line, number))
    if (!parser.statement(line, number, error)) return false;
  return parser.finish(in.name, error);
}

}  // namespace geom::detail
