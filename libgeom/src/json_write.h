// json_write.h (private): the one way libgeom writes JSON text (the topology
// report of geom/report.h, the bake's silhouette section of geom/bake.h):
// strings, numbers that read back to the same double, and counts. Public:
// geom::json_quote (geom/report.h) is quote() for the tools' file names.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

namespace geom::json {

// The length of the valid UTF-8 sequence at s[i], 0 if none starts there.
inline size_t utf8_length(const std::string& s, size_t i) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((b(i + k) & 0xc0) != 0x80) return 0;
  if ((n == 2 && c < 0xc2) || (n == 3 && c == 0xe0 && b(i + 1) < 0xa0) || (n == 3 && c == 0xed && b(i + 1) >= 0xa0) ||
      (n == 4 && c == 0xf0 && b(i + 1) < 0x90) || (n == 4 && (c > 0xf4 || (c == 0xf4 && b(i + 1) >= 0x90))))
    return 0;  // overlong, a surrogate, or over U+10FFFF
  return n;
}

// `s` as a JSON string literal, quotes included, whatever bytes it holds:
// valid UTF-8 kept ('"', '\\', \n, \r, \t and other control characters
// escaped), each other byte as \udcXX (PEP 383's surrogateescape: lossless,
// and valid JSON text). See geom/report.h json_quote.
inline std::string quote(const std::string& s) {
  std::string out = "\"";
  out.reserve(s.size() + 2);
  char buf[8];
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const size_t n = utf8_length(s, i);
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\udc%02x", c);
      out += buf;
      ++i;
      continue;
    }
    if (n > 1) {
      out.append(s, i, n);
    } else if (c == '"') {
      out += "\\\"";
    } else if (c == '\\') {
      out += "\\\\";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += char(c);
    }
    i += n;
  }
  return out + "\"";
}

// A double with 17 significant digits (%.17g): it reads back to the same value.
inline std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

inline std::string count(uint64_t v) { return std::to_string(v); }

}  // namespace geom::json
