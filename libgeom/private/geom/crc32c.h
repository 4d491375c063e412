// geom/crc32c.h: CRC-32C (Castagnoli) at the speed of the CPU.
//
// The checksum of the baked container (geom/baked_reader.h: reflected
// polynomial 0x82F63B78, initial value 0xFFFFFFFF, final xor 0xFFFFFFFF;
// crc32c("123456789") = 0xE3069283). crc32c() uses SSE4.2's crc32 instruction
// where the CPU has it (checked once, at run time) and otherwise the
// slicing-by-8 table of geom::baked::crc32c, which gives the same value for the
// same bytes. The writer computes each section's checksum once with it
// (geom/baked_writer.h write_baked hands them back for reports).
#pragma once
#include <cstddef>
#include <cstdint>

namespace geom {

// CRC-32C of `size` bytes continuing from `crc` (0 to start; else the value a
// previous call returned), so crc32c(ab) == crc32c(b, crc32c(a)).
uint32_t crc32c(const void* data, size_t size, uint32_t crc = 0);

// The table version (what crc32c() falls back to), whatever the CPU.
uint32_t crc32c_portable(const void* data, size_t size, uint32_t crc = 0);

// Whether crc32c() runs on the crc32 instruction on this CPU.
bool crc32c_uses_hardware();

}  // namespace geom
