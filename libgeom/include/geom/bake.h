// geom/bake.h: the bake, from an imported Scene to the sections of a baked
// container (format: geom/baked_reader.h; writer: geom/baked_writer.h).
//
//   Scene -> the pipeline of geom/pipeline.h (weld, topology, half-edge
//   summary, face planes, adjacency, ESM quads, shadow volume, one exact
//   volume per static light) -> sections
//
// Sections, in this order, each only when its option asks for it (a light
// volume needs the generic volume, which is then built but not emitted):
//   name          type              format  count            contents
//   positions     Positions         F32x3   welded vertices  welded positions (input coordinates and units)
//   indices       Indices           U32     3 x triangles    welded triangles, one per input triangle, in
//                                                            input order (collapsed ones kept: they draw nothing)
//   weld_remap    WeldRemap         U32     source vertices  Scene vertex -> welded vertex
//   caster_hull   CasterHull        F64x4   planes           (nx, ny, nz, d) in input coordinates, inside where
//                                                            n.p + d >= 0: the convex hull of `positions` (at
//                                                            most 16 supporting planes of it), as
//                                                            BakeOptions::caster_hull computes it (empty when
//                                                            they span no volume); only when that is set
//   face_planes   FacePlanes        F32x4   triangles        (nx, ny, nz, d) in input coordinates, n.p + d = 0:
//                                                            the face's stored plane (geom/face_planes.h, shared
//                                                            by coplanar neighbours), (0,0,0,0) if degenerate
//   topology      TopologyReport    Utf8    bytes            the JSON object of geom/report.h (`geombake info
//                                                            --json`), without timings
//   frame         Frame             F64x3   1                origin of the local frame of every buffer below:
//                                                            local = input - origin (lights: geom/extrude.h
//                                                            to_local_light)
//   esm_quads     EsmQuads          Record  quads            EsmQuad, 36 B (geom/esm_quads.h)
//   esm_planes    EsmPlanes         F32x4   planes           their plane table
//   volume_sides  VolumeSides       Record  sides            SvSide, 32 B (geom/shadow_volume.h)
//   volume_caps   VolumeCaps        Record  caps             SvCap, 40 B
//   volume_planes VolumePlanes      F32x4   planes           their plane table
//   adjacency     AdjacencyIndices  U32     6 x triangles    GL_TRIANGLES_ADJACENCY over `positions`
//   lights        Lights            F64x4   lights           (x, y, z, w) input coordinates, each light as
//                                                            geom/scene.h light_homogeneous gives it (w = 0:
//                                                            directional, (x, y, z) towards the light); scene
//                                                            lights first, then BakeOptions::lights
//   light_params  LightParams       Record  lights           LightRecord, 120 B (geom/baked_records.h): each
//                                                            light whole (type, position, direction, range,
//                                                            colour, intensity, cone angles), input coordinates
//   light_names   LightNames        Utf8    bytes            the lights' names, one after the other
//   light_sides   LightSides        Record  sides            per light, item = light index: its exact volume
//   light_caps    LightCaps         Record  caps             (geom/shadow_volume.h build_light_volume)
//   light_planes  LightPlanes       F32x4   planes
//   silhouette    SilhouetteReport  Utf8    bytes            JSON: frame, what each rule saved (ESM and volume
//                                                            stats), per light its name and record counts
// `frame` comes with any buffer in the local frame (ESM, volume or a light),
// `silhouette` with any silhouette buffer (those, or adjacency).
//
// Deterministic: the same scene and options give the same sections, byte for
// byte, on any run and any thread count (no timestamps, pointers or timings).
// Nothing throws: failures come back in BakeResult (geom/status.h: a code and
// "FILE: what is wrong").
#pragma once
#include <string>
#include <vector>

#include "geom/baked_writer.h"
#include "geom/import.h"
#include "geom/pipeline.h"
#include "geom/report.h"
#include "geom/scene.h"
#include "geom/span.h"

