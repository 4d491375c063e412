// esm_soft.cpp: esm-soft, soft shadows of a disc light from the extended
// shadow map's edge distance: this project's own extension of 000. The paper
// has no penumbra: its Sect. 3.2 lookup leaves the v coordinate of its
// transfer texture for "arbitrary attenuation" (one dp3; its figures use
// per-pixel linear attenuation, the light's falloff), not a shadow's softness. Here the bilinear edge distance is
// instead read in units of an estimated penumbra and mapped through the disc's
// kernel of soft_light.frag. Measured against the area-light reference
// (geombench, 640x480, light-fraction error at 512 / 1024 / 2048, pcf-soft in
// brackets): pipes 0.0113 / 0.0097 / 0.0085 (0.0453 / 0.0266 / 0.0245),
// default 0.0079 / 0.0072 / 0.0065 (0.0097 / 0.0057 / 0.0061), scan 0.0068 /
// 0.0058 / 0.0052 (0.0300 / 0.0230 / 0.0126): better on 7 of 9, so kept. Per face of esm's
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
