// Shared by geombake subcommands: input expansion and numeric option parsing.
#pragma once
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <type_traits>
#include <vector>

#include "cli/args.h"

namespace geombake {

// Expands each argument: ARCHIVE.pk3 (no ":member") becomes every .bsp inside
// it, a directory every mesh file under it (recursive, sorted; an archive
// found there as an archive argument), anything
// else stays as it is (an archive that cannot be listed or holds no map too,
// and a mesh-named entry of a directory that is not a regular file: their
// import reports why). Returns true.
bool expand_inputs(const std::vector<std::string>& args, std::vector<std::string>& inputs);

// Parses option `name` into `value` if present; prints `Error:` and returns false if malformed.
template <class T>
bool parse_number(const cli::Args& args, const std::string& name, T& value) {
  if (!args.has(name)) return true;
  const std::string text = args.get(name);
  char* end = nullptr;
  errno = 0;
  bool ok = !text.empty();
  if constexpr (std::is_floating_point_v<T>) {
    double v = std::strtod(text.c_str(), &end);
    ok = ok && *end == 0 && errno == 0 && v >= 0;
    value = T(v);
  } else {
    long long v = std::strtoll(text.c_str(), &end, 10);
    ok = ok && *end == 0 && errno == 0 && v >= 0;
    value = T(v);
  }
  if (!ok) std::fprintf(stderr, "Error: option %s: '%s' is not a non-negative number\n", name.c_str(), text.c_str());
  return ok;
}

}  // namespace geombake
