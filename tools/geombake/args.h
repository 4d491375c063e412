// A small command-line parser for geombake subcommands (gltfpack style: short
// flags, `-o FILE`, `--name VALUE` or `--name=VALUE`). Errors are reported as
// `Error: ...` by the caller with exit code 2.
#pragma once
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace geombake {

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

// Parses "a,b,c[,d]" into n floats; false on anything else.
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

}  // namespace geombake
