// libFuzzer target: the glTF importer through geom::import_memory (see
// fuzz_import.h). Bytes that start with the GLB magic "glTF" go in as fuzz.glb,
// the rest as fuzz.gltf (JSON), so one corpus covers both containers; the
// dictionary fuzz/gltf.dict holds the glTF keys and values. No base directory:
// an external buffer URI resolves against the working directory, where the
// importer accepts only a regular file of exactly byteLength bytes.
#include "fuzz_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return geom_fuzz::fuzz_import("gltf", data, size);
}
