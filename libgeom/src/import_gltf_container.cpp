// glTF importer, the container: GLB framing (parsed here, before tinygltf,
// whose BIN chunk check can read past the end), the JSON's nesting depth and
// buffers' data URIs (gltf.h).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gltf.h"

namespace geom::detail::gltf {

namespace {

uint32_t read_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

}  // namespace

Container split_container(const ImportInput& in, bool glb_extension, std::vector<std::string>& warnings) {
  Container c;
  bool has_magic = in.size >= 4 && read_u32(in.data) == kGlbMagic;
  if (!has_magic && !glb_extension) {
    if (in.size) c.json.assign(reinterpret_cast<const char*>(in.data), in.size);
    return c;
  }
  c.glb = true;
  if (in.size < 12) refuse("GLB header truncated: " + str(in.size) + " bytes, a GLB header needs 12");
  if (!has_magic) refuse("not a GLB file: the first 4 bytes are not 'glTF'");
  uint32_t version = read_u32(in.data + 4), length = read_u32(in.data + 8);
  if (version != 2) refuse("GLB version " + str(version) + " is not supported (only version 2)");
  if (length > in.size)
    refuse("GLB header says the file is " + str(length) + " bytes, but it is " + str(in.size) + " (truncated)");
  if (length < 12) refuse("GLB header says the file is " + str(length) + " bytes, less than the header");
  if (length < in.size)
    warnings.push_back("GLB header says the file is " + str(length) + " bytes; the " + str(in.size - length) +
                       " bytes after that are ignored");
  const size_t size = length;
  size_t off = 12;
  int index = 0;
  bool have_json = false, have_bin = false;
  while (off < size) {
    if (size - off < 8) refuse("GLB chunk " + str(index) + " header at byte " + str(off) + " is truncated");
    uint32_t clen = read_u32(in.data + off), ctype = read_u32(in.data + off + 4);
    if (clen > size - off - 8)
      refuse("GLB chunk " + str(index) + " at byte " + str(off) + " claims " + str(clen) +
             " bytes, past the end of the file");
    const unsigned char* data = in.data + off + 8;
    if (clen % 4 != 0)
      warnings.push_back("GLB chunk " + str(index) + " length " + str(clen) + " is not a multiple of 4");
    if (index == 0 && ctype != kChunkJson) refuse("the first GLB chunk is not JSON");
    if (ctype == kChunkJson) {
      if (have_json) refuse("GLB has a second JSON chunk (chunk " + str(index) + ")");
      if (clen == 0) refuse("the GLB JSON chunk is empty");
      have_json = true;
      c.json.assign(reinterpret_cast<const char*>(data), clen);
    } else if (ctype == kChunkBin) {
      if (have_bin) refuse("GLB has a second BIN chunk (chunk " + str(index) + ")");
      if (index != 1) refuse("the GLB BIN chunk must be the second chunk, it is chunk " + str(index));
      have_bin = true;
      if (clen > 0) {
        c.bin = data;
        c.bin_size = clen;
      }
    }  // other chunk types are skipped, as the specification says
    off += 8 + size_t(clen);
    ++index;
  }
  if (!have_json) refuse("GLB has no JSON chunk");
  return c;
}

int json_depth(const std::string& s) {
  int depth = 0, max_depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < s.size(); ++i) {
    char ch = s[i];
    if (in_string) {
      if (ch == '\\')
        ++i;
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      max_depth = std::max(max_depth, ++depth);
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  return max_depth;
}

namespace {

// tinygltf's own decoding of URIs ('+' a space), kept for percent-encoded data
// URIs; external file URIs are decoded by uri.h (RFC 3986) and handed to
// tinygltf re-encoded, so that it reads the file checked here.
std::string url_decode(const std::string& s) {
  auto hex = [](unsigned char ch) -> unsigned char {
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return 0;
  };
  std::string r;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      r += ' ';
    } else if (s[i] == '%' && s.size() > i + 2) {
      r += char(hex(static_cast<unsigned char>(s[i + 1])) << 4 | hex(static_cast<unsigned char>(s[i + 2])));
      i += 2;
    } else {
      r += s[i];
    }
  }
  return r;
}

}  // namespace

std::vector<unsigned char> decode_data_uri(const std::string& u, const std::string& name) {
  const size_t comma = u.find(',');
  if (comma == std::string::npos) refuse(name + ": data URI has no ','");
  std::string header = u.substr(5, comma - 5);
  const bool b64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
  if (b64) header.resize(header.size() - 7);
  if (header != "application/octet-stream" && header != "application/gltf-buffer")
    refuse(name + ": data URI media type is \"" + header.substr(0, 60) +
           "\", not application/octet-stream or application/gltf-buffer");
  std::vector<unsigned char> out;
  if (!b64) {
    std::string decoded = url_decode(u.substr(comma + 1));
    out.assign(decoded.begin(), decoded.end());
    return out;
  }
  static const std::array<int8_t, 256> table = [] {
    std::array<int8_t, 256> t;
    t.fill(-1);
    const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int i = 0; i < 64; ++i) t[static_cast<unsigned char>(k[i])] = int8_t(i);
    return t;
  }();
  size_t end = u.size();
  while (end > comma + 1 && u[end - 1] == '=' && u.size() - end < 2) --end;
  const size_t n = end - comma - 1;
  if (n % 4 == 1) refuse(name + ": data URI base64 length is impossible");
  out.reserve(n / 4 * 3 + 2);
  uint32_t acc = 0;
  int bits = 0;
  for (size_t i = comma + 1; i < end; ++i) {
    const int v = table[static_cast<unsigned char>(u[i])];
    if (v < 0) refuse(name + ": data URI has a character that is not base64 at offset " + str(i));
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>(acc >> bits));
    }
  }
  return out;
}

}  // namespace geom::detail::gltf
