// Private: libgeom's one whole-file read, used by every reader of the library
// (import_file, input_dependencies, a glTF's external buffers; archive members
// are read through libzip, archive.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace geom::detail {

// Reads a regular file whole. Anything else (a FIFO, a device, a directory) is
// refused by name before it is opened, and again by its descriptor after (it
// may have been swapped in between); a file larger than max_bytes (0 = no
// limit), or than this machine's memory, is refused before anything is
// allocated. False with `error` saying what is wrong (no file name: the caller
// prefixes it, "FILE: what is wrong").
bool read_whole_file(const std::string& path, std::vector<unsigned char>& bytes, uint64_t max_bytes,
                     std::string& error);

// This machine's physical memory in bytes (0 if unknown): no input or archive
// member larger than it is read.
uint64_t physical_memory_bytes();

}  // namespace geom::detail
