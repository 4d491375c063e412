// glTF 2.0 importer (gltf.h: the contract, the stages): the JSON passes
// (checks, what is not read taken out, lights, indices and Draco extensions
// taken aside), tinygltf's load of what remains, and the Model the later
// stages read. The one file that includes tinygltf and the JSON library.
#include <sys/stat.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "file_read.h"
#include "gltf.h"
#include "importers.h"
#include "uri.h"

namespace geom::detail {
namespace gltf {
namespace {

using Json = nlohmann::json;

constexpr int kMaxJsonDepth = 64;
constexpr uint64_t kDefaultMaxBytes = uint64_t(4) << 30;

static_assert(kByte == TINYGLTF_COMPONENT_TYPE_BYTE && kUnsignedByte == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
              kShort == TINYGLTF_COMPONENT_TYPE_SHORT && kUnsignedShort == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
              kUnsignedInt == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && kFloat == TINYGLTF_COMPONENT_TYPE_FLOAT);
static_assert(kVec2 == TINYGLTF_TYPE_VEC2 && kVec3 == TINYGLTF_TYPE_VEC3 && kVec4 == TINYGLTF_TYPE_VEC4 &&
              kMat2 == TINYGLTF_TYPE_MAT2 && kMat3 == TINYGLTF_TYPE_MAT3 && kMat4 == TINYGLTF_TYPE_MAT4 &&
              kScalar == TINYGLTF_TYPE_SCALAR);
static_assert(kTriangles == TINYGLTF_MODE_TRIANGLES && kTriangleStrip == TINYGLTF_MODE_TRIANGLE_STRIP);

void put_u32(std::vector<unsigned char>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

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

bool is_regular_file(const std::string& path, uint64_t* size) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  if (size) *size = uint64_t(st.st_size);
  return true;
}

// The JSON's shape, the asset version, the extensions it requires.
void check_root(Json& doc) {
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
}

// Buffer i: its byte length (added to `total`, refused over max_bytes) and
// its source: none (a one-byte stand-in), the GLB's BIN chunk, a data URI
// (decoded here into the side table) or an external file (checked, confined).
void sanitize_buffer(Json& b, size_t i, const Container& c, const ImportInput& in, uint64_t max_bytes, uint64_t& total,
                     SideTable& side) {
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
    return;
  }
  if (uri == b.end()) {
    if (!c.bin) refuse(name + " has no uri, but the GLB has no BIN chunk");
    if (length > c.bin_size)
      refuse(name + ": byteLength " + str(length) + " is larger than the GLB BIN chunk (" + str(c.bin_size) +
             " bytes)");
    return;
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
    return;
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

// Lights: taken out of the JSON, read leniently (problems become warnings).
void take_lights(Json& doc, SideTable& side) {
  auto ext = doc.find("extensions");
  if (ext == doc.end() || !ext->is_object()) return;
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

// Primitive p of mesh m: its indices accessor and its Draco extension taken
// into the side table.
void take_primitive(Json& prim, size_t m, size_t p, SideTable& side) {
  if (!prim.is_object()) return;
  // Indices are read here (tinygltf refuses an indices accessor without a
  // bufferView, which is valid glTF: zeros plus sparse values).
  if (auto ind = prim.find("indices"); ind != prim.end()) {
    if (!ind->is_number_integer())
      refuse("mesh " + str(m) + " primitive " + str(p) + ": indices is not an accessor index");
    side.indices[{int(m), int(p)}] = ind->get<int>();
    prim.erase(ind);
  }
  auto ext = prim.find("extensions");
  if (ext == prim.end() || !ext->is_object()) return;
  auto dr = ext->find("KHR_draco_mesh_compression");
  if (dr == ext->end()) return;
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

// Checks what tinygltf would otherwise find late or report vaguely: the asset
// version, required extensions, every buffer's source and size. Then removes
// what the importer does not read and takes the Draco extensions out.
void sanitize(Json& doc, const Container& c, const ImportInput& in, uint64_t max_bytes, SideTable& side) {
  check_root(doc);
  uint64_t total = 0;
  if (auto buffers = doc.find("buffers"); buffers != doc.end())
    for (size_t i = 0; i < buffers->size(); ++i) sanitize_buffer((*buffers)[i], i, c, in, max_bytes, total, side);
  take_lights(doc, side);

  // Not geometry: never loaded, never able to refuse the file.
  for (const char* key : {"images", "textures", "samplers", "materials", "animations", "skins", "cameras"})
    doc.erase(key);

  if (auto meshes = doc.find("meshes"); meshes != doc.end()) {
    for (size_t m = 0; m < meshes->size(); ++m) {
      Json& mesh = (*meshes)[m];
      // Required by glTF 2.0 (5.23); a mesh without them would bake empty.
      if (!mesh.is_object()) refuse("mesh " + str(m) + " is not a JSON object");
      if (!mesh.contains("primitives") || !mesh["primitives"].is_array())
        refuse("mesh " + str(m) + ": \"primitives\" is missing or not an array");
      Json& prims = mesh["primitives"];
      for (size_t p = 0; p < prims.size(); ++p) take_primitive(prims[p], m, p, side);
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
  std::string error;  // a file changed since the checks: tinygltf reports the read as failed
  return read_whole_file(path, *out, limit, error);
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

// The fields the later stages read, out of tinygltf's model (buffers moved).
Model plain_model(tinygltf::Model& t) {
  Model m;
  m.buffers.resize(t.buffers.size());
  for (size_t i = 0; i < t.buffers.size(); ++i) m.buffers[i].data = std::move(t.buffers[i].data);
  for (const tinygltf::BufferView& v : t.bufferViews)
    m.bufferViews.push_back({v.buffer, v.byteOffset, v.byteLength, v.byteStride});
  for (const tinygltf::Accessor& a : t.accessors) {
    const auto& sp = a.sparse;
    const Sparse sparse{sp.count,
                        sp.isSparse,
                        {sp.indices.byteOffset, sp.indices.bufferView, sp.indices.componentType},
                        {sp.values.bufferView, sp.values.byteOffset}};
    m.accessors.push_back({a.bufferView, a.byteOffset, a.normalized, a.componentType, a.count, a.type, sparse});
  }
  for (const tinygltf::Mesh& mesh : t.meshes) {
    Mesh out;
    for (const tinygltf::Primitive& p : mesh.primitives) out.primitives.push_back({p.attributes, p.mode});
    m.meshes.push_back(std::move(out));
  }
  for (const tinygltf::Node& n : t.nodes) {
    NodeLight light;
    auto ext = n.extensions.find("KHR_lights_punctual");
    if (ext != n.extensions.end() && ext->second.IsObject()) {
      const tinygltf::Value& li = ext->second.Get("light");
      light = {true, li.IsInt(), li.IsInt() ? li.Get<int>() : 0};
    }
    m.nodes.push_back({n.mesh, n.children, n.rotation, n.scale, n.translation, n.matrix, light});
  }
  for (const tinygltf::Scene& s : t.scenes) m.scenes.push_back({s.nodes});
  m.defaultScene = t.defaultScene;
  return m;
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
  Model model;
  {
    tinygltf::Model parsed;
    load_model(c, doc, in, max_bytes, side.external, parsed);
    doc = Json();
    model = plain_model(parsed);
  }
  for (auto& [i, bytes] : side.data_uri)
    if (i < model.buffers.size()) model.buffers[i].data = std::move(bytes);

  build_scene(model, side, in, max_bytes, out);
}

}  // namespace
}  // namespace gltf

bool import_gltf(const ImportInput& in, Scene& out, std::string& error) {
  try {
    gltf::import(in, out);
    return true;
  } catch (const gltf::Refusal& r) {
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
  const nlohmann::json doc = nlohmann::json::parse(data, data + size, nullptr, false);
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return uris;
  for (const auto& b : doc["buffers"]) {
    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
    std::string uri = b["uri"].get<std::string>();
    if (uri.rfind("data:", 0) != 0) uris.push_back(std::move(uri));
  }
  return uris;
}

}  // namespace geom::detail
