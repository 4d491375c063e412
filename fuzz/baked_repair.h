// Fuzz helper: recomputes the checksums of a baked container
// (geom/baked_reader.h) as a valid writer would have stored them, so that a
// mutated file gets past the CRCs to the checks behind them. Standard library
// and the reader only.
#pragma once
#include <cstdint>
#include <vector>

#include "geom/baked_reader.h"

namespace geom_fuzz {

inline void store_u32(unsigned char* p, uint32_t v) {
  for (int k = 0; k < 4; ++k) p[k] = uint8_t(v >> (8 * k));
}

// Every section checksum the table can reach, then the header checksum.
inline void repair_checksums(std::vector<unsigned char>& b) {
  using namespace geom::baked;
  if (b.size() < kHeaderSize) return;
  const uint64_t count = detail::load_u32(&b[24]);
  const uint64_t table_end = kHeaderSize + count * kEntrySize;
  if (count > kMaxSections || table_end > b.size()) return;
  for (uint64_t i = 0; i < count; ++i) {
    unsigned char* e = &b[kHeaderSize + i * kEntrySize];
    const uint64_t offset = detail::load_u64(e + 24), size = detail::load_u64(e + 32);
    if (offset <= b.size() && size <= b.size() - offset) store_u32(e + 40, crc32c(&b[offset], size));
  }
  uint32_t crc = crc32c(b.data(), kHeaderCrcOffset);
  crc = crc32c(b.data() + kHeaderSize, table_end - kHeaderSize, crc);
  store_u32(&b[kHeaderCrcOffset], crc);
}

}  // namespace geom_fuzz
