// glTF importer, KHR_draco_mesh_compression: decoded here with Draco's
// decoder, not inside tinygltf (gltf.h), after the stream's counts are checked
// against its size.
#include <string>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/compression/point_cloud/point_cloud_decoder.h"
#include "draco/core/varint_decoding.h"
#include "draco/metadata/geometry_metadata.h"
#include "draco/metadata/metadata_decoder.h"
#include "gltf.h"

namespace geom::detail::gltf {

namespace {

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

}  // namespace

void decode_draco(const Model& model, const Primitive& prim, const DracoRef& ref, const std::string& what, Decoded& d) {
  check_range(model, what + " (KHR_draco_mesh_compression)", ref.buffer_view, 0, 1, 0, 0);
  const BufferView& view = model.bufferViews[size_t(ref.buffer_view)];
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
    const Accessor& acc = model.accessors[size_t(pos->second)];
    if (acc.normalized && !att->normalized() && acc.componentType != kFloat)
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
  assemble(positions, idx, kTriangles, d);
}

}  // namespace geom::detail::gltf
