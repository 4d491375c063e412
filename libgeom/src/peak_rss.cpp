// The process's peak resident set (geom/process.h), read from /proc/self/status.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "geom/process.h"

namespace geom {

uint64_t peak_rss_bytes() {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  uint64_t kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::strtoull(line + 6, nullptr, 10);
  std::fclose(f);
  return kb * 1024;
}

}  // namespace geom
