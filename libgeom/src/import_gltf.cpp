// glTF 2.0 importer (.gltf with external or data-URI buffers, .glb).
//
// Contract (see geom/import.h for the caller's side): fills Scene with the
// triangles of the chosen scene in world space, one TriangleSource per
// triangle (file 0, mesh, primitive, node), and the KHR_lights_punctual
// lights its nodes carry; or returns false with one line saying what is wrong.
//
// What is read, per the glTF 2.0 specification (Khronos, sections 3.5-3.7, 3.11):
//   scene       the default scene, else scene 0, else (no scenes) every root node
//   nodes       matrix or TRS (T * R * S, quaternion normalised), composed down
//               the hierarchy; a mesh used by two nodes is emitted twice
//   primitives  mode 4 (list), 5 (strip), 6 (fan; absent = 4); strips and fans are
//               unrolled with the specification's vertex order (3.7.2.1):
//                 strip i: (v[i], v[i+1+i%2], v[i+2-i%2])   fan i: (v[i+1], v[i+2], v[0])
//               and their index-degenerate triangles (repeated vertex: strip
//               joins) dropped; lists are kept as written. Modes 0-3 (points,
//               lines) are skipped with a warning naming file, mesh, primitive.
//   positions   FLOAT, or (KHR_mesh_quantization) [UNSIGNED_]BYTE/SHORT,
//               normalised (max(x/127, -1), x/255, max(x/32767, -1), x/65535) or not;
//               any byteStride; sparse accessors applied here (tinygltf parses
//               them but does not apply them); an accessor with no bufferView
//               reads as zeros. Only vertices some triangle uses are emitted.
//   Draco       KHR_draco_mesh_compression is decoded here with Draco's decoder,
//               not inside tinygltf: tinygltf 2.7.0's decoder indexes bufferViews,
//               buffers and accessors without bounds checks, dereferences a null
//               attribute for an unknown Draco id and ignores decoding failures.
//               The extension is removed from the JSON before tinygltf sees it.
//   lights      KHR_lights_punctual (read here from the JSON: tinygltf refuses the
//               whole file for one malformed light): position = the node's world
//               origin, direction = its world -Z (normalised), cone angles, range
//               (0 = infinite), colour, intensity. Only lights that nodes of the
//               scene carry are emitted, once per such node. Out-of-spec values are
//               replaced by the defaults or clamped, and a light with no known
//               type or a dangling reference skipped, each with a warning.
//   indices     UNSIGNED_BYTE/SHORT/INT; every value below the vertex count and
//               not the primitive restart value (255, 65535, 2^32-1: section 3.7.2.1).
//               Read here too: tinygltf refuses an indices accessor without a
//               bufferView (valid glTF: zeros plus sparse values).
//   buffers     data URIs (base64 or percent-encoded) are decoded here; external
//               files are read by tinygltf after the checks below. A buffer with no data (no uri outside a GLB's first
//               buffer, e.g. a placeholder an extension fills, or byteLength 0) is accepted, and a bufferView that uses
//               it refused. Integers written as 1.0 are accepted, as the validator does.
// Every mesh is decoded, also those no node uses, so a broken mesh refuses the
// file; the output holds the scene's instances only.
// Ignored: materials, textures, images (never loaded or decoded), animations,
// skins, morph targets, cameras. They are removed from the JSON handed to
// tinygltf, so their problems cannot refuse a file whose geometry is sound.
//
// Hostile input (all refused with a message, never a crash or a huge allocation):
//   GLB framing is parsed here before tinygltf (whose BIN chunk check can read 8
//   bytes past the end): a short header, wrong magic or version, a declared
//   length past the end, a chunk past the end, a first chunk that is not JSON, a
//   second JSON or BIN chunk, a BIN chunk not in second place are refused (an
//   unaligned chunk length or bytes after the declared length: a warning); the
//   GLB handed to tinygltf is rebuilt, well-formed, from the parts. JSON nesting deeper than kMaxJsonDepth (64)
//   is refused (tinygltf converts extras recursively); every bufferView and
//   accessor range (sparse parts included) is checked against the bytes the
//   buffer really holds before anything is read; index values must be below the
//   vertex count; node graphs must be trees (a cycle, a node with two parents, a
//   scene listing a child node or a node twice are refused), so every node is
//   visited once; extensionsRequired other than the ones read here or ones that
//   do not change geometry is refused; external buffers must be regular files of
//   exactly byteLength bytes. The output size is computed before it is allocated
//   and refused over ImportOptions::max_triangles / max_bytes (default limit when
//   max_bytes is 0: kDefaultMaxBytes, 4 GiB) or over 2^32 - 1 vertices.
//   Non-finite positions are refused by the dispatcher (import.cpp).
#include <sys/stat.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "draco/compression/decode.h"
#include "draco/compression/point_cloud/point_cloud_decoder.h"
#include "draco/core/varint_decoding.h"
#include "draco/metadata/geometry_metadata.h"
#include "draco/metadata/metadata_decoder.h"
#include "importers.h"
#include "uri.h"

