// CRC-32C with run-time dispatch (geom/crc32c.h): SSE4.2's crc32 instruction
// (Intel, "Fast CRC Computation for iSCSI Polynomial Using CRC32 Instruction",
// 2011: the instruction computes exactly this reflected CRC, 8 bytes a step),
// else the slicing-by-8 table of geom/baked_reader.h.
#include "geom/crc32c.h"

#include <cstring>

#include "geom/baked_reader.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <nmmintrin.h>
#define GEOM_CRC32C_X86 1
#endif

namespace geom {
namespace {

#if GEOM_CRC32C_X86
__attribute__((target("sse4.2"))) uint32_t crc32c_sse42(const void* data, size_t size, uint32_t crc) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint64_t c = ~crc;
  while (size && (reinterpret_cast<uintptr_t>(p) & 7)) {
    c = _mm_crc32_u8(uint32_t(c), *p++);
    --size;
  }
  // One stream, 8 bytes a step (bound by the instruction's latency: about
  // 8 bytes per 3 cycles, several times the table).
  while (size >= 8) {
    uint64_t v;
    std::memcpy(&v, p, 8);
    c = _mm_crc32_u64(c, v);
    p += 8;
    size -= 8;
  }
  while (size--) c = _mm_crc32_u8(uint32_t(c), *p++);
  return ~uint32_t(c);
}

bool have_sse42() {
  static const bool yes = __builtin_cpu_supports("sse4.2");
  return yes;
}
#endif

}  // namespace

uint32_t crc32c_portable(const void* data, size_t size, uint32_t crc) { return baked::crc32c(data, size, crc); }

bool crc32c_uses_hardware() {
#if GEOM_CRC32C_X86
  return have_sse42();
#else
  return false;
#endif
}

uint32_t crc32c(const void* data, size_t size, uint32_t crc) {
#if GEOM_CRC32C_X86
  if (have_sse42()) return crc32c_sse42(data, size, crc);
#endif
  return crc32c_portable(data, size, crc);
}

}  // namespace geom
