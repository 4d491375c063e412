// External URIs of glTF assets (uri.h): decoded once, confined to the asset's folder.
#include "uri.h"

#include <cctype>
#include <filesystem>

namespace geom::detail {

std::string percent_decode(const std::string& uri) {
  auto hex = [](char ch) {
    const unsigned char c = static_cast<unsigned char>(ch);
    return std::isdigit(c) ? c - '0' : std::isxdigit(c) ? std::tolower(c) - 'a' + 10 : -1;
  };
  std::string r;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      r += char(hex(uri[i + 1]) << 4 | hex(uri[i + 2]));
      i += 2;
    } else {
      r += uri[i];
    }
  }
  return r;
}

std::string resolve_external_uri(const std::string& base_dir, const std::string& uri, bool allow_outside,
                                 std::string& path) {
  namespace fs = std::filesystem;
  const std::string decoded = percent_decode(uri);
  path = base_dir.empty() ? decoded : base_dir.back() == '/' ? base_dir + decoded : base_dir + "/" + decoded;
  if (decoded.find('\0') != std::string::npos) return "'" + uri + "' holds a NUL byte";
  if (allow_outside) return "";
  if (base_dir.empty())  // import_memory() without a folder, an archive member: nothing beside it to read
    return "'" + uri + "' is an external file, but the asset has no folder (read from memory or an archive)";
  // A scheme: letters, digits, '+', '-', '.' before the first ':' (RFC 3986 3.1).
  const size_t colon = uri.find(':');
  if (colon != std::string::npos && colon > 0 && std::isalpha(static_cast<unsigned char>(uri[0])) &&
      uri.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789+-.") == colon)
    return "'" + uri +
           "' is not a relative file reference (only files beside the asset are read; --allow-outside-uris)";
  if (!decoded.empty() && (decoded[0] == '/' || decoded[0] == '\\'))
    return "'" + uri + "' is an absolute path, outside the asset's folder (--allow-outside-uris reads it)";
  std::error_code ec;
  const fs::path base = fs::canonical(base_dir.empty() ? fs::path(".") : fs::path(base_dir), ec);
  if (ec) return "cannot resolve the asset's folder '" + base_dir + "': " + ec.message();
  const fs::path target = fs::weakly_canonical(base / fs::path(decoded), ec);
  if (ec) return "cannot resolve '" + uri + "': " + ec.message();
  const std::string b = base.string(), t = target.string();
  if (t.size() <= b.size() || t.compare(0, b.size(), b) != 0 || (b != "/" && t[b.size()] != '/'))
    return "'" + uri + "' leads outside the asset's folder (to " + t + "); --allow-outside-uris reads it";
  return "";
}

}  // namespace geom::detail
