// Private: the glTF 2.0 importer (.gltf with external or data-URI buffers, .glb),
// its stages and what they hand each other.
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
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "importers.h"

namespace geom::detail::gltf {

// The stages, each a file, and what they hand on (plain data: only
// import_gltf.cpp sees tinygltf and the JSON library):
//   import_gltf.cpp            the JSON passes, tinygltf's load, the Model below
//   import_gltf_container.cpp  GLB framing, JSON nesting depth, data URIs
//   import_gltf_accessors.cpp  bufferView and accessor ranges, reading accessors
//   import_gltf_draco.cpp      KHR_draco_mesh_compression
//   import_gltf_scene.cpp      primitives, the node hierarchy, lights, the output

// Thrown inside the importer's files only, caught by import_gltf.
struct Refusal : std::runtime_error {
  using std::runtime_error::runtime_error;
};
[[noreturn]] inline void refuse(const std::string& what) { throw Refusal(what); }

inline std::string str(uint64_t v) { return std::to_string(v); }

// glTF 2.0's numbers (tinygltf's TINYGLTF_* values, checked in import_gltf.cpp).
constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;  // componentType
constexpr int kVec2 = 2, kVec3 = 3, kVec4 = 4, kMat2 = 32 + 2, kMat3 = 32 + 3, kMat4 = 32 + 4,
              kScalar = 64 + 1;                    // accessor type
constexpr int kTriangles = 4, kTriangleStrip = 5;  // primitive mode
constexpr uint32_t kGlbMagic = 0x46546C67;         // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

// ---------------------------------------------------------------- container

struct Container {
  std::string json;
  const unsigned char* bin = nullptr;  // GLB BIN chunk, or null
  size_t bin_size = 0;
  bool glb = false;
};

// GLB layout: glTF 2.0 specification section 4.4 (12-byte header, then chunks
// of [length, type, data]; the first is JSON, an optional BIN follows).
Container split_container(const ImportInput& in, bool glb_extension, std::vector<std::string>& warnings);
// Nesting depth of a JSON text, counted outside strings.
int json_depth(const std::string& s);
// A buffer's data URI (RFC 2397): base64 or percent-encoded, media type
// application/octet-stream or application/gltf-buffer (glTF 2.0 section 3.6.1.1).
std::vector<unsigned char> decode_data_uri(const std::string& u, const std::string& name);

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
  std::set<std::string> external;                         // the external files checked here: all tinygltf may read
};

// ---------------------------------------------------------------- the model

// What tinygltf parsed, as the later stages read it: the fields they use,
// named and typed as tinygltf (and glTF's JSON) name them.
struct Buffer {
  std::vector<unsigned char> data;
};
struct BufferView {
  int buffer = -1;
  size_t byteOffset = 0, byteLength = 0, byteStride = 0;
};
struct SparseIndices {
  int byteOffset = 0, bufferView = -1, componentType = -1;
};
struct SparseValues {
  int bufferView = -1, byteOffset = 0;
};
struct Sparse {
  int count = 0;
  bool isSparse = false;
  SparseIndices indices;
  SparseValues values;
};
struct Accessor {
  int bufferView = -1;  // -1: none (zeros)
  size_t byteOffset = 0;
  bool normalized = false;
  int componentType = -1;
  size_t count = 0;
  int type = -1;
  Sparse sparse;
};
struct Primitive {
  std::map<std::string, int> attributes;
  int mode = kTriangles;
};
struct Mesh {
  std::vector<Primitive> primitives;
};
// A node's KHR_lights_punctual extension: present when it is an object; its
// "light" an integer (is_int) or not.
struct NodeLight {
  bool present = false, is_int = false;
  int index = 0;
};
struct Node {
  int mesh = -1;
  std::vector<int> children;
  std::vector<double> rotation, scale, translation, matrix;
  NodeLight light;
};
struct SceneRoots {
  std::vector<int> nodes;
};
struct Model {
  std::vector<Buffer> buffers;
  std::vector<BufferView> bufferViews;
  std::vector<Accessor> accessors;
  std::vector<Mesh> meshes;
  std::vector<Node> nodes;
  std::vector<SceneRoots> scenes;
  int defaultScene = -1;
};

// ------------------------------------------------------------ accessors

// "SCALAR", "VEC3", ... for messages.
const char* type_name(int type);
// The integer that a normalized component maps to 1.0.
double normalized_max(int type);
// Checks that `count` elements of `elem` bytes, `stride` apart, starting at
// `offset` in bufferView `view_index`, lie inside the bufferView and its buffer.
void check_range(const Model& model, const std::string& what, int view_index, uint64_t offset, uint64_t count,
                 uint64_t elem, uint64_t stride);
// Every bufferView inside its buffer, every accessor (sparse parts included)
// inside its bufferView, before anything is read.
void validate_ranges(const Model& model, const std::vector<char>& buffer_has_data);
// Reads accessor `index` (ranges already validated) into `out`, `ncomp` values
// per element, sparse substitutions applied. `budget` bounds what an accessor
// without a bufferView (zeros, no bytes behind them) may allocate. T: float or uint32_t.
template <class T>
void read_accessor(const Model& model, int index, const std::string& what, uint64_t budget, std::vector<T>& out);

// ------------------------------------------------------------ primitives

// One primitive's triangles in its own (mesh) space, only the used vertices.
struct Decoded {
  bool triangles = false;        // false: skipped (points, lines, no positions)
  std::vector<float> positions;  // xyz
  std::vector<uint32_t> indices;
};

// Unrolls `idx` (a list, strip or fan) into triangles, then keeps only the
// vertices they use, renumbered in first-use order.
void assemble(const std::vector<float>& positions, const std::vector<uint32_t>& idx, int mode, Decoded& d);
// Decodes a KHR_draco_mesh_compression primitive (import_gltf_draco.cpp).
void decode_draco(const Model& model, const Primitive& prim, const DracoRef& ref, const std::string& what, Decoded& d);

// The scene's triangles and lights into `out` (import_gltf_scene.cpp): every
// primitive of every mesh decoded, the node hierarchy walked, the output's size
// checked against the limits before it is allocated.
void build_scene(const Model& model, const SideTable& side, const ImportInput& in, uint64_t max_bytes, Scene& out);

}  // namespace geom::detail::gltf
