// esm_soft.cpp: esm-soft, soft shadows of a disc light from the extended
// shadow map's edge distance (seed 000, Sect. 3.2: the lookup's "one dp3"
// attenuation, here the disc's kernel of soft_light.frag). Per face of esm's
// light frames (silhouette_faces.cpp: the fitted frustum, or six cube faces
// for a point light among its receivers): the depth map, then ESM's
// silhouette quads (geom/esm_quads.h, esm_quad.vert) extruded as far as the
// face's widest penumbra, keeping the signed distance in texels
// (shaders/esm_soft_edges.frag); the lookup is shaders/lookup_esm_soft.frag,
// whose penumbra estimate reads the face's matrix (soft_light.frag).
#include "edge_pass.h"

namespace render {
namespace {

bool esm_soft_face(Frame& f, const glm::mat4& light_clip) {
  // Bias factor 2, as esm's: the lookup compares a 2 x 2 footprint. The quad
  // reaches the widest penumbra beyond its edge (its lit side; the occluder's
  // side, half as far, does not cover the umbra: esm_quad.vert's q). Twice as
  // far was measured: up to 2.2x slower and 7-16% more light-fraction error.
  const float texels = soft_reach(f, projection_scale(light_clip));
  return esm_quad_pass(f, light_clip, 2.0f, texels, "esm_soft_edges.frag");
}

}  // namespace

bool esm_soft_passes(Frame& f) {
  if (!silhouette_faces(f, esm_soft_face, GL_RGBA32F)) return false;
  f.lookup = "lookup_esm_soft.frag";
  f.lookup_extra = "soft_light.frag";
  return true;
}

}  // namespace render
