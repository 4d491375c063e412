// geom/process.h (private to the project: not installed): what the process
// itself has used, for the pipeline's stage timings, the CLI and the benchmarks.
#pragma once
#include <cstdint>

namespace geom {

// The process's peak resident set size in bytes (Linux VmHWM), 0 if unknown.
uint64_t peak_rss_bytes();

}  // namespace geom