namespace geom::detail {
namespace {

using Json = nlohmann::json;

constexpr int kMaxJsonDepth = 64;
constexpr uint64_t kDefaultMaxBytes = uint64_t(4) << 30;
constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

// Thrown inside this file only, caught by import_gltf.
struct Refusal : std::runtime_error {
  using std::runtime_error::runtime_error;
};
[[noreturn]] void refuse(const std::string& what) { throw Refusal(what); }

std::string str(uint64_t v) { return std::to_string(v); }

uint32_t read_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
void put_u32(std::vector<unsigned char>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

// ---------------------------------------------------------------- container

struct Container {
  std::string json;
  const unsigned char* bin = nullptr;  // GLB BIN chunk, or null
  size_t bin_size = 0;
  bool glb = false;
};

// GLB layout: glTF 2.0 specification section 4.4 (12-byte header, then chunks
// of [length, type, data]; the first is JSON, an optional BIN follows).
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

// Nesting depth of a JSON text, counted outside strings.
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

// ------------------------------------------------------------- JSON passes

// A primitive whose geometry is Draco-compressed.
struct DracoRef {
  int buffer_view = -1;
  int position_id = -1;
};
using PrimKey = std::pair<int, int>;  // mesh, primitive

// A KHR_lights_punctual light as the JSON gives it (read here, not by tinygltf,
// which refuses the whole file for a malformed light). NaN marks "absent".
struct LightDef {
  std::string type, name;
  std::vector<double> color;
  double intensity = NAN, range = NAN, inner = NAN, outer = NAN;
};

// What sanitize() takes out of the JSON, or learns, for the later stages.
struct SideTable {
  std::vector<LightDef> lights;
  std::map<PrimKey, DracoRef> draco;
  std::map<PrimKey, int> indices;  // primitive -> its indices accessor (absent: not indexed)
  std::vector<char> buffer_has_data;
  std::map<size_t, std::vector<unsigned char>> data_uri;  // buffer -> bytes decoded here
  std::set<std::string> external;                          // the external files checked here: all tinygltf may read
};

bool extension_allowed(const std::string& e) {
  static const char* const kRead[] = {"KHR_draco_mesh_compression", "KHR_mesh_quantization", "KHR_lights_punctual"};
  // Extensions that do not change where vertices are or which triangles exist.
  static const char* const kNeutral[] = {"KHR_texture_transform", "KHR_texture_basisu",    "KHR_xmp_json_ld",
                                         "KHR_animation_pointer", "KHR_node_visibility",   "KHR_techniques_webgl",
                                         "EXT_lights_ies",        "EXT_lights_image_based"};
  for (const char* k : kRead)
    if (e == k) return true;
  for (const char* k : kNeutral)
    if (e == k) return true;
  return e.rfind("KHR_materials_", 0) == 0 || e.rfind("EXT_texture_", 0) == 0 || e.rfind("EXT_materials_", 0) == 0;
}

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

// A buffer's data URI (RFC 2397): base64 or percent-encoded, media type
// application/octet-stream or application/gltf-buffer (glTF 2.0 section 3.6.1.1).
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

bool is_regular_file(const std::string& path, uint64_t* size) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  if (size) *size = uint64_t(st.st_size);
  return true;
}

// Checks what tinygltf would otherwise find late or report vaguely: the asset
// version, required extensions, every buffer's source and size. Then removes
// what the importer does not read and takes the Draco extensions out.
void sanitize(Json& doc, const Container& c, const ImportInput& in, uint64_t max_bytes, SideTable& side) {
  if (!doc.is_object()) refuse("the JSON root is not an object");
  for (const char* key : {"buffers", "bufferViews", "accessors", "meshes", "nodes", "scenes", "extensionsRequired"})
    if (doc.contains(key) && !doc[key].is_array()) refuse(std::string("\"") + key + "\" is not an array");
  auto asset = doc.find("asset");
  if (asset == doc.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
    refuse("asset.version is missing: not a glTF 2.0 file");
  std::string version = (*asset)["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) refuse("asset.version is \"" + version + "\"; only glTF 2.x is supported");

  if (auto req = doc.find("extensionsRequired"); req != doc.end() && req->is_array())
    for (const Json& e : *req)
      if (e.is_string() && !extension_allowed(e.get<std::string>()))
        refuse("the file requires extension " + e.get<std::string>() + ", which this importer does not support");

  uint64_t total = 0;
  if (auto buffers = doc.find("buffers"); buffers != doc.end()) {
    for (size_t i = 0; i < buffers->size(); ++i) {
      Json& b = (*buffers)[i];
      std::string name = "buffer " + str(i);
      if (!b.is_object()) refuse(name + " is not a JSON object");
      auto bl = b.find("byteLength");
      if (bl == b.end() || !bl->is_number_unsigned())
        refuse(name + ": byteLength is missing or not a non-negative integer");
      uint64_t length = bl->get<uint64_t>();
      total += length;
      if (total > max_bytes) refuse("the buffers claim " + str(total) + " bytes, over the limit of " + str(max_bytes));
      auto uri = b.find("uri");
      side.buffer_has_data.push_back(1);
      if ((uri == b.end() && !(c.glb && i == 0)) || length == 0) {
        // No data (a placeholder some extension fills, or empty): tinygltf gets a
        // one-byte stand-in; a bufferView that uses it is refused later.
        side.buffer_has_data.back() = 0;
        b = {{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
        continue;
      }
      if (uri == b.end()) {
        if (!c.bin) refuse(name + " has no uri, but the GLB has no BIN chunk");
        if (length > c.bin_size)
          refuse(name + ": byteLength " + str(length) + " is larger than the GLB BIN chunk (" + str(c.bin_size) +
                 " bytes)");
        continue;
      }
      if (!uri->is_string()) refuse(name + ": uri is not a string");
      const std::string& u = uri->get_ref<const std::string&>();
      if (u.rfind("data:", 0) == 0) {
        // Decoded here (tinygltf's base64 decoder looks each character up in a
        // string, and the JSON handed to it then carries one byte instead).
        std::vector<unsigned char> bytes = decode_data_uri(u, name);
        if (bytes.size() != length)
          refuse(name + ": its data URI holds " + str(bytes.size()) + " bytes, but byteLength says " + str(length));
        side.data_uri[i] = std::move(bytes);
        b = {{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
        continue;
      }
      // One decoding (RFC 3986: '+' is a '+') for reading and for the depfile;
      // confined to the asset's folder unless allowed (uri.h).
      std::string path;
      const std::string why = resolve_external_uri(in.base_dir, u, in.options.allow_outside_uris, path);
      if (!why.empty()) refuse(name + ": " + why);
      uint64_t size = 0;
      if (!is_regular_file(path, &size)) refuse(name + ": cannot open '" + u + "' (looked for " + path + ")");
      if (size != length) refuse(name + ": '" + u + "' is " + str(size) + " bytes, but byteLength says " + str(length));
      // tinygltf decodes with '+' as a space: hand it a URI that decodes to `path`.
      std::string tiny_uri;
      for (char ch : percent_decode(u)) tiny_uri += ch == '%' ? "%25" : ch == '+' ? "%2B" : std::string(1, ch);
      b["uri"] = tiny_uri;
      side.external.insert(path);
    }
  }

  // Lights: taken out of the JSON, read leniently (problems become warnings).
  if (auto ext = doc.find("extensions"); ext != doc.end() && ext->is_object()) {
    auto kl = ext->find("KHR_lights_punctual");
    if (kl != ext->end() && kl->is_object() && kl->contains("lights") && (*kl)["lights"].is_array()) {
      auto number = [](const Json& o, const char* key) {
        return o.is_object() && o.contains(key) && o[key].is_number() ? o[key].get<double>() : NAN;
      };
      for (const Json& l : (*kl)["lights"]) {
        LightDef d;
        if (l.is_object()) {
          if (l.contains("type") && l["type"].is_string()) d.type = l["type"].get<std::string>();
          if (l.contains("name") && l["name"].is_string()) d.name = l["name"].get<std::string>();
          if (l.contains("color") && l["color"].is_array())
            for (const Json& c : l["color"]) d.color.push_back(c.is_number() ? c.get<double>() : -1.0);
          d.intensity = number(l, "intensity");
          d.range = number(l, "range");
          if (l.contains("spot"))
            d.inner = number(l["spot"], "innerConeAngle"), d.outer = number(l["spot"], "outerConeAngle");
        }
        side.lights.push_back(std::move(d));
      }
    }
    if (kl != ext->end()) ext->erase(kl);
  }

  // Not geometry: never loaded, never able to refuse the file.
  for (const char* key : {"images", "textures", "samplers", "materials", "animations", "skins", "cameras"})
    doc.erase(key);

  if (auto meshes = doc.find("meshes"); meshes != doc.end()) {
    for (size_t m = 0; m < meshes->size(); ++m) {
      Json& mesh = (*meshes)[m];
      // Required by glTF 2.0 (5.23): a mesh without them used to bake empty.
      if (!mesh.is_object()) refuse("mesh " + str(m) + " is not a JSON object");
      if (!mesh.contains("primitives") || !mesh["primitives"].is_array())
        refuse("mesh " + str(m) + ": \"primitives\" is missing or not an array");
      Json& prims = mesh["primitives"];
      for (size_t p = 0; p < prims.size(); ++p) {
        Json& prim = prims[p];
        if (!prim.is_object()) continue;
        // Indices are read here (tinygltf refuses an indices accessor without a
        // bufferView, which is valid glTF: zeros plus sparse values).
        if (auto ind = prim.find("indices"); ind != prim.end()) {
          if (!ind->is_number_integer())
            refuse("mesh " + str(m) + " primitive " + str(p) + ": indices is not an accessor index");
          side.indices[{int(m), int(p)}] = ind->get<int>();
          prim.erase(ind);
        }
        auto ext = prim.find("extensions");
        if (ext == prim.end() || !ext->is_object()) continue;
        auto dr = ext->find("KHR_draco_mesh_compression");
        if (dr == ext->end()) continue;
        std::string name = "mesh " + str(m) + " primitive " + str(p) + ": KHR_draco_mesh_compression";
        DracoRef ref;
        if (!dr->is_object() || !dr->contains("bufferView") || !(*dr)["bufferView"].is_number_integer())
          refuse(name + " has no bufferView");
        ref.buffer_view = (*dr)["bufferView"].get<int>();
        auto attrs = dr->find("attributes");
        if (attrs == dr->end() || !attrs->is_object()) refuse(name + " has no attributes");
        if (auto pos = attrs->find("POSITION"); pos != attrs->end()) {
          if (!pos->is_number_integer()) refuse(name + ": attributes.POSITION is not an integer");
          ref.position_id = pos->get<int>();
        }
        side.draco[{int(m), int(p)}] = ref;
        ext->erase(dr);
      }
    }
  }
}

// ------------------------------------------------------------ tinygltf glue

// What tinygltf may read: the external files sanitize() checked, nothing else.
struct FsState {
  uint64_t limit;
  const std::set<std::string>* allowed;
};
bool fs_file_exists(const std::string& path, void* user) {
  return static_cast<const FsState*>(user)->allowed->count(path) && is_regular_file(path, nullptr);
}
std::string fs_expand(const std::string& path, void*) { return path; }
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const FsState& state = *static_cast<const FsState*>(user);
  uint64_t limit = state.limit, size = 0;
  if (!state.allowed->count(path)) {
    if (err) *err = "not a file this importer checked";
    return false;
  }
  if (!is_regular_file(path, &size)) {
    if (err) *err = "not a regular file";
    return false;
  }
  if (size > limit) {
    if (err) *err = "file over the size limit";
    return false;
  }
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  out->resize(size_t(size));
  bool ok = size == 0 || std::fread(out->data(), 1, out->size(), f) == out->size();
  std::fclose(f);
  return ok;
}
bool fs_write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;  // textures are not needed; never decode them
}

// tinygltf's error text: the first line, without data URIs, bounded.
std::string tinygltf_message(const std::string& err) {
  std::string line = err.substr(0, err.find('\n'));
  if (size_t d = line.find("data:"); d != std::string::npos) line = line.substr(0, d) + "(data URI)";
  if (line.size() > 300) line = line.substr(0, 300) + "...";
  return "tinygltf: " + (line.empty() ? std::string("cannot parse the file") : line);
}

void load_model(const Container& c, const Json& doc, const ImportInput& in, uint64_t max_bytes,
                const std::set<std::string>& external, tinygltf::Model& model) {
  std::string json = doc.dump();
  tinygltf::TinyGLTF loader;
  FsState fs_state{max_bytes, &external};
  loader.SetFsCallbacks({&fs_file_exists, &fs_expand, &fs_read, &fs_write, &fs_state});
  loader.SetImageLoader(&skip_image, nullptr);
  std::string err, warn;
  bool ok;
  if (c.glb) {
    // Rebuild a well-formed GLB around the sanitised JSON and the original BIN.
    size_t json_padded = (json.size() + 3) & ~size_t(3);
    size_t bin_padded = (c.bin_size + 3) & ~size_t(3);
    uint64_t total = 12 + 8 + uint64_t(json_padded) + (c.bin ? 8 + uint64_t(bin_padded) : 0);
    if (total > 0xffffffffu) refuse("the GLB is over 4 GiB");
    std::vector<unsigned char> glb;
    glb.reserve(size_t(total));
    put_u32(glb, kGlbMagic);
    put_u32(glb, 2);
    put_u32(glb, uint32_t(total));
    put_u32(glb, uint32_t(json_padded));
    put_u32(glb, kChunkJson);
    glb.insert(glb.end(), json.begin(), json.end());
    glb.resize(glb.size() + json_padded - json.size(), ' ');
    if (c.bin) {
      put_u32(glb, uint32_t(bin_padded));
      put_u32(glb, kChunkBin);
      glb.insert(glb.end(), c.bin, c.bin + c.bin_size);
      glb.resize(glb.size() + bin_padded - c.bin_size, 0);
    }
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size()), in.base_dir,
                                     tinygltf::NO_REQUIRE);
  } else {
    if (json.size() > 0xffffffffu) refuse("the JSON is over 4 GiB");
    ok = loader.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()), in.base_dir,
                                    tinygltf::NO_REQUIRE);
  }
  if (!ok) refuse(tinygltf_message(err));
}

// ------------------------------------------------------------ accessors

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 component types
  }
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "unknown";
  }
}

