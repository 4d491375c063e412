// The viewer's file path as a fuzz target's body (fuzz_viewer_file.cpp) and
// the tests' replay (tests/test_fuzz_viewer_file.cpp): the bytes of a baked
// file through geom::baked::Reader::open and then validate_floats, as geomview
// reads its input (viewer/options.cpp) before anything reaches GL or Embree.
// Laws, each checked here independently of the reader:
//   refused by open             -> a one-line error, no sections;
//   refused by validate_floats  -> a one-line error naming "section I 'NAME'";
//   accepted by both            -> every float of every f32/f64 section and of
//       the records' points is finite; positions, frames, record points and
//       point lights within kMaxCoordinate; every light's w is 0 or 1.
// Standard library and the reader only: it builds without libgeom.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "geom/baked_reader.h"

namespace geom_fuzz {

namespace viewer_detail {
// "" when every float of `s` keeps the accepted file's law, else what breaks.
inline std::string section_law(const geom::baked::Section& s) {
  using geom::baked::Format;
  using geom::baked::SectionType;
  uint32_t n = 0, width = 4;
  if (s.format == Format::F32 || s.format == Format::F32x2 || s.format == Format::F32x3 || s.format == Format::F32x4)
    n = s.stride / 4;
  if (s.format == Format::F64x3 || s.format == Format::F64x4) n = s.stride / 8, width = 8;
  const bool caps = s.type == SectionType::VolumeCaps || s.type == SectionType::LightCaps;
  const bool sides =
      s.type == SectionType::EsmQuads || s.type == SectionType::VolumeSides || s.type == SectionType::LightSides;
  if (s.format == Format::Record && (caps || sides)) n = caps ? 9 : 6;
  if (uint64_t(n) * width > s.stride) n = 0;
  const bool points = s.type == SectionType::Positions || s.type == SectionType::Frame ||
                      (s.format == Format::Record && (caps || sides));
  const bool lights = s.type == SectionType::Lights && s.format == Format::F64x4;
  for (uint64_t e = 0; e < s.count; ++e) {
    double v[16];
    for (uint32_t k = 0; k < n; ++k) {
      v[k] = geom::baked::detail::load_float(s.data + e * s.stride + k * width, width == 8);
      if (!std::isfinite(v[k])) return "a non-finite float accepted";
      if (points && std::fabs(v[k]) > geom::baked::kMaxCoordinate) return "a coordinate over the limit accepted";
    }
    if (lights && v[3] != 0 && v[3] != 1) return "a light with w neither 0 nor 1 accepted";
    if (lights && v[3] == 1)
      for (int k = 0; k < 3; ++k)
        if (std::fabs(v[k]) > geom::baked::kMaxCoordinate) return "a point light over the limit accepted";
  }
  return "";
}
}  // namespace viewer_detail

// "" when every law holds, else the law broken.
inline std::string check_viewer_file(const unsigned char* data, size_t size) {
  geom::baked::Reader reader;
  if (!reader.open(data, size)) {
    if (reader.error().empty() || reader.error().find('\n') != std::string::npos) return "refusal not one line";
    return reader.sections().empty() ? "" : "sections after a refusal";
  }
  std::string error;
  if (!geom::baked::validate_floats(reader, error)) {
    if (error.rfind("section ", 0) != 0 || error.find('\n') != std::string::npos)
      return "float refusal not one line naming the section: " + error;
    return "";
  }
  for (const geom::baked::Section& s : reader.sections()) {
    const std::string broken = viewer_detail::section_law(s);
    if (!broken.empty()) return broken + " in section '" + std::string(s.name) + "'";
  }
  return "";
}

}  // namespace geom_fuzz
