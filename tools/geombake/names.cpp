// File names in JSON, depfiles and output checks (names.h).
#include "geombake/names.h"

#include <sys/stat.h>

#include <cstdint>
#include <cstdio>
#include <vector>

namespace geombake {

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