// Checks that `count` elements of `elem` bytes, `stride` apart, starting at
// `offset` in bufferView `view_index`, lie inside the bufferView and its buffer.
void check_range(const tinygltf::Model& model, const std::string& what, int view_index, uint64_t offset, uint64_t count,
                 uint64_t elem, uint64_t stride) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    refuse(what + " refers to bufferView " + std::to_string(view_index) + ", but the file has " +
           str(model.bufferViews.size()));
  const tinygltf::BufferView& view = model.bufferViews[size_t(view_index)];
  if (count == 0) return;
  uint64_t length = view.byteLength;
  // offset + stride * (count - 1) + elem <= length, without overflow
  bool fits = offset <= length && elem <= length - offset &&
              (count - 1 == 0 || (stride > 0 && (count - 1) <= (length - offset - elem) / stride));
  if (!fits)
    refuse(what + " reads past the end of bufferView " + std::to_string(view_index) + " (" + str(count) +
           " elements of " + str(elem) + " bytes, stride " + str(stride) + ", from byte " + str(offset) + " of " +
           str(length) + "; buffer " + std::to_string(view.buffer) + ")");
}

// Every bufferView inside its buffer, every accessor (sparse parts included)
// inside its bufferView, before anything is read.
void validate_ranges(const tinygltf::Model& model, const std::vector<char>& buffer_has_data) {
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& v = model.bufferViews[i];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size())
      refuse("bufferView " + str(i) + " refers to buffer " + std::to_string(v.buffer) + ", but the file has " +
             str(model.buffers.size()));
    if (size_t(v.buffer) >= buffer_has_data.size() || !buffer_has_data[size_t(v.buffer)])
      refuse("bufferView " + str(i) + " refers to buffer " + std::to_string(v.buffer) +
             ", which has no data (no uri, or byteLength 0)");
    uint64_t size = model.buffers[size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
      refuse("bufferView " + str(i) + " (bytes " + str(v.byteOffset) + " to " +
             str(uint64_t(v.byteOffset) + v.byteLength) + ") reaches past the end of buffer " +
             std::to_string(v.buffer) + " (" + str(size) + " bytes)");
  }
  for (size_t i = 0; i < model.accessors.size(); ++i) {
    const tinygltf::Accessor& a = model.accessors[i];
    std::string what = "accessor " + str(i);
    int csize = component_size(a.componentType), ncomp = component_count(a.type);
    if (!csize)
      refuse(what + ": componentType " + std::to_string(a.componentType) + " is not a glTF 2.0 component type");
    uint64_t elem = uint64_t(csize) * uint64_t(ncomp);
    if (a.bufferView != -1) {
      if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
        refuse(what + " refers to bufferView " + std::to_string(a.bufferView) + ", but the file has " +
               str(model.bufferViews.size()));
      uint64_t stride = model.bufferViews[size_t(a.bufferView)].byteStride;
      if (stride == 0) stride = elem;
      if (stride < elem)
        refuse(what + ": bufferView " + std::to_string(a.bufferView) + " has byteStride " + str(stride) +
               ", smaller than one " + type_name(a.type) + " element (" + str(elem) + " bytes)");
      check_range(model, what, a.bufferView, a.byteOffset, a.count, elem, stride);
    }
    if (!a.sparse.isSparse) continue;
    const auto& s = a.sparse;
    if (s.count < 1 || uint64_t(s.count) > a.count)
      refuse(what + ": sparse count " + std::to_string(s.count) + " is outside 1.." + str(a.count));
    int isize = component_size(s.indices.componentType);
    if (s.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        s.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        s.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || !isize)
      refuse(what + ": sparse indices componentType " + std::to_string(s.indices.componentType) +
             " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    if (s.indices.byteOffset < 0 || s.values.byteOffset < 0) refuse(what + ": negative sparse byteOffset");
    check_range(model, what + " (sparse indices)", s.indices.bufferView, uint64_t(s.indices.byteOffset),
                uint64_t(s.count), uint64_t(isize), uint64_t(isize));
    check_range(model, what + " (sparse values)", s.values.bufferView, uint64_t(s.values.byteOffset), uint64_t(s.count),
                elem, elem);
  }
}

