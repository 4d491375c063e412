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
  GLuint p = edge_program(f, light_clip, kBias, GL_RGBA32F, {"esm_quad.vert", "esm_edges.frag"});
  if (!p) return false;
  const float texels = 2.5f;  // quad reach beyond the edge, in texels
  set(p, "u_extrude_scale", 2.0f * texels / (float(f.n) * projection_scale(light_clip)));
  set(p, "u_planes", 2);
  begin_edge_pass(f, p, "extended map quads", EdgeTarget::ExtendedMax);
  for (const Caster& c : f.s.casters) {
    set(p, "u_light_view_proj", at(glm::dmat4(light_clip), c.origin));
    set(p, "u_light", local_light(c, glm::dvec4(f.light.position)));
    glBindTextureUnit(2, c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
  end_edge_pass(f, EdgeTarget::ExtendedMax);
  return true;
}

}  // namespace

bool esm_passes(Frame& f) {
  if (!silhouette_faces(f, esm_face, GL_RGBA32F)) return false;
  f.lookup = "lookup_esm.frag";
  return true;
}

}  // namespace render
