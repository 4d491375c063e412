// peak_rss.h (private): the process's peak resident set, for the stage
// timings of geom/pipeline.h and the memory figures of geombake, geombench and
// the benchmarks. Linux only (VmHWM of /proc/self/status); a process's
// measure, so no part of the library's public API.
#pragma once
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace geom {

// The process's peak resident set size in bytes, 0 if unknown.
inline uint64_t peak_rss_bytes() {
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
