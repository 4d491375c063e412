// libFuzzer target: the header-only baked-file reader (geom/baked_reader.h).
//
// The first byte is a mode, the rest the file. Mode bit 0 set: before reading,
// every section checksum the table can reach and the header checksum are
// recomputed and stored, so that mutations get past the CRCs to the structural
// checks behind them (order, overlap, bounds, padding, names, formats);
// otherwise the bytes are read as they are. Laws checked on every result:
//   refused  -> one-line error, no sections;
//   accepted -> every section lies inside the buffer, size = count x stride,
//               offsets aligned, increasing and not overlapping, its CRC-32C
//               matches, and find() returns the first of its type and item.
// A broken law aborts (a finding); crashes and overreads are ASan's.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "baked_repair.h"
#include "geom/baked_reader.h"

namespace {

void require(bool law, const char* what) {
  if (law) return;
  std::fprintf(stderr, "reader law broken: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::vector<unsigned char> file(data + 1, data + size);
  if (data[0] & 1) geom_fuzz::repair_checksums(file);
  geom::baked::Reader reader;
  const bool ok = reader.open(file.data(), file.size());
  if (!ok) {
    require(!reader.error().empty() && reader.error().find('\n') == std::string::npos, "one-line error");
    require(reader.sections().empty(), "no sections after a refusal");
    return 0;
  }
  const unsigned char* begin = file.data();
  uint64_t end_of_previous = 0;
  for (const geom::baked::Section& s : reader.sections()) {
    require(s.stride > 0 && s.size == s.count * s.stride, "size = count x stride");
    require(s.offset % reader.alignment() == 0, "aligned offset");
    require(s.offset >= end_of_previous, "increasing, non-overlapping offsets");
    require(s.offset <= file.size() && s.size <= file.size() - s.offset, "inside the buffer");
    require(s.data == begin + s.offset, "data points at the offset");
    require(geom::baked::crc32c(s.data, s.size) == s.crc, "checksum matches");
    require(reader.find(s.type, s.item) != nullptr, "find() finds it");
    require(s.name[geom::baked::kNameSize - 1] == 0, "name NUL-terminated");
    end_of_previous = s.offset + s.size;
  }
  require(reader.file_size() == file.size(), "file_size is the buffer's size");
  return 0;
}
