// SHA-256 (FIPS 180-4) of a file's bytes, for the report's content hashes: a
// pipeline's cache keys an input by what it holds, not by its path or mtime.
#pragma once
#include <string>

namespace geombake {

// The SHA-256 of the file at `path` as 64 lower-case hex digits; "" if it
// cannot be read (missing, not a regular file, an I/O error).
std::string file_sha256(const std::string& path);

// The SHA-256 of `bytes`, as above.
std::string sha256_hex(const std::string& bytes);

}  // namespace geombake
