// cli/args.h (tools/common, library geom::cli): what the apps share on the
// command line (geombake, geomview, geombench): the flag parser (gltfpack
// style: short flags, `-o FILE`, `--name VALUE` or `--name=VALUE`), number
// lists, the `Error:` / `Warning:` lines on stderr and the exit codes. No app
// includes another app's files; what two apps need lives here.
#pragma once
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

// `Error: MESSAGE` on stderr (printf-style).
[[gnu::format(printf, 1, 2)]] inline void error(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::fputs("Error: ", stderr);
  std::vfprintf(stderr, format, args);
  std::fputc('\n', stderr);
  va_end(args);
}

// `Warning: MESSAGE` on stderr (printf-style).
[[gnu::format(printf, 1, 2)]] inline void warning(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::fputs("Warning: ", stderr);
  std::vfprintf(stderr, format, args);
  std::fputc('\n', stderr);
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

// Parses "a,b,c[,d]" (exactly n numbers, comma-separated, nothing after)
// into n floats; false on anything else. Non-finite numbers parse: callers
// that refuse them check.
inline bool parse_floats(const std::string& text, int n, float* out) {
  const char* p = text.c_str();
  for (int i = 0; i < n; ++i) {
    char* end = nullptr;
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

}  // namespace cli
