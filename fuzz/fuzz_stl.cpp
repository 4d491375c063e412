// libFuzzer target: the STL importer through geom::import_memory (see fuzz_import.h).
#include "fuzz_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return geom_fuzz::fuzz_import("stl", data, size);
}
