// Private: the file a glTF's external URI names, one decoding for
// reading it and for listing it in a depfile.
#pragma once
#include <string>

namespace geom::detail {

// RFC 3986 percent-decoding: each "%XX" becomes its byte; everything else,
// '+' included (a literal in a URI path), stays as it is.
std::string percent_decode(const std::string& uri);

// The file that the relative URI `uri` of an asset in `base_dir` names, in
// `path` (base_dir joined with the decoded URI). Returns "" if it may be read,
// else why not. Unless `allow_outside`, the file must lie in base_dir or below
// it once "..", "." and symlinks are resolved: an absolute path, a URI with a
// scheme ("file:", "http:") or one that climbs out is refused, and so is
// every external file of an asset with no folder (base_dir empty: read from
// memory, or an archive member), which would otherwise be looked up in the
// working directory.
std::string resolve_external_uri(const std::string& base_dir, const std::string& uri, bool allow_outside,
                                 std::string& path);

}  // namespace geom::detail