// The integer that a normalized component maps to 1.0.
double normalized_max(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return 127.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return 32767.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 65535.0;
    default:
      return 4294967295.0;
  }
}

double read_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// Reads accessor `index` (ranges already validated) into `out`, `ncomp` values
// per element, sparse substitutions applied. `budget` bounds what an accessor
// without a bufferView (zeros, no bytes behind them) may allocate.
template <class T>
void read_accessor(const tinygltf::Model& model, int index, const std::string& what, uint64_t budget,
                   std::vector<T>& out) {
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  const size_t ncomp = size_t(component_count(a.type));
  const size_t csize = size_t(component_size(a.componentType));
  if (a.bufferView == -1 && a.count > budget / (ncomp * sizeof(T)))
    refuse(what + ": accessor " + std::to_string(index) + " has no bufferView and claims " + str(a.count) +
           " elements, over the memory limit");
  out.assign(size_t(a.count) * ncomp, T(0));
  if (a.bufferView != -1) {
    const tinygltf::BufferView& view = model.bufferViews[size_t(a.bufferView)];
    const unsigned char* base = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    const size_t stride = view.byteStride ? view.byteStride : ncomp * csize;
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && std::is_same<T, float>::value) {
      for (size_t i = 0; i < a.count; ++i) std::memcpy(&out[i * ncomp], base + i * stride, ncomp * 4);
    } else {
      for (size_t i = 0; i < a.count; ++i)
        for (size_t k = 0; k < ncomp; ++k)
          out[i * ncomp + k] =
              static_cast<T>(read_component(base + i * stride + k * csize, a.componentType, a.normalized));
    }
  }
  if (!a.sparse.isSparse) return;
  const auto& s = a.sparse;
  const tinygltf::BufferView& iv = model.bufferViews[size_t(s.indices.bufferView)];
  const tinygltf::BufferView& vv = model.bufferViews[size_t(s.values.bufferView)];
  const unsigned char* ip = model.buffers[size_t(iv.buffer)].data.data() + iv.byteOffset + size_t(s.indices.byteOffset);
  const unsigned char* vp = model.buffers[size_t(vv.buffer)].data.data() + vv.byteOffset + size_t(s.values.byteOffset);
  const size_t isize = size_t(component_size(s.indices.componentType));
  for (size_t j = 0; j < size_t(s.count); ++j) {
    uint64_t target = uint64_t(read_component(ip + j * isize, s.indices.componentType, false));
    if (target >= a.count)
      refuse(what + ": accessor " + std::to_string(index) + " sparse index " + str(target) + " (entry " + str(j) +
             ") is out of range (" + str(a.count) + " elements)");
    for (size_t k = 0; k < ncomp; ++k)
      out[size_t(target) * ncomp + k] =
          static_cast<T>(read_component(vp + (j * ncomp + k) * csize, a.componentType, a.normalized));
  }
}

