// Private: scanning numbers and tokens in text mesh files (OBJ, PLY, OFF, STL)
// held in memory. No iostreams, no locale: std::from_chars on the bytes.
//
// Conventions: a cursor is a `const char*` advanced in place, bounded by
// `end`; nothing here reads at or past `end`. "Space" is blank within a line
// (space, tab, vertical tab, form feed); "EOL" is '\n' or '\r' (so LF, CRLF
// and CR-only files all work); "white" is either.
//
// Numbers: decimal, an optional leading '+' or '-', "inf"/"nan" accepted
// (the dispatcher refuses non-finite coordinates that a triangle uses). A
// number token must end at white space, at the end of the buffer, or at one
// of the `stop` characters the caller allows ('/' in OBJ faces); anything else
// ("3.1+e2", "1,5") is a bad number, not a silent prefix.
#pragma once
#include <cfloat>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

namespace geom::detail {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
inline bool is_eol(char c) { return c == '\n' || c == '\r'; }
inline bool is_white(char c) { return is_space(c) || is_eol(c); }

inline const char* skip_spaces(const char* p, const char* end) {
  while (p < end && is_space(*p)) ++p;
  return p;
}
inline const char* skip_white(const char* p, const char* end) {
  while (p < end && is_white(*p)) ++p;
  return p;
}

// The token at p (after skipping spaces, not EOLs): up to the next white char.
inline std::string_view next_token(const char*& p, const char* end) {
  p = skip_spaces(p, end);
  const char* b = p;
  while (p < end && !is_white(*p)) ++p;
  return std::string_view(b, size_t(p - b));
}

// Like next_token, but EOLs are skipped too.
inline std::string_view next_word(const char*& p, const char* end) {
  p = skip_white(p, end);
  return next_token(p, end);
}

// True when the number just scanned ends properly at q.
inline bool number_ends(const char* q, const char* end, const char* stop) {
  return q == end || is_white(*q) || (stop && *q && std::strchr(stop, *q));
}

// A double at p (no white skipped). On success advances p past it.
inline bool scan_double(const char*& p, const char* end, double& out, const char* stop = nullptr) {
  const char* q = p;
  if (q < end && *q == '+') {
    ++q;
    if (q < end && (*q == '-' || *q == '+')) return false;
  }
  double v = 0;
  auto r = std::from_chars(q, end, v, std::chars_format::general);
  if (r.ec == std::errc::result_out_of_range) {
    // Underflow becomes a signed zero, overflow an infinity (refused later if
    // used); strtod (only on this rare path) rounds both the standard way.
    std::string s(q, size_t(r.ptr - q));
    v = std::strtod(s.c_str(), nullptr);
  } else if (r.ec != std::errc()) {
    return false;
  }
  if (!number_ends(r.ptr, end, stop)) return false;
  out = v;
  p = r.ptr;
  return true;
}

// A double converted to float without undefined behaviour: out of range gives +-inf.
inline float to_float(double v) {
  if (v > double(FLT_MAX)) return std::numeric_limits<float>::infinity();
  if (v < -double(FLT_MAX)) return -std::numeric_limits<float>::infinity();
  return float(v);
}

inline bool scan_float(const char*& p, const char* end, float& out, const char* stop = nullptr) {
  double v;
  if (!scan_double(p, end, v, stop)) return false;
  out = to_float(v);
  return true;
}

// A decimal integer at p (no white skipped), optional sign. Advances p on success.
inline bool scan_int(const char*& p, const char* end, int64_t& out, const char* stop = nullptr) {
  const char* q = p;
  if (q < end && *q == '+') {
    ++q;
    if (q < end && *q == '-') return false;
  }
  int64_t v = 0;
  auto r = std::from_chars(q, end, v);
  if (r.ec != std::errc() || !number_ends(r.ptr, end, stop)) return false;
  out = v;
  p = r.ptr;
  return true;
}

// Case-insensitive ASCII comparison of a token with a lower-case keyword.
inline bool token_is(std::string_view token, std::string_view lower_keyword) {
  if (token.size() != lower_keyword.size()) return false;
  for (size_t i = 0; i < token.size(); ++i) {
    char c = token[i];
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    if (c != lower_keyword[i]) return false;
  }
  return true;
}

// A token for a message: printable ASCII, at most 32 characters.
inline std::string quote_token(std::string_view token) {
  std::string s = "'";
  for (size_t i = 0; i < token.size() && i < 32; ++i) {
    unsigned char c = static_cast<unsigned char>(token[i]);
    s += (c >= 32 && c < 127) ? char(c) : '?';
  }
  if (token.size() > 32) s += "...";
  return s + "'";
}

// Text files in UTF-16 or UTF-32 (by byte-order mark or NUL bytes among the
// first characters) are refused: the parsers read ASCII / UTF-8.
inline bool looks_like_utf16(const unsigned char* data, size_t size) {
  if (size >= 2 && ((data[0] == 0xff && data[1] == 0xfe) || (data[0] == 0xfe && data[1] == 0xff))) return true;
  size_t n = size < 64 ? size : 64;
  size_t zeros = 0;
  for (size_t i = 0; i < n; ++i) zeros += data[i] == 0;
  return n >= 4 && zeros * 4 >= n;
}

// Skips a UTF-8 byte-order mark.
inline const char* skip_utf8_bom(const char* p, const char* end) {
  if (end - p >= 3 && (unsigned char)p[0] == 0xef && (unsigned char)p[1] == 0xbb && (unsigned char)p[2] == 0xbf)
    return p + 3;
  return p;
}

}  // namespace geom::detail
