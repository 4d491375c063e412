// geom/pipeline.h: the one pipeline from a triangle soup to every buffer the
// library makes, with one options struct. `geombake bake` (geom/bake.h), the
// topology report (geom/report.h analyze), `geombake volume`, the renderer's
// in-process casters, the benchmarks and the tests all run it.
//
//   weld (geom/weld.h) -> topology (geom/topology.h) -> OpenMesh's half-edge
//   summary (geom/halfedge.h) -> face planes with coplanar groups
//   (geom/face_planes.h) -> adjacency (geom/adjacency.h) -> extended-shadow-map
//   quads (geom/esm_quads.h) -> generic shadow volume (geom/shadow_volume.h)
//   -> one exact volume per static light (build_light_volume)
//
// Each stage runs only when a buffer asked for needs it; each buffer's layout
// is documented in its own header. All buffers after the face planes share
// the local frame `planes.origin` (lights: geom/extrude.h to_local_light); the
// adjacency buffer indexes `weld.positions`.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "geom/esm_quads.h"
#include "geom/face_planes.h"
#include "geom/halfedge.h"
#include "geom/scene.h"
#include "geom/shadow_volume.h"
#include "geom/span.h"
#include "geom/status.h"
#include "geom/topology.h"
#include "geom/weld.h"

namespace geom {

struct PipelineOptions {
  // The settings the stages read.
  float weld_tolerance = 0;         // 0: weld exactly equal positions (geom/weld.h)
  double coplanar_degrees = 0.01;   // one threshold: the topology's coplanar edges and the face planes' groups
  double coplanar_distance = 1e-6;  // face planes: vertices this close to a group's plane (geom/face_planes.h)
  bool dihedral_angles = false;     // fill Edge::dihedral_degrees (no later stage reads an angle)
  EsmOptions esm_options;
  ShadowVolumeOptions volume_options;  // the generic volume and each light's
  // The buffers asked for (a light volume needs the generic volume and every
  // buffer past the topology the face planes: those then run, asked or not).
  bool halfedge = false;  // Pipeline::halfedge, OpenMesh's summary (the topology report's)
  bool face_planes = true;
  bool esm = true;
  bool volume = true;  // the generic shadow volume
  bool adjacency = true;
  // Free what no later stage reads as soon as it is read, so the peak holds
  // less: the topology's per-face tables after the adjacency, the face
  // normals after the ESM quads, the edge table after the volume.
  // Pipeline::topology then keeps its stats only, Pipeline::planes its
  // origin, planes and face_plane.
  bool release_early = false;
  bool timing = false;  // Pipeline::stages
};

struct StageTiming {
  std::string stage;  // "weld", "topology", "halfedge", "planes", "adjacency", "esm", "volume", "lights"
  double seconds = 0;
  uint64_t peak_rss_bytes = 0;  // the process's peak resident set after the stage (0 if unknown)
};

struct LightVolume {
  Light light;          // as given, in input coordinates
  ShadowVolume volume;  // its exact volume (build_light_volume)
};

// What a run built; a stage that did not run leaves its member empty.
struct Pipeline {
  WeldResult weld;
  Topology topology;
  HalfedgeSummary halfedge;
  FacePlanes planes;
  std::vector<uint32_t> adjacency;  // 6 per triangle (GL_TRIANGLES_ADJACENCY over weld.positions)
  EsmQuads esm;
  ShadowVolume volume;
  std::vector<LightVolume> lights;  // one per light given, in order
  std::vector<StageTiming> stages;  // with PipelineOptions::timing
};

// Runs the pipeline over `triangle_count` triangles (`indices`: 3 each, into
// `positions`), with an exact volume for each of `lights`. Deterministic: the
// same input and options give the same buffers on any run. `after_stage`, if
// given, is called after each stage that ran with its name (as StageTiming's)
// and the run so far, e.g. to free the input once "weld" has read it, or to
// write a buffer no later stage changes and free it (geom/bake.h streams the
// sections so): a buffer the callback empties must be one no later stage
// reads (the generic volume is read by "lights"). May throw std::bad_alloc.
// Preconditions (a caller bug, asserted by each stage with its name where
// NDEBUG is not defined): every index < positions.size(), at most
// kMaxTriangles triangles (geom/validate.h); untrusted data:
// run_pipeline_checked below.
Pipeline run_pipeline(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                      const std::vector<Light>& lights = {}, const PipelineOptions& options = {},
                      const std::function<void(const char* stage, Pipeline& run)>& after_stage = {});

// The pipeline for untrusted triangles: validate_triangles (geom/validate.h)
// first (`index_count` need not be a multiple of 3, indices need not be in
// range: those are errors here), each light checked (non-finite or all zero:
// NonFinite), then run_pipeline; an allocation that fails is OutOfMemory.
// Nothing is thrown; on failure `run` is empty and the Status says why, as
// "NAME: what is wrong".
struct PipelineResult : Status {
  Pipeline run;
};
PipelineResult run_pipeline_checked(const std::string& name, PositionSpan positions, const uint32_t* indices,
                                    size_t index_count, const std::vector<Light>& lights = {},
                                    const PipelineOptions& options = {});

// The report of what each rule saved, one line per rule, for people.
std::string silhouette_report(const Pipeline& run);

}  // namespace geom