// ------------------------------------------------------------ primitives

// One primitive's triangles in its own (mesh) space, only the used vertices.
struct Decoded {
  bool triangles = false;        // false: skipped (points, lines, no positions)
  std::vector<float> positions;  // xyz
  std::vector<uint32_t> indices;
};

// Unrolls `idx` (a list, strip or fan) into triangles, then keeps only the
// vertices they use, renumbered in first-use order.
void assemble(const std::vector<float>& positions, const std::vector<uint32_t>& idx, int mode, Decoded& d) {
  std::vector<uint32_t> tris;
  const size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    tris.assign(idx.begin(), idx.begin() + ptrdiff_t(n - n % 3));
  } else if (n >= 3) {
    tris.reserve(3 * (n - 2));
    for (size_t i = 0; i + 2 < n; ++i) {
      uint32_t a, b, c;
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        a = idx[i], b = idx[i + 1 + i % 2], c = idx[i + 2 - i % 2];
      } else {
        a = idx[i + 1], b = idx[i + 2], c = idx[0];
      }
      if (a == b || b == c || a == c) continue;
      tris.insert(tris.end(), {a, b, c});
    }
  }
  std::vector<uint32_t> remap(positions.size() / 3, 0xffffffffu);
  d.indices.resize(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    uint32_t& r = remap[tris[i]];
    if (r == 0xffffffffu) {
      r = uint32_t(d.positions.size() / 3);
      d.positions.insert(d.positions.end(), &positions[3 * size_t(tris[i])], &positions[3 * size_t(tris[i])] + 3);
    }
    d.indices[i] = r;
  }
  d.triangles = true;
}

// Draco (Debian's 1.5.5) allocates, and fills, the counts its connectivity
// header declares before it reads the data they need: 325 bytes claiming 808
// million faces took 19 GB and 46 s, 41 bytes claiming 1.1 billion faces asked for
// 4.6 GB (both found by fuzz/fuzz_draco). So the counts are read here first, as
// Draco reads them (mesh_edgebreaker_decoder_impl.cc, mesh_sequential_decoder.cc):
// header; metadata when the flag is set and the version is 1.3 or later;
// sequential: faces, points (u32 before 2.2, varints after); Edgebreaker:
// traversal type, new vertices (before 2.2), vertices, faces, attribute data,
// symbols, split symbols (u32 before 2.0, varints after). Each must fit the
// stream: real streams hold under one face per byte (0.02 to 0.6 in
// google/draco's test data), so over kMaxDracoCountPerByte per byte is refused.
// Returns "" when the counts fit or are not a mesh's (Draco refuses those itself).
constexpr uint64_t kMaxDracoCountPerByte = 64;
std::string draco_counts_problem(const unsigned char* data, size_t size) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::DracoHeader header;
  if (!draco::PointCloudDecoder::DecodeHeader(&buffer, &header).ok()) return "";
  if (header.encoder_type != draco::TRIANGULAR_MESH) return "";
  const uint16_t version = uint16_t(header.version_major << 8 | header.version_minor);
  buffer.set_bitstream_version(version);
  if (version >= 0x103 && (header.flags & METADATA_FLAG_MASK)) {
    draco::GeometryMetadata metadata;
    if (!draco::MetadataDecoder().DecodeGeometryMetadata(&buffer, &metadata)) return "";
  }
  auto count = [&](uint32_t& v) {
    return version < 0x200 ? buffer.Decode(&v) : draco::DecodeVarint<uint32_t>(&v, &buffer);
  };
  uint32_t faces = 0, vertices = 0, symbols = 0, split_symbols = 0;
  if (header.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
    if (version < 0x202
            ? !(buffer.Decode(&faces) && buffer.Decode(&vertices))
            : !(draco::DecodeVarint<uint32_t>(&faces, &buffer) && draco::DecodeVarint<uint32_t>(&vertices, &buffer)))
      return "";
  } else if (header.encoder_method == draco::MESH_EDGEBREAKER_ENCODING) {
    uint8_t traversal = 0, attribute_data = 0;
    uint32_t new_vertices = 0;
    if (!buffer.Decode(&traversal) || (version < 0x202 && !count(new_vertices)) || !count(vertices) || !count(faces) ||
        !buffer.Decode(&attribute_data) || !count(symbols) || !count(split_symbols))
      return "";
  } else {
    return "";
  }
  const uint64_t limit = kMaxDracoCountPerByte * uint64_t(size);
  auto over = [&](uint32_t a, const char* a_name, uint32_t b, const char* b_name) -> std::string {
    if (a <= limit && b <= limit) return "";
    return "the Draco stream claims " + std::to_string(a) + " " + a_name + " and " + std::to_string(b) + " " + b_name +
           " in " + std::to_string(size) + " bytes (at most " + std::to_string(kMaxDracoCountPerByte) + " per byte)";
  };
  std::string problem = over(faces, "faces", vertices, "vertices");
  return problem.empty() ? over(symbols, "symbols", split_symbols, "split symbols") : problem;
}

