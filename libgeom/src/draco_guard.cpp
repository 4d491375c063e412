// A bound Debian's libdraco 1.5.5 lacks: the orientation count of its
// texture-coordinate prediction schemes.
//
// MeshPredictionSchemeTexCoords[Portable]Decoder::DecodePredictionData reads
// an orientation count from the stream (int32 in the portable scheme, u32 or a
// varint in the deprecated one), resizes a vector<bool> to it and then draws one
// bit per orientation from an rANS decoder that never runs out: a 393-byte
// stream claiming 1.3 billion orientations allocated 166 MB and looped for 29 s
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
// the decoder libdraco runs is this one. libgeom/tests/test_draco_guard.cpp checks that
// dlsym resolves the symbols here, that the replacements decode real streams
// right and that absurd counts are refused within a second, so a libdraco that
// binds its own copies (built with -Bsymbolic, say) fails the tests instead of
// hanging on hostile input.
//
// The glTF importer calls draco_guard_refusal() around every Draco decode, which
// also makes the linker take this object from the static libgeom.
#include <array>
#include <atomic>
#include <string>
#include <utility>

#include "draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_data.h"
#include "draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_tex_coords_decoder.h"
#include "draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_tex_coords_portable_decoder.h"
#include "draco/compression/attributes/prediction_schemes/prediction_scheme_wrap_decoding_transform.h"
#include "draco/mesh/corner_table.h"
#include "draco/mesh/mesh_attribute_corner_table.h"
#include "importers.h"

namespace geom::detail {
namespace {
std::array<std::atomic<uint64_t>, 4> guard_checks{};  // per instantiation, for the tests
thread_local std::string guard_refusal;               // why the last refusal, on this thread

// True when the count fits; otherwise notes why for draco_guard_refusal().
bool draco_guard_check(int which, uint64_t orientations, uint64_t corners) {
  guard_checks[size_t(which)].fetch_add(1, std::memory_order_relaxed);
  if (orientations <= corners) return true;
  guard_refusal = "its texture-coordinate prediction claims " + std::to_string(orientations) + " orientations for " +
                  std::to_string(corners) + " corners";
  return false;
}
}  // namespace

std::string draco_guard_refusal() { return std::exchange(guard_refusal, std::string()); }
uint64_t draco_guard_checks(int which) { return guard_checks[size_t(which)].load(); }
}  // namespace geom::detail

namespace draco {
namespace {

using GuardWrap = PredictionSchemeWrapDecodingTransform<int32_t, int32_t>;

// The loop both of Draco's bodies share (mesh_prediction_scheme_tex_coords_
// [portable_]decoder.h): delta-coded orientation bits from an rANS bit decoder,
// after the bound. `which` names the instantiation for draco_guard_checks().
template <class MeshDataT, class Resize, class Set>
bool decode_orientations(uint64_t count, const MeshDataT& mesh_data, int which, DecoderBuffer* buffer, Resize resize,
                         Set set) {
  const auto* table = mesh_data.corner_table();
  if (!geom::detail::draco_guard_check(which, count, table ? uint64_t(table->num_corners()) : 0)) return false;
  resize(count);
  bool last_orientation = true;
  RAnsBitDecoder decoder;
  if (!decoder.StartDecoding(buffer)) return false;
  for (uint64_t i = 0; i < count; ++i) {
    if (!decoder.DecodeNextBit()) last_orientation = !last_orientation;
    set(i, last_orientation);
  }
  decoder.EndDecoding();
  return true;
}

// The portable scheme's count: an int32, negative refused.
template <class MeshDataT>
bool decode_portable_orientations(MeshPredictionSchemeTexCoordsPortablePredictor<int32_t, MeshDataT>& predictor,
                                  const MeshDataT& mesh_data, int which, DecoderBuffer* buffer) {
  int32_t count = 0;
  if (!buffer->Decode(&count) || count < 0) return false;
  return decode_orientations(
      uint64_t(count), mesh_data, which, buffer, [&](uint64_t n) { predictor.ResizeOrientations(int(n)); },
      [&](uint64_t i, bool v) { predictor.set_orientation(int(i), v); });
}

// The deprecated scheme's count: a u32 before 2.2, a varint after; 0 refused.
template <class MeshDataT>
bool decode_deprecated_orientations(std::vector<bool>& orientations, const MeshDataT& mesh_data, int which,
                                    DecoderBuffer* buffer) {
  uint32_t count = 0;
  if (buffer->bitstream_version() < DRACO_BITSTREAM_VERSION(2, 2) ? !buffer->Decode(&count)
                                                                  : !DecodeVarint(&count, buffer))
    return false;
  if (count == 0) return false;
  return decode_orientations(
      count, mesh_data, which, buffer, [&](uint64_t n) { orientations.resize(n); },
      [&](uint64_t i, bool v) { orientations[i] = v; });
}

}  // namespace

#define GEOM_DRACO_GUARD(MESH_DATA, WHICH)                                                                           \
  template <>                                                                                                        \
  __attribute__((visibility("default"))) bool                                                                        \
  MeshPredictionSchemeTexCoordsPortableDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(                 \
      DecoderBuffer* buffer) {                                                                                       \
    return decode_portable_orientations(predictor_, this->mesh_data(), WHICH, buffer) &&                             \
           MeshPredictionSchemeDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(buffer);                 \
  }                                                                                                                  \
  template <>                                                                                                        \
  __attribute__((visibility("default"))) bool                                                                        \
  MeshPredictionSchemeTexCoordsDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(DecoderBuffer* buffer) { \
    return decode_deprecated_orientations(orientations_, this->mesh_data(), WHICH + 1, buffer) &&                    \
           MeshPredictionSchemeDecoder<int32_t, GuardWrap, MESH_DATA>::DecodePredictionData(buffer);                 \
  }

GEOM_DRACO_GUARD(MeshPredictionSchemeData<CornerTable>, 0)
GEOM_DRACO_GUARD(MeshPredictionSchemeData<MeshAttributeCornerTable>, 2)
#undef GEOM_DRACO_GUARD

}  // namespace draco
