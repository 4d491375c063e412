// geom/baked_records.h: the fixed-size records of the baked container's Record
// sections, the companion of geom/baked_reader.h with the same property: C++17
// standard library only and no other geom header, so an engine copies the two
// files and reads every section of a `.gbake` without the library.
//
//   section                      record    layout and meaning
//   EsmQuads                     EsmQuad   geom/esm_quads.h "GPU layout"
//   VolumeSides, LightSides      SvSide    geom/shadow_volume.h "GPU layout"
//   VolumeCaps, LightCaps        SvCap     geom/shadow_volume.h "GPU layout"
//   LightParams                  LightRecord  below (a light as KHR_lights_punctual has it)
//
// The other sections are arrays of the Format the table names (U32, F32x3,
// F32x4, F64x3, F64x4, Utf8: geom/baked_reader.h). Plane indices in the
// records index the matching plane table (EsmPlanes, VolumePlanes, the
// LightPlanes of the same item); bit 31 is a flag, as the constants say.
// Little-endian, tightly packed, as the GPU reads them (one instance each).
#pragma once
#include <cstdint>

namespace geom {

#pragma pack(push, 1)
// One extended-shadow-map quad: the edge p0-p1 between the faces of planes
// plane_a (side A) and plane_b (side B), q its octahedral snorm16 extrusion.
struct EsmQuad {
  static constexpr uint32_t kFlip = 0x80000000u;  // in plane_a / plane_b: the side's test flipped
  float p0[3];
  float p1[3];
  uint32_t plane_a;
  uint32_t plane_b;
  int16_t q[2];
};
// One shadow-volume side: the edge p0-p1 between the faces of plane_a and
// plane_b (a single-faced edge: plane_b's index with kFlip for the far side).
struct SvSide {
  static constexpr uint32_t kFlip = 0x80000000u;    // in plane_b
  static constexpr uint32_t kSecond = 0x80000000u;  // in plane_a
  float p0[3];
  float p1[3];
  uint32_t plane_a;
  uint32_t plane_b;
};
// One cap: the triangle a, b, c of the face with plane `plane`.
struct SvCap {
  static constexpr uint32_t kDoubleSided = 0x80000000u;  // in plane
  float a[3];
  float b[3];
  float c[3];
  uint32_t plane;
};
#pragma pack(pop)
// One static light, whole, as KHR_lights_punctual declares it (glTF's names,
// geom/scene.h's Light), in input coordinates (the node's transform applied);
// record i of LightParams is light i of the Lights section (its (x, y, z, w)).
// Fields a type has none of are zero: a directional light's position and
// range, a point light's direction and cone angles. Naturally aligned with no
// padding (not packed: its doubles can be passed by pointer).
struct LightRecord {
  static constexpr uint32_t kDirectional = 0, kPoint = 1, kSpot = 2;  // `type`
  uint32_t type;
  uint32_t name_offset;     // the name: bytes [name_offset, name_offset + name_size) of
  uint32_t name_size;       // the LightNames section (UTF-8, not NUL-terminated)
  uint32_t reserved;        // zero
  double position[3];       // point, spot
  double direction[3];      // spot, directional: where the light travels (the node's -Z), as long as given
  double range;             // point, spot: the distance beyond which it gives no light; 0 = infinite
  double inner_cone_angle;  // spot: radians from the axis where the falloff starts
  double outer_cone_angle;  // spot: radians from the axis to the cone's edge
  double color[3];          // linear RGB
  double intensity;         // candela (point, spot) or lux (directional)
};
static_assert(sizeof(LightRecord) == 120, "LightRecord is the 120-byte light record");
static_assert(sizeof(EsmQuad) == 36, "EsmQuad is the 36-byte GPU record");
static_assert(sizeof(SvSide) == 32, "SvSide is the 32-byte GPU record");
static_assert(sizeof(SvCap) == 40, "SvCap is the 40-byte GPU record");

}  // namespace geom
