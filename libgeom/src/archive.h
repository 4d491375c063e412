// Private: zip (.pk3) archive access through libzip.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace geom::detail {

// Reads one member of a zip archive. False with `error` set when the archive
// cannot be opened, the member is missing, or it is larger than max_bytes (0 = no limit).
bool read_archive_member(const std::string& archive, const std::string& member, std::vector<unsigned char>& bytes,
                         uint64_t max_bytes, std::string& error);

// Listing: geom/import.h list_archive_members.

}  // namespace geom::detail