void decode_draco(const tinygltf::Model& model, const tinygltf::Primitive& prim, const DracoRef& ref,
                  const std::string& what, Decoded& d) {
  check_range(model, what + " (KHR_draco_mesh_compression)", ref.buffer_view, 0, 1, 0, 0);
  const tinygltf::BufferView& view = model.bufferViews[size_t(ref.buffer_view)];
  if (ref.position_id < 0) refuse(what + ": KHR_draco_mesh_compression has no POSITION attribute");
  const unsigned char* bytes = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset;
  if (std::string problem = draco_counts_problem(bytes, view.byteLength); !problem.empty())
    refuse(what + ": " + problem);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), view.byteLength);
  draco::Decoder decoder;
  draco_guard_refusal();  // libdraco runs draco_guard.cpp's bounded texture-coordinate decoders
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    const std::string guard = draco_guard_refusal();
    refuse(what + ": Draco data in bufferView " + std::to_string(ref.buffer_view) +
           " cannot be decoded: " + (guard.empty() ? decoded.status().error_msg_string() : guard));
  }
  const draco::Mesh& mesh = *decoded.value();
  const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(uint32_t(ref.position_id));
  if (!att)
    refuse(what + ": the Draco data has no attribute with id " + std::to_string(ref.position_id) + " (POSITION)");
  if (att->num_components() != 3)
    refuse(what + ": the Draco POSITION attribute has " + std::to_string(att->num_components()) + " components");
  // Numbers only: reading a DT_BOOL attribute converts bytes other than 0 and 1
  // through a bool, which is undefined behaviour (found by fuzz/fuzz_draco).
  if (att->data_type() < draco::DT_INT8 || att->data_type() > draco::DT_FLOAT64)
    refuse(what + ": the Draco POSITION attribute has data type " + std::to_string(int(att->data_type())) +
           ", not a number type");
  // A quantized (integer) position accessor describes the decoded values: apply
  // its normalisation when Draco's attribute does not say so itself.
  double scale = 1.0;
  auto pos = prim.attributes.find("POSITION");
  if (pos != prim.attributes.end() && pos->second >= 0 && size_t(pos->second) < model.accessors.size()) {
    const tinygltf::Accessor& acc = model.accessors[size_t(pos->second)];
    if (acc.normalized && !att->normalized() && acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      scale = 1.0 / normalized_max(acc.componentType);
  }
  const size_t np = mesh.num_points();
  std::vector<float> positions(np * 3);
  for (size_t i = 0; i < np; ++i) {
    float v[3];
    if (!att->ConvertValue<float, 3>(att->mapped_index(draco::PointIndex(uint32_t(i))), v))
      refuse(what + ": the Draco POSITION value of point " + str(i) + " cannot be read");
    for (int k = 0; k < 3; ++k) positions[3 * i + k] = float(v[k] * scale);
  }
  std::vector<uint32_t> idx(size_t(mesh.num_faces()) * 3);
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      uint32_t v = face[k].value();
      if (v >= np) refuse(what + ": Draco face " + str(f) + " uses point " + str(v) + " of " + str(np));
      idx[3 * size_t(f) + k] = v;
    }
  }
  assemble(positions, idx, TINYGLTF_MODE_TRIANGLES, d);
}

void decode_primitive(const tinygltf::Model& model, int mesh_index, int prim_index, const SideTable& side,
                      const std::string& file, uint64_t budget, std::vector<std::string>& warnings, Decoded& d) {
  const tinygltf::Primitive& prim = model.meshes[size_t(mesh_index)].primitives[size_t(prim_index)];
  const std::string what = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(prim_index);
  static const char* const kModeNames[] = {"points", "lines", "line loop", "line strip"};
  if (prim.mode >= 0 && prim.mode <= 3) {
    warnings.push_back(file + ": " + what + ": " + kModeNames[prim.mode] + " (mode " + std::to_string(prim.mode) +
                       ") skipped, only triangles are imported");
    return;
  }
  if (prim.mode > 6 || prim.mode < 0)
    refuse(what + ": mode " + std::to_string(prim.mode) + " is not a glTF primitive mode");
  if (auto it = side.draco.find({mesh_index, prim_index}); it != side.draco.end()) {
    decode_draco(model, prim, it->second, what, d);
    return;
  }
  auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) {
    warnings.push_back(file + ": " + what + " has no POSITION attribute, skipped");
    return;
  }
  if (pos->second < 0 || size_t(pos->second) >= model.accessors.size())
    refuse(what + ": POSITION refers to accessor " + std::to_string(pos->second) + ", but the file has " +
           str(model.accessors.size()));
  const tinygltf::Accessor& pa = model.accessors[size_t(pos->second)];
  if (pa.type != TINYGLTF_TYPE_VEC3)
    refuse(what + ": POSITION accessor " + std::to_string(pos->second) + " is " + type_name(pa.type) + ", not VEC3");
  std::vector<float> positions;
  read_accessor(model, pos->second, what + " POSITION", budget, positions);
  const size_t nv = positions.size() / 3;

  std::vector<uint32_t> idx;
  if (auto ind = side.indices.find({mesh_index, prim_index}); ind != side.indices.end()) {
    const int indices = ind->second;
    if (indices < 0 || size_t(indices) >= model.accessors.size())
      refuse(what + ": indices refer to accessor " + std::to_string(indices) + ", but the file has " +
             str(model.accessors.size()));
    const tinygltf::Accessor& ia = model.accessors[size_t(indices)];
    if (ia.type != TINYGLTF_TYPE_SCALAR ||
        (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ||
        ia.normalized)
      refuse(what + ": indices accessor " + std::to_string(indices) +
             " is not a SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    read_accessor(model, indices, what + " indices", budget, idx);
    const uint32_t restart = uint32_t(normalized_max(ia.componentType));
    for (size_t i = 0; i < idx.size(); ++i) {
      if (idx[i] >= nv)
        refuse("accessor " + std::to_string(indices) + " (indices of " + what + "): element " + str(i) + " is vertex " +
               str(idx[i]) + ", out of range (" + str(nv) + " vertices)");
      if (idx[i] == restart)  // glTF 2.0 section 3.7.2.1: MUST NOT be used
        refuse("accessor " + std::to_string(indices) + " (indices of " + what + "): element " + str(i) + " is " +
               str(restart) + ", the primitive restart value, which glTF forbids");
    }
  } else {
    if (nv > 0xffffffffu) refuse(what + ": more than 2^32 - 1 vertices");
    idx.resize(nv);
    for (size_t i = 0; i < nv; ++i) idx[i] = uint32_t(i);
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLES && idx.size() % 3 != 0)
    warnings.push_back(file + ": " + what + ": " + str(idx.size()) + " indices is not a multiple of 3, the last " +
                       str(idx.size() % 3) + " ignored");
  assemble(positions, idx, prim.mode, d);
}

// ------------------------------------------------------------ scene graph

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it
constexpr Mat4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

// The node's local matrix: `matrix`, else T * R * S (glTF 2.0 section 3.5.3).
Mat4 local_matrix(const tinygltf::Node& n, size_t index) {
  const std::string what = "node " + str(index);
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) refuse(what + ": matrix has " + str(n.matrix.size()) + " numbers, not 16");
    Mat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  if (!n.translation.empty() && n.translation.size() != 3)
    refuse(what + ": translation has " + str(n.translation.size()) + " numbers, not 3");
  if (!n.scale.empty() && n.scale.size() != 3) refuse(what + ": scale has " + str(n.scale.size()) + " numbers, not 3");
  if (!n.rotation.empty() && n.rotation.size() != 4)
    refuse(what + ": rotation has " + str(n.rotation.size()) + " numbers, not 4");
  double t[3] = {0, 0, 0}, s[3] = {1, 1, 1}, q[4] = {0, 0, 0, 1};
  std::copy(n.translation.begin(), n.translation.end(), t);
  std::copy(n.scale.begin(), n.scale.end(), s);
  std::copy(n.rotation.begin(), n.rotation.end(), q);
  double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(len > 0) || !std::isfinite(len)) refuse(what + ": rotation is not a usable quaternion");
  for (double& c : q) c /= len;
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};  // columns
  Mat4 m{};
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m[c * 4 + row] = r[c * 3 + row] * s[c];
  m[12] = t[0], m[13] = t[1], m[14] = t[2], m[15] = 1;
  return m;
}

