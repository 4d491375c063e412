// cli/args.h (tools/common, library geom::cli): what the apps share on the
// command line (geombake, geomview, geombench): the flag parser (gltfpack
// style: short flags, `-o FILE`, `--name VALUE` or `--name=VALUE`), number
// lists, the `Error:` / `Warning:` lines on stderr and the exit codes. No app
// includes another app's files; what two apps need lives here.
#pragma once
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace cli {

// Exit codes: 0 success, 1 bad input or a failed run, 2 bad usage.
constexpr int kExitOk = 0, kExitFailure = 1, kExitUsage = 2;

// `PREFIX: MESSAGE` on stderr, one line.
inline void vline(const char* prefix, const char* format, std::va_list args) {
  std::fprintf(stderr, "%s: ", prefix);
  std::vfprintf(stderr, format, args);
  std::fputc('\n', stderr);
}

// `Error: MESSAGE` on stderr (printf-style).
[[gnu::format(printf, 1, 2)]] inline void error(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  vline("Error", format, args);
  va_end(args);
}

// `Warning: MESSAGE` on stderr (printf-style).
[[gnu::format(printf, 1, 2)]] inline void warning(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  vline("Warning", format, args);
  va_end(args);
}

class Args {
 public:
  // `flags`: options without a value; `options`: options taking one value
  // (repeatable: all values kept). Anything else starting with '-' is an error.
  Args(const std::vector<std::string>& argv, std::set<std::string> flags, std::set<std::string> options) {
    for (size_t i = 0; i < argv.size(); ++i) {
      std::string a = argv[i];
      if (a.size() > 1 && a[0] == '-' && !positional_only_) {
        if (a == "--") {
          positional_only_ = true;
          continue;
        }
        std::string value;
        bool has_value = false;
        size_t eq = a.find('=');
        if (a.rfind("--", 0) == 0 && eq != std::string::npos) {
          value = a.substr(eq + 1);
          a = a.substr(0, eq);
          has_value = true;
        }
        if (flags.count(a)) {
          if (has_value) error_ = "option " + a + " takes no value";
          flags_.insert(a);
        } else if (options.count(a)) {
          if (!has_value) {
            if (i + 1 >= argv.size()) {
              error_ = "option " + a + " needs a value";
              return;
            }
            value = argv[++i];
          }
          values_[a].push_back(value);
        } else {
          error_ = "unknown option " + a;
          return;
        }
      } else {
        positional_.push_back(a);
      }
    }
  }
  const std::string& error() const { return error_; }
  bool has(const std::string& name) const { return flags_.count(name) || values_.count(name); }
  std::string get(const std::string& name, const std::string& fallback = "") const {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second.back();
  }
  const std::vector<std::string>& all(const std::string& name) const {
    static const std::vector<std::string> none;
    auto it = values_.find(name);
    return it == values_.end() ? none : it->second;
  }
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::set<std::string> flags_;
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positional_;
  std::string error_;
  bool positional_only_ = false;
};

// Parses "a,b,c[,d]" (exactly n numbers, comma-separated, nothing after, no
// spaces) into n floats; false on anything else. Non-finite numbers parse:
// callers that refuse them check.
inline bool parse_floats(const std::string& text, int n, float* out) {
  const char* p = text.c_str();
  for (int i = 0; i < n; ++i) {
    char* end = nullptr;
    if (*p == 0 || std::isspace(static_cast<unsigned char>(*p))) return false;
    out[i] = std::strtof(p, &end);
    if (end == p) return false;
    p = end;
    if (i + 1 < n) {
      if (*p != ',') return false;
      ++p;
    }
  }
  return *p == 0;
}

// ---- Strict numbers: the whole text, a range, integers where integers are meant ----
// Every number a flag takes goes through these: "1e3" is no integer, "1024abc"
// and " 5" are no number, a value out of its range is refused, never wrapped
// or clamped; the message names the flag ("--frames: '1e3' is not an integer
// within 1..100000").

// The whole of `text` as a decimal integer (an optional '-' or '+', then
// digits; nothing else) within [lo, hi].
inline bool parse_int(const std::string& text, long long lo, long long hi, long long& out) {
  size_t i = text.empty() ? 0 : (text[0] == '-' || text[0] == '+');
  if (i >= text.size()) return false;
  for (size_t k = i; k < text.size(); ++k)
    if (text[k] < '0' || text[k] > '9') return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno == ERANGE || *end != 0 || v < lo || v > hi) return false;
  out = v;
  return true;
}

// The whole of `text` as a finite real number (strtod's syntax, no leading
// space) within [lo, hi].
inline bool parse_real(const std::string& text, double lo, double hi, double& out) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != 0 || !std::isfinite(v) || !(v >= lo && v <= hi)) return false;
  out = v;
  return true;
}

// "WxH" with both integers within [lo, hi].
inline bool parse_size(const std::string& text, long long lo, long long hi, int& width, int& height) {
  const size_t x = text.find('x');
  long long w = 0, h = 0;
  if (x == std::string::npos || !parse_int(text.substr(0, x), lo, hi, w) || !parse_int(text.substr(x + 1), lo, hi, h))
    return false;
  width = int(w), height = int(h);
  return true;
}

// The comma-separated items of `text`; false on an empty list or an empty
// item ("", ",", "a,,b", "a,").
inline bool parse_list(const std::string& text, std::vector<std::string>& items) {
  items.clear();
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty()) return items.clear(), false;
    items.push_back(item);
    if (comma == std::string::npos) return true;
    start = comma + 1;
  }
}

// The flag's last value, when given, into `out` (left alone when absent),
// through the parsers above; false with `error` naming the flag, the value and
// the range.
inline std::string range_text(double lo, double hi) {
  char b[96];
  std::snprintf(b, sizeof b, "%.17g..%.17g", lo, hi);
  return b;
}
inline bool int_option(const Args& args, const std::string& name, long long lo, long long hi, int& out,
                       std::string& error) {
  if (!args.has(name)) return true;
  long long v = 0;
  if (!parse_int(args.get(name), lo, hi, v))
    return error = name + ": '" + args.get(name) + "' is not an integer within " + std::to_string(lo) + ".." +
                   std::to_string(hi),
           false;
  out = int(v);
  return true;
}
inline bool real_option(const Args& args, const std::string& name, double lo, double hi, double& out,
                        std::string& error) {
  if (!args.has(name)) return true;
  if (!parse_real(args.get(name), lo, hi, out))
    return error = name + ": '" + args.get(name) + "' is not a number within " + range_text(lo, hi), false;
  return true;
}
inline bool size_option(const Args& args, const std::string& name, long long lo, long long hi, int& width, int& height,
                        std::string& error) {
  if (!args.has(name)) return true;
  if (!parse_size(args.get(name), lo, hi, width, height))
    return error = name + ": '" + args.get(name) + "' is not WxH with W and H integers within " + std::to_string(lo) +
                   ".." + std::to_string(hi),
           false;
  return true;
}
inline bool list_option(const Args& args, const std::string& name, std::vector<std::string>& items,
                        std::string& error) {
  if (!args.has(name)) return true;
  if (!parse_list(args.get(name), items))
    return error = name + ": '" + args.get(name) + "' is not a comma-separated list of non-empty names", false;
  return true;
}

}  // namespace cli
