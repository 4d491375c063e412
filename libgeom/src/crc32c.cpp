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
// Three streams at once: the instruction's latency is 3 cycles and its
// throughput one a cycle, so three independent CRCs of three kBlock pieces
// cost what one does; they are joined by the CRC's linearity (the register
// after A then B is the register after A run over |B| zero bytes, xor that of
// B alone from 0), the run over kBlock zeros being one table look-up per byte.
constexpr size_t kBlock = 4096;

__attribute__((target("sse4.2"))) uint32_t zeros_shift_slow(uint32_t c) {
  uint64_t r = c;
  for (size_t i = 0; i < kBlock / 8; ++i) r = _mm_crc32_u64(r, 0);
  return uint32_t(r);
}

// shift[k][b]: the register b << 8k after kBlock zero bytes (linear in the register).
struct ZeroShift {
  uint32_t shift[4][256];
  ZeroShift() {
    for (int k = 0; k < 4; ++k)
      for (uint32_t b = 0; b < 256; ++b) shift[k][b] = zeros_shift_slow(b << (8 * k));
  }
  uint32_t operator()(uint32_t c) const {
    return shift[0][c & 255] ^ shift[1][(c >> 8) & 255] ^ shift[2][(c >> 16) & 255] ^ shift[3][c >> 24];
  }
};

__attribute__((target("sse4.2"))) uint32_t crc32c_sse42(const void* data, size_t size, uint32_t crc) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint64_t c = ~crc;
  while (size && (reinterpret_cast<uintptr_t>(p) & 7)) {
    c = _mm_crc32_u8(uint32_t(c), *p++);
    --size;
  }
  if (size >= 3 * kBlock) {
    static const ZeroShift shift;
    while (size >= 3 * kBlock) {
      uint64_t a = c, b = 0, d = 0;
      for (size_t i = 0; i < kBlock; i += 8) {
        uint64_t va, vb, vd;
        std::memcpy(&va, p + i, 8);
        std::memcpy(&vb, p + kBlock + i, 8);
        std::memcpy(&vd, p + 2 * kBlock + i, 8);
        a = _mm_crc32_u64(a, va);
        b = _mm_crc32_u64(b, vb);
        d = _mm_crc32_u64(d, vd);
      }
      c = shift(shift(uint32_t(a)) ^ uint32_t(b)) ^ uint32_t(d);
      p += 3 * kBlock;
      size -= 3 * kBlock;
    }
  }
  // One stream, 8 bytes a step.
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
