// geom/silhouette.h: every silhouette buffer of one mesh, in one call.
//
// weld (geom/weld.h) -> topology (geom/topology.h) -> face planes with coplanar
// groups (geom/face_planes.h) -> extended-shadow-map quads (geom/esm_quads.h),
// the generic shadow volume (geom/shadow_volume.h), the adjacency index buffer
// (geom/adjacency.h), and one exact shadow volume per static light. Each
// buffer's layout is documented in its own header; all share the local frame
// `planes.origin`. The adjacency buffer indexes `weld.positions`.
//
// Lights: the scene's KHR_lights_punctual lights (point and spot as points,
// directional as directions) and any given as (x, y, z, w) in input
// coordinates, w = 1 point, w = 0 directional towards (x, y, z).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geom/esm_quads.h"
#include "geom/face_planes.h"
#include "geom/scene.h"
#include "geom/shadow_volume.h"
#include "geom/span.h"
#include "geom/topology.h"
#include "geom/weld.h"

namespace geom {

struct SilhouetteOptions {
  float weld_tolerance = 0;  // geom/weld.h
  // geom/topology.h; no silhouette buffer reads a dihedral angle, so the bake
  // leaves them out (dihedral_angles = true fills SilhouetteBuffers::topology's).
  TopologyOptions topology = {0.01, false};
  FacePlaneOptions planes;
  EsmOptions esm;
  ShadowVolumeOptions volume;
  bool esm_quads = true, shadow_volume = true, adjacency = true;
};

struct LightVolume {
  double light[4] = {0, 0, 0, 0};  // input coordinates
  std::string name;                // the glTF light's name, or "--light N"
  ShadowVolume volume;             // exact for this light (build_light_volume)
};

struct SilhouetteBuffers {
  WeldResult weld;
  Topology topology;
  FacePlanes planes;
  EsmQuads esm;
  ShadowVolume volume;
  std::vector<uint32_t> adjacency;  // 6 per triangle
  std::vector<LightVolume> lights;
};

// Lights of a scene as (x, y, z, w) in input coordinates (directional: the
// opposite of the direction the light travels). Spot lights count as points.
std::vector<LightVolume> scene_lights(const Scene& scene);

// `lights`: the lights whose exact volumes to emit (their `volume` is filled in).
SilhouetteBuffers bake_silhouettes(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                   std::vector<LightVolume> lights, const SilhouetteOptions& options = {});

// The report of what each rule saved, one line per rule, for people.
std::string silhouette_report(const SilhouetteBuffers& buffers);

}  // namespace geom
