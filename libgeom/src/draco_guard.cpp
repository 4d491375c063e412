// A bound Debian's libdraco 1.5.5 lacks: the orientation count of its
// texture-coordinate prediction schemes.
//
// MeshPredictionSchemeTexCoords[Portable]Decoder::DecodePredictionData reads
// an orientation count from the stream (int32 in the portable scheme, u32 or a
// varint in the deprecated one), resizes a vector<bool> to it and then draws one
// bit per orientation from an rANS decoder that never runs out: a 393-byte
// stream claiming two billion orientations allocated 256 MB and looped for 29 s
// inside libdraco (found by fuzz/fuzz_draco; tests/fuzz_regressions/draco/
// texcoord_orientations.drc). A real stream stores at most one orientation per
// predicted value, and an attribute has at most one value per corner, so the
// count is refused over the number of corners: the bound Draco itself applies
// to the crease flags of its constrained multi-parallelogram scheme, and the one
// later Draco releases added to the deprecated scheme.
//
// How the bound reaches libdraco: the four instantiations libdraco uses (int32
// values, wrap transform, a corner table or an attribute corner table) are
// explicitly specialised here with Draco's own body plus that check. libdraco.so
// exports them as weak symbols and calls them through its vtables, whose
// relocations the dynamic linker binds to the first definition in lookup order,
// the program's (the program exports them: the linker puts into the dynamic
// symbol table every symbol a linked shared library also defines). Linked
// statically, libdraco.a's weak copies give way to these strong ones. Either way
// the decoder libdraco runs is this one; tests/test_draco_guard.cpp checks that
// the bomb is refused in milliseconds and that dlsym resolves the symbols here,
// so a libdraco built with -Bsymbolic (which would bypass this) fails the tests
// instead of silently hanging on hostile input.
//
// draco_guard_linked() is referenced by the glTF importer so that this object
// is always linked from the static libgeom.
#include "draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_data.h"
#include "draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_tex_coords_decoder.h"
#include "draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_tex_coords_portable_decoder.h"
#include "draco/compression/attributes/prediction_schemes/prediction_scheme_wrap_decoding_transform.h"
#include "draco/mesh/corner_table.h"
#include "draco/mesh/mesh_attribute_corner_table.h"
#include <array>
#include <atomic>
#include <string>
#include <utility>

#include "importers.h"

namespace geom::detail {
namespace {
std::array<std::atomic<uint64_t>, 4> guard_checks{};  // per instantiation, for the tests
thread_local std::string guard_refusal;                // why the last refusal, on this thread
}  // namespace

// True when the count fits; otherwise notes why for draco_guard_refusal().
bool draco_guard_check(int which, uint64_t orientations, const void* corner_table, uint64_t corners) {
  guard_checks[size_t(which)].fetch_add(1, std::memory_order_relaxed);
  if (corner_table && orientations <= corners) return true;
  guard_refusal = "its texture-coordinate prediction claims " + std::to_string(orientations) +
                  " orientations for " + std::to_string(corners) + " corners";
  return false;
}

std::string draco_guard_refusal() { return std::exchange(guard_refusal, std::string()); }
uint64_t draco_guard_checks(int which) { return guard_checks[size_t(which)].load(); }
}  // namespace geom::detail

namespace draco {

using GuardWrap = PredictionSchemeWrapDecodingTransform<int32_t, int32_t>;

// Draco's body (mesh_prediction_scheme_tex_coords_portable_decoder.h) plus the bound.
template <class MeshDataT>
bool fits(int which, uint64_t orientations, const MeshDataT& mesh_data) {
  const auto* table = mesh_data.corner_table();
  return geom::detail::draco_guard_check(which, orientations, table, table ? uint64_t(table->num_corners()) : 0);
}

template <class MeshDataT>
bool decode_portable_orientations(MeshPredictionSchemeTexCoordsPortablePredictor<int32_t, MeshDataT>& predictor,
                                  const MeshDataT& mesh_data, int which, DecoderBuffer* buffer) {
  int32_t num_orientations = 0;
  if (!buffer->Decode(&num_orientations) || num_orientations < 0) return false;
  if (!fits(which, uint64_t(num_orientations), mesh_data)) return false;
  predictor.ResizeOrientations(num_orientations);
  bool last_orientation = true;
  RAnsBitDecoder decoder;
  if (!decoder.StartDecoding(buffer)) return false;
  for (int i = 0; i < num_orientations; ++i) {
    if (!decoder.DecodeNextBit()) last_orientation = !last_orientation;
    predictor.set_orientation(i, last_orientation);
  }
  decoder.EndDecoding();
  return true;
}

// Draco's body (mesh_prediction_scheme_tex_coords_decoder.h) plus the bound.
template <class MeshDataT>
bool decode_deprecated_orientations(std::vector<bool>& orientations, const MeshDataT& mesh_data, int which,
                                    DecoderBuffer* buffer) {
  uint32_t num_orientations = 0;
  if (buffer->bitstream_version() < DRACO_BITSTREAM_VERSION(2, 2)) {
    if (!buffer->Decode(&num_orientations)) return false;
  } else if (!DecodeVarint(&num_orientations, buffer)) {
    return false;
  }
  if (num_orientations == 0) return false;
  if (!fits(which, num_orientations, mesh_data)) return false;
  orientations.resize(num_orientations);
  bool last_orientation = true;
  RAnsBitDecoder decoder;
  if (!decoder.StartDecoding(buffer)) return false;
  for (uint32_t i = 0; i < num_orientations; ++i) {
    if (!decoder.DecodeNextBit()) last_orientation = !last_orientation;
    orientations[i] = last_orientation;
  }
  decoder.EndDecoding();
  return true;
}

#define GEOM_DRACO_GUARD(MESH_DATA, WHICH)                                                                            \
  template <>                                                                                                   \
  __attribute__((visibility("default"))) bool                                                                   \
  MeshPredictionSchemeTexCoordsPortableDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(           \
      DecoderBuffer* buffer) {                                                                                  \
    return decode_portable_orientations(predictor_, this->mesh_data(), WHICH, buffer) &&                              \
           MeshPredictionSchemeDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(buffer);            \
  }                                                                                                             \
  template <>                                                                                                   \
  __attribute__((visibility("default"))) bool                                                                   \
  MeshPredictionSchemeTexCoordsDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(                   \
      DecoderBuffer* buffer) {                                                                                  \
    return decode_deprecated_orientations(orientations_, this->mesh_data(), WHICH + 1, buffer) &&                         \
           MeshPredictionSchemeDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(buffer);            \
  }

GEOM_DRACO_GUARD(MeshPredictionSchemeData<CornerTable>, 0)
GEOM_DRACO_GUARD(MeshPredictionSchemeData<MeshAttributeCornerTable>, 2)
#undef GEOM_DRACO_GUARD

}  // namespace draco
