// cli/file.h (tools/common, library geom::cli): the apps' one whole-file read
// (geombake's outputs and focus frames, geombench's scene files, geomview's
// inputs). libgeom reads its own inputs (geom/import.h); render/ reads its
// shaders itself, being below the apps.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace cli {

// Reads the regular file `path` into `bytes` (a std::string or a
// std::vector<unsigned char>), whole, or its first `at_most` bytes. False with
// `error` saying what is wrong, without the file name ("cannot open", "not a
// regular file (a directory, FIFO or device): not read", "cannot read"); a
// FIFO or a device is refused before it is opened, so the read cannot block.
template <class Bytes>
bool read_file(const std::string& path, Bytes& bytes, std::string& error, uint64_t at_most = UINT64_MAX) {
  bytes.clear();
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) return error = "cannot open", false;
  if (!std::filesystem::is_regular_file(st))
    return error = "not a regular file (a directory, FIFO or device): not read", false;
  std::ifstream f(path, std::ios::binary);
  if (!f) return error = "cannot open", false;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return error = "cannot read", false;
  bytes.resize(size_t(size < at_most ? size : at_most));
  if (!bytes.empty() && !f.read(reinterpret_cast<char*>(&bytes[0]), std::streamsize(bytes.size()))) {
    bytes.clear();
    return error = "cannot read", false;
  }
  return true;
}

}  // namespace cli
