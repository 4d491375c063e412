// File names in JSON, depfiles and output checks (names.h).
#include "geombake/names.h"

#include <sys/stat.h>

#include <cstdint>
#include <cstdio>
#include <vector>

namespace geombake {
namespace {

// The length of the valid UTF-8 sequence at s[i], 0 if none starts there
// (overlong forms, surrogates and code points over U+10FFFF are invalid).
size_t utf8_length(const std::string& s, size_t i) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((b(i + k) & 0xc0) != 0x80) return 0;
  if (n == 2 && c < 0xc2) return 0;                                       // overlong
  if (n == 3 && c == 0xe0 && b(i + 1) < 0xa0) return 0;                   // overlong
  if (n == 3 && c == 0xed && b(i + 1) >= 0xa0) return 0;                  // a surrogate
  if (n == 4 && c == 0xf0 && b(i + 1) < 0x90) return 0;                   // overlong
  if (n == 4 && (c > 0xf4 || (c == 0xf4 && b(i + 1) >= 0x90))) return 0;  // over U+10FFFF
  return n;
}

}  // namespace

std::string json_quote(const std::string& s) {
  std::string o = "\"";
  char buf[8];
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const size_t n = utf8_length(s, i);
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\udc%02x", c);
      o += buf;
      ++i;
      continue;
    }
    if (n == 1) {
      if (c == '"')
        o += "\\\"";
      else if (c == '\\')
        o += "\\\\";
      else if (c == '\n')
        o += "\\n";
      else if (c == '\r')
        o += "\\r";
      else if (c == '\t')
        o += "\\t";
      else if (c < 0x20 || c == 0x7f)
        std::snprintf(buf, sizeof buf, "\\u%04x", c), o += buf;
      else
        o += char(c);
    } else {
      o.append(s, i, n);
    }
    i += n;
  }
  return o + "\"";
}

bool make_escape(const std::string& path, std::string& out) {
  out.clear();
  for (size_t i = 0; i < path.size(); ++i) {
    const char c = path[i];
    if (c == '\n' || c == '\r') return false;
    if (c == ' ' || c == '\t') {
      for (size_t k = i; k > 0 && path[k - 1] == '\\'; --k) out += '\\';  // double the backslashes before it
      out += '\\';
    } else if (c == '#') {
      out += '\\';
    } else if (c == '$') {
      out += '$';
    }
    out += c;
  }
  return true;
}

std::string output_problem(const std::string& output) {
  if (output.empty()) return "the output path is empty (-o \"\")";
  struct stat st;
  if (::stat(output.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return "'" + output + "' is a directory";
    if (!S_ISREG(st.st_mode)) return "'" + output + "' exists and is not a regular file (a device, FIFO or socket)";
    return "";
  }
  const size_t slash = output.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : output.substr(0, slash);
  if (::stat(dir.c_str(), &st) != 0) return "the folder '" + dir + "' of the output '" + output + "' does not exist";
  if (!S_ISDIR(st.st_mode)) return "'" + dir + "' in the output path '" + output + "' is not a directory";
  return "";
}

nlohmann::ordered_json json_text(const std::string& text) {
  nlohmann::ordered_json v = nlohmann::ordered_json::parse(text, nullptr, false);
  if (!v.is_discarded()) return v;
  return nlohmann::ordered_json::binary(std::vector<std::uint8_t>(text.begin(), text.end()));  // raw, see dump_json
}

namespace {
void dump_into(const nlohmann::ordered_json& j, int indent, int depth, std::string& o) {
  const std::string pad = indent < 0 ? "" : "\n" + std::string(size_t(indent) * size_t(depth + 1), ' ');
  const std::string end = indent < 0 ? "" : "\n" + std::string(size_t(indent) * size_t(depth), ' ');
  if (j.is_object()) {
    if (j.empty()) {
      o += "{}";
      return;
    }
    o += '{';
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      o += (first ? "" : ",") + pad + json_quote(it.key()) + (indent < 0 ? ":" : ": ");
      dump_into(it.value(), indent, depth + 1, o);
      first = false;
    }
    o += end + "}";
  } else if (j.is_array()) {
    if (j.empty()) {
      o += "[]";
      return;
    }
    o += '[';
    for (size_t i = 0; i < j.size(); ++i) {
      o += (i ? "," : "") + pad;
      dump_into(j[i], indent, depth + 1, o);
    }
    o += end + "]";
  } else if (j.is_string()) {
    o += json_quote(j.get_ref<const std::string&>());
  } else if (j.is_binary()) {
    const auto& raw = j.get_binary();
    o.append(raw.begin(), raw.end());
  } else {
    o += j.dump();
  }
}
}  // namespace

std::string dump_json(const nlohmann::ordered_json& j, int indent) {
  std::string o;
  dump_into(j, indent, 0, o);
  return o;
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace geombake
