// cli/memory.h (tools/common, library geom::cli): the memory a run may plan
// to take, so that geomview and geombench refuse a size that cannot fit before
// any work (an estimate against a budget) instead of ending in std::bad_alloc
// after minutes.
#pragma once
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

namespace cli {

// Half of the smaller of this machine's physical memory and this process's
// address-space limit (RLIMIT_AS, `ulimit -v`): the rest is for the GL
// driver, the libraries and the other processes.
inline uint64_t memory_budget() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  uint64_t total = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : uint64_t(1) << 32;
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    total = std::min<uint64_t>(total, uint64_t(limit.rlim_cur));
  return total / 2;
}

// "3.2 GiB"
inline std::string gib(uint64_t bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  return b;
}

// Bytes one image pixel costs a run that renders it and compares it with the
// ray-cast reference: the GL colour and depth-stencil targets (8), the read
// back (4) and the image (3), the reference's per-pixel records (about 24),
// the error mask and overlay (8).
constexpr uint64_t kBytesPerImagePixel = 48;
// Bytes one shadow-map texel costs at most (a 32-bit depth, and a two-channel
// float map beside it for the edge-distance techniques).
constexpr uint64_t kBytesPerMapTexel = 12;

}  // namespace cli