namespace geom {

// The convex hull of `points` as planes, 4 doubles each (nx, ny, nz, d), n
// unit and pointing inside, a point p inside where n.p + d >= 0; false when the points
// span no volume. geom::focus's focus_caster_hull (geom/focus.h, CGAL) is one:
// the bake takes it as a function so that geom::bake itself links no CGAL.
using CasterHullFunction = bool (*)(PositionSpan points, std::vector<double>& planes);

struct BakeOptions {
  // The pipeline's settings and the buffers asked for: each of face_planes,
  // esm, volume and adjacency asked for is emitted (the generic volume is
  // built for lights anyway, emitted only when asked). The bake always runs
  // the half-edge summary (its report) and releases each stage's buffers
  // early; it never times (the sections hold no timings).
  PipelineOptions pipeline;
  bool positions = true;
  bool indices = true;
  bool weld_remap = true;
  bool topology_report = true;
  bool scene_lights = true;  // an exact volume per KHR_lights_punctual light of the scene
  // The caster_hull section (the per-frame focus's precomputed hull), made by
  // this function when set; `geombake bake` sets geom::focus_caster_hull.
  CasterHullFunction caster_hull = nullptr;
  // More static lights, in input coordinates, after the scene's; each gets an
  // exact volume. One without a name is named "--light N" (N from 1).
  std::vector<Light> lights;
};

struct BakeResult : Status {  // ok, code, error: "FILE: what is wrong" when !ok (geom/status.h)
  std::vector<BakedSection> sections;
  Report report;             // the topology report (also the `topology` section's text)
  std::string silhouette;    // the `silhouette` section's JSON text ("" when no silhouette buffer)
  EsmStats esm;              // what the ESM rules saved (zero without ESM quads)
  ShadowVolumeStats volume;  // what the volume rules saved (zero without the generic volume)
};

// Memory kept across the bakes of a batch: asks the C library's allocator (glibc)
// to serve every allocation of every thread from its one main heap and never
// hand freed memory back, so each bake reuses the pages earlier stages and
// inputs touched instead of faulting in fresh zeroed ones (a bake touches about
// 300 bytes per triangle; fresh pages were a quarter of its time).
// Process-wide and for the process's life: for tools that bake, not for a
// library's host to have imposed on it; the resident size stays at the largest
// peak. No effect elsewhere (another C library, a sanitizer's allocator).
// Returns whether it took effect.
bool keep_memory_across_bakes();

// Bakes an imported scene; `name` is the input's name as the report shows it.
BakeResult bake_scene(const Scene& scene, const std::string& name, const BakeOptions& options = {});
// The same bake, the same sections, with a lower peak: the scene's
// triangles (positions, indices, sources) are freed as soon as the weld has
// read them. `scene` keeps its lights, warnings and counts.
BakeResult bake_scene(Scene&& scene, const std::string& name, const BakeOptions& options = {});

// The same bake with the lowest peak: each section is written to `out`
// (opened, not yet expected or finished: the caller finishes it) as soon as
// the stage that makes it has run, and its buffer freed, so the weld's
// remap, the ESM quads, the volume and the adjacency never all coexist. The
// file is byte for byte write_baked's of bake_scene's sections;
// result.sections describe them (size() is 0: their bytes are gone). A
// failed write is result.error ("NAME: cannot write the output: ..."), and
// out.error() says it.
BakeResult bake_scene(Scene&& scene, const std::string& name, const BakeOptions& options, BakedFileWriter& out);

// The source name a bake of `input` stores (the report's "file"), as
// `geombake bake` stores it for an input named on its command line: the base
// name ("dir/pig.off" -> "pig.off"), or for "dir/maps.pk3:maps/x.bsp" the
// archive's base name and the member ("maps.pk3:maps/x.bsp"). No path of the
// machine is stored, so the bytes do not depend on where the input lies.
std::string stored_name(const std::string& input);

// Imports `input`, bakes it and writes the container to `output` atomically:
// on any failure no output file is created (an existing one is left as it was).
// `result.sections` holds what was written. The stored name is `name`, or
// stored_name(input) when empty (the importer's warnings name it too), so the
// file is byte for byte `geombake bake INPUT -o OUTPUT`'s with the same options;
// errors name `input` as given.
BakeResult bake_file(const std::string& input, const std::string& output, const BakeOptions& options = {},
                     const ImportOptions& import_options = {}, const std::string& name = {});

}  // namespace geom
