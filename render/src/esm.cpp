// esm.cpp: the extended shadow map (seed 000, Sect. 4.1-4.2): the depth map,
// then the caster's silhouette quads (geom/esm_quads.h, extruded in
// shaders/esm_quad.vert) write edge distance and edge depth beside it with MAX
// blending (shaders/esm_edges.frag); the lookup is shaders/lookup_esm.frag.
#include <cmath>

#include "edge_pass.h"

namespace render {
namespace {
// Depth bias factor: the lookup compares a 2 x 2 footprint, taps up to one
// texel from the sample (shadow_map.cpp: k + 1 texel slopes for k texels).
constexpr float kBias = 2.0f;

// One face: the depth map, then the silhouette quads beside it.
bool esm_face(Frame& f, const glm::mat4& light_clip) {
  return esm_quad_pass(f, light_clip, kBias, 2.5f, "esm_edges.frag");  // quad reach beyond the edge: 2.5 texels
}

}  // namespace

bool esm_passes(Frame& f) {
  if (!silhouette_faces(f, esm_face, GL_RGBA32F)) return false;
  f.lookup = "lookup_esm.frag";
  return true;
}

}  // namespace render
