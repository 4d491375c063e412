// geom/bake.h: the bake pipeline, from an imported Scene to the sections of a
// baked container (format: geom/baked_reader.h; writer: geom/baked_writer.h).
//
//   Scene -> weld (geom/weld.h) -> topology (geom/topology.h) -> buffers -> sections
//
// Sections, in this order, each one only when its option is set:
//   name        type            format  count               contents
//   positions   Positions       F32x3   welded vertices     the welded positions (world space, the file's units)
//   indices     Indices         U32     3 x triangles       the welded triangles, one per input triangle, in input
//                                                           order (collapsed ones included: they draw nothing)
//   weld_remap  WeldRemap       U32     source vertices     Scene vertex -> welded vertex
//   face_planes FacePlanes      F32x4   triangles           (nx, ny, nz, d): unit normal by the right-hand rule
//                                                           of the welded triangle, n.p + d = 0 on its plane;
//                                                           (0, 0, 0, 0) for a collapsed or zero-area triangle
//   topology    TopologyReport  Utf8    bytes               the JSON object of geom/report.h (`geombake info
//                                                           --json`), without timings
//
// Deterministic: the same scene and options give the same sections, byte for
// byte, on any run and any thread count (no timestamps, pointers or timings).
// Nothing throws: failures come back in BakeResult::error.
#pragma once
#include <string>
#include <vector>

#include "geom/baked_writer.h"
#include "geom/import.h"
#include "geom/report.h"
#include "geom/scene.h"
#include "geom/topology.h"

namespace geom {

struct BakeOptions {
  float weld_tolerance = 0;  // 0: weld exactly equal positions (geom/weld.h)
  TopologyOptions topology;
  bool positions = true;
  bool indices = true;
  bool weld_remap = true;
  bool face_planes = true;
  bool topology_report = true;
};

struct BakeResult {
  bool ok = false;
  std::string error;  // "FILE: what is wrong" when !ok
  std::vector<BakedSection> sections;
  Report report;  // the topology report (also the `topology` section's text)
};

// Bakes an imported scene; `name` is the input's name as the report shows it.
BakeResult bake_scene(const Scene& scene, const std::string& name, const BakeOptions& options = {});

// Imports `input`, bakes it and writes the container to `output` atomically:
// on any failure no output file is created (an existing one is left as it was).
// `result.sections` holds what was written.
BakeResult bake_file(const std::string& input, const std::string& output, const BakeOptions& options = {},
                     const ImportOptions& import_options = {});

}  // namespace geom
