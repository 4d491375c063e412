// libFuzzer target: Draco-compressed glTF geometry (KHR_draco_mesh_compression).
//
// The fuzzer's bytes are a Draco stream (seeded with the .drc files of
// tests/data/draco); fuzz_import.h wraps them as the BIN chunk of a
// fixed GLB whose only primitive points its Draco extension at them, and
// imports that through geom::import_memory, so the whole path runs: GLB
// framing, bufferView checks, Draco's decoder, the checks of the decoded faces
// and points. Draco itself (libdraco.so from Debian) is not instrumented:
// crashes inside it are found, its coverage does not guide.
#include "fuzz_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return geom_fuzz::fuzz_import("draco", data, size);
}