struct Instance {
  int node, mesh;
  Mat4 world;
};

// Picks the scene's root nodes, checks that the node graph is a set of trees,
// and returns every node of the scene with its world matrix (each once).
std::vector<Instance> walk_scene(const tinygltf::Model& model) {
  const size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const tinygltf::Node& node = model.nodes[i];
    if (node.mesh < -1 || node.mesh >= int(model.meshes.size()))
      refuse("node " + str(i) + " refers to mesh " + std::to_string(node.mesh) + ", but the file has " +
             str(model.meshes.size()));
    for (int c : node.children) {
      if (c < 0 || size_t(c) >= n)
        refuse("node " + str(i) + " has child " + std::to_string(c) + ", but the file has " + str(n) + " nodes");
      if (size_t(c) == i) refuse("node " + str(i) + " is its own child (a node loop)");
      if (parent[size_t(c)] != -1)
        refuse("node " + std::to_string(c) + " has two parents (nodes " + std::to_string(parent[size_t(c)]) + " and " +
               str(i) + ")");
      parent[size_t(c)] = int(i);
    }
  }
  // With one parent per node, a node whose parent chain never reaches a root
  // lies on a cycle or below one.
  std::vector<char> state(n, 0);  // 0 unknown, 1 reaches a root, 2 on the current chain
  for (size_t i = 0; i < n; ++i) {
    std::vector<size_t> chain;
    size_t k = i;
    while (state[k] == 0 && parent[k] != -1) {
      state[k] = 2;
      chain.push_back(k);
      k = size_t(parent[k]);
    }
    if (state[k] == 2) refuse("the node hierarchy has a cycle through node " + str(k));
    for (size_t c : chain) state[c] = 1;
    state[k] = 1;
  }

  std::vector<int> roots;
  if (!model.scenes.empty() || model.defaultScene >= 0) {
    int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(s) >= model.scenes.size())
      refuse("the default scene " + std::to_string(s) + " does not exist (the file has " + str(model.scenes.size()) +
             " scenes)");
    std::vector<char> listed(n, 0);
    for (int r : model.scenes[size_t(s)].nodes) {
      if (r < 0 || size_t(r) >= n)
        refuse("scene " + std::to_string(s) + " lists node " + std::to_string(r) + ", but the file has " + str(n) +
               " nodes");
      if (parent[size_t(r)] != -1)
        refuse("scene " + std::to_string(s) + " lists node " + std::to_string(r) + ", a child of node " +
               std::to_string(parent[size_t(r)]) + ", as a root");
      if (listed[size_t(r)]++) refuse("scene " + std::to_string(s) + " lists node " + std::to_string(r) + " twice");
      roots.push_back(r);
    }
  } else {
    for (size_t i = 0; i < n; ++i)
      if (parent[i] == -1) roots.push_back(int(i));
  }

  std::vector<Instance> out;
  std::vector<std::pair<int, Mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, kIdentity});
  while (!stack.empty()) {
    auto [index, parent_world] = stack.back();
    stack.pop_back();
    const tinygltf::Node& node = model.nodes[size_t(index)];
    Mat4 world = multiply(parent_world, local_matrix(node, size_t(index)));
    out.push_back({index, node.mesh, world});
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
  }
  return out;
}

// ------------------------------------------------------------ lights

void add_light(const tinygltf::Model& model, const std::vector<LightDef>& lights, const Instance& inst,
               const std::string& file, Scene& out) {
  const tinygltf::Node& node = model.nodes[size_t(inst.node)];
  auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end() || !ext->second.IsObject()) return;
  const std::string where = file + ": node " + std::to_string(inst.node);
  const tinygltf::Value& li = ext->second.Get("light");
  if (!li.IsInt() || li.Get<int>() < 0 || size_t(li.Get<int>()) >= lights.size()) {
    out.warnings.push_back(where + " refers to a KHR_lights_punctual light that does not exist, ignored");
    return;
  }
  const int index = li.Get<int>();
  const LightDef& src = lights[size_t(index)];
  const std::string what = where + ": light " + std::to_string(index);
  Light l;
  if (src.type == "directional")
    l.type = LightType::Directional;
  else if (src.type == "point")
    l.type = LightType::Point;
  else if (src.type == "spot")
    l.type = LightType::Spot;
  else {
    out.warnings.push_back(what + " has no known type (\"" + src.type + "\"), ignored");
    return;
  }
  l.name = src.name;
  const Mat4& m = inst.world;
  double p[3] = {m[12], m[13], m[14]};
  double d[3] = {-m[8], -m[9], -m[10]};  // world image of (0, 0, -1)
  double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
    out.warnings.push_back(what + " has a non-finite position, ignored");
    return;
  }
  if (l.type != LightType::Point && !(len > 0 && std::isfinite(len))) {
    out.warnings.push_back(what + ": the node's transform gives no direction (zero scale), ignored");
    return;
  }
  for (int k = 0; k < 3; ++k) {
    l.position[k] = float(p[k]);
    if (len > 0 && std::isfinite(len)) l.direction[k] = float(d[k] / len);
  }
  if (src.color.size() == 3 && std::all_of(src.color.begin(), src.color.end(), [](double c) { return c >= 0; })) {
    for (int k = 0; k < 3; ++k) l.color[k] = float(src.color[size_t(k)]);
  } else if (!src.color.empty()) {
    out.warnings.push_back(what + ": color is not 3 non-negative numbers, white used");
  }
  if (src.intensity >= 0)
    l.intensity = float(src.intensity);
  else if (!std::isnan(src.intensity))
    out.warnings.push_back(what + ": negative intensity, 1 used");
  if (src.range > 0)
    l.range = float(src.range);
  else if (!std::isnan(src.range))
    out.warnings.push_back(what + ": range is not positive, infinite used");
  if (l.type == LightType::Spot) {
    const double half_pi = 1.5707963267948966;
    double inner = std::isnan(src.inner) ? 0.0 : src.inner;
    double outer = std::isnan(src.outer) ? half_pi / 2 : src.outer;
    if (!(outer > 0 && outer <= half_pi) || !(inner >= 0 && inner < outer)) {
      out.warnings.push_back(what + ": spot cone angles outside 0 <= inner < outer <= pi/2, clamped");
      outer = std::min(std::max(outer, 1e-6), half_pi);
      inner = std::min(std::max(inner, 0.0), outer);
    }
    l.inner_cone = float(inner);
    l.outer_cone = float(outer);
  }
  out.lights.push_back(l);
}

