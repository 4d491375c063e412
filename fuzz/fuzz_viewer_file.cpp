// libFuzzer target: geomview's file path, the baked reader and its float
// validation (fuzz/viewer_file.h says what is checked). The first byte is a
// mode, the rest the file: mode bit 0 set, the checksums are recomputed first
// (fuzz/baked_repair.h), so that mutated floats reach validate_floats instead
// of a checksum mismatch. A broken law aborts (a finding); crashes, overreads
// and undefined behaviour are ASan's and UBSan's.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "baked_repair.h"
#include "viewer_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::vector<unsigned char> file(data + 1, data + size);
  if (data[0] & 1) geom_fuzz::repair_checksums(file);
  const std::string broken = geom_fuzz::check_viewer_file(file.data(), file.size());
  if (!broken.empty()) {
    std::fprintf(stderr, "viewer file law broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