// JSON numbers written as 1.0 where an integer is meant are integers
// (the validator accepts them; tinygltf does not).
void integral_floats_to_integers(Json& j) {
  if (j.is_number_float()) {
    double v = j.get<double>();
    if (std::floor(v) == v && std::fabs(v) < 9007199254740992.0) {
      if (v >= 0)
        j = uint64_t(v);
      else
        j = int64_t(v);
    }
  } else if (j.is_structured()) {
    for (Json& e : j) integral_floats_to_integers(e);
  }
}

void import(const ImportInput& in, Scene& out) {
  const uint64_t max_bytes = in.options.max_bytes ? in.options.max_bytes : kDefaultMaxBytes;
  std::string ext = in.name.size() >= 4 ? in.name.substr(in.name.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  std::vector<std::string> container_warnings;
  Container c = split_container(in, ext == ".glb", container_warnings);
  for (const std::string& w : container_warnings) out.warnings.push_back(in.name + ": " + w);

  if (json_depth(c.json) > kMaxJsonDepth)
    refuse("the JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  Json doc;
  try {
    doc = Json::parse(c.json);
  } catch (const Json::exception& e) {
    std::string msg = e.what();
    if (msg.rfind("[json.exception.", 0) == 0 && msg.find("] ") != std::string::npos)
      msg = msg.substr(msg.find("] ") + 2);
    refuse("invalid JSON: " + msg);
  }
  integral_floats_to_integers(doc);  // depth bounded by kMaxJsonDepth
  SideTable side;
  sanitize(doc, c, in, max_bytes, side);
  tinygltf::Model model;
  load_model(c, doc, in, max_bytes, side.external, model);
  doc = Json();
  for (auto& [i, bytes] : side.data_uri)
    if (i < model.buffers.size()) model.buffers[i].data = std::move(bytes);

  validate_ranges(model, side.buffer_has_data);
  std::vector<Instance> nodes = walk_scene(model);

  // Every primitive of every mesh, once (a broken mesh refuses the file even
  // when no node uses it).
  std::vector<std::vector<Decoded>> decoded(model.meshes.size());
  uint64_t skipped = 0;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    decoded[m].resize(model.meshes[m].primitives.size());
    for (size_t p = 0; p < decoded[m].size(); ++p) {
      decode_primitive(model, int(m), int(p), side, in.name, max_bytes, out.warnings, decoded[m][p]);
      if (!decoded[m][p].triangles) ++skipped;
    }
  }

  // The output's size, before it is allocated.
  uint64_t vertices = 0, triangles = 0;
  for (const Instance& inst : nodes) {
    if (inst.mesh < 0) continue;
    for (const Decoded& d : decoded[size_t(inst.mesh)]) {
      vertices += d.positions.size() / 3;
      triangles += d.indices.size() / 3;
    }
  }
  if (in.options.max_triangles && triangles > in.options.max_triangles)
    refuse(str(triangles) + " triangles, over the limit of " + str(in.options.max_triangles));
  if (vertices > 0xffffffffu) refuse("the scene has " + str(vertices) + " vertices, more than 2^32 - 1");
  const uint64_t bytes = vertices * 12 + triangles * (12 + sizeof(TriangleSource));
  if (bytes > max_bytes)
    refuse("the scene expands to " + str(triangles) + " triangles and " + str(vertices) + " vertices (" + str(bytes) +
           " bytes), over the limit of " + str(max_bytes));

  out.positions.reserve(size_t(vertices) * 3);
  out.indices.reserve(size_t(triangles) * 3);
  out.sources.reserve(size_t(triangles));
  uint64_t draco_used = 0, instances = 0;
  for (const Instance& inst : nodes) {
    add_light(model, side.lights, inst, in.name, out);
    if (inst.mesh < 0) continue;
    const Mat4& m = inst.world;
    for (size_t p = 0; p < decoded[size_t(inst.mesh)].size(); ++p) {
      const Decoded& d = decoded[size_t(inst.mesh)][p];
      if (!d.triangles) continue;
      ++instances;
      if (side.draco.count({inst.mesh, int(p)})) ++draco_used;
      const uint32_t base = uint32_t(out.positions.size() / 3);
      for (size_t v = 0; v < d.positions.size(); v += 3) {
        const double x = d.positions[v], y = d.positions[v + 1], z = d.positions[v + 2];
        for (int r = 0; r < 3; ++r) out.positions.push_back(float(m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r]));
      }
      for (uint32_t i : d.indices) out.indices.push_back(base + i);
      TriangleSource src;
      src.file = 0;
      src.mesh = uint32_t(inst.mesh);
      src.primitive = uint32_t(p);
      src.node = uint32_t(inst.node);
      out.sources.insert(out.sources.end(), d.indices.size() / 3, src);
    }
  }
  out.source_counts.push_back({"primitives.instanced", instances});
  out.source_counts.push_back({"primitives.draco", draco_used});
  out.source_counts.push_back({"primitives.skipped", skipped});
}

}  // namespace

bool import_gltf(const ImportInput& in, Scene& out, std::string& error) {
  try {
    import(in, out);
    return true;
  } catch (const Refusal& r) {
    error = r.what();
  } catch (const std::bad_alloc&) {
    error = "out of memory (the file claims more data than can be held)";
  } catch (const std::exception& e) {
    error = std::string("unexpected error: ") + e.what();
  }
  return false;
}

std::vector<std::string> gltf_buffer_uris(const unsigned char* data, size_t size) {
  std::vector<std::string> uris;
  const Json doc = Json::parse(data, data + size, nullptr, false);
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return uris;
  for (const auto& b : doc["buffers"]) {
    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
    std::string uri = b["uri"].get<std::string>();
    if (uri.rfind("data:", 0) != 0) uris.push_back(std::move(uri));
  }
  return uris;
}

}  // namespace geom::detail
