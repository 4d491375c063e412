// esm.cpp: the extended shadow map (seed 000, Sect. 4.1-4.2): the depth map,
// then the caster's silhouette quads (geom/esm_quads.h, extruded in
// shaders/esm_quad.vert) write edge distance and edge depth beside it with MAX
// blending (shaders/esm_edges.frag); the lookup is shaders/lookup_esm.frag.
#include <cmath>

#include "state.h"

namespace render {
namespace {
// Depth bias factor: the lookup compares a 2 x 2 footprint, taps up to one
// texel from the sample (shadow_map.cpp: k + 1 texel slopes for k texels).
constexpr float kBias = 2.0f;

// One face: the depth map, then the silhouette quads beside it.
bool esm_face(Frame& f, const glm::mat4& light_clip) {
  State& s = f.s;
  const int n = f.n;
  if (!depth_map_pass(f, light_clip, kBias, false)) return false;
  ensure_edge_map(s, n, GL_RGBA32F);
  GLuint p = program(s.programs, {"esm_quad.vert", "esm_edges.frag"}, f.error);
  if (!p) return false;
  const float texels = 2.5f;  // quad reach beyond the edge, in texels
  set(p, "u_extrude_scale", 2.0f * texels / (float(n) * projection_scale(light_clip)));
  set(p, "u_planes", 2);
  set(p, "u_depth", 1);
  set(p, "u_map_size", float(n));
  f.timer.begin("extended map quads");
  glBindFramebuffer(GL_FRAMEBUFFER, s.edge_map.fbo);
  glViewport(0, 0, n, n);
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(s.edge_map.fbo, GL_COLOR, 0, zero);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_MAX);  // 000 Sect. 4.1: MAX of the inverted distance and of the edge depth
  glBindTextureUnit(1, s.shadow_map.depth);
  glBindSampler(1, depth_sampler(s));
  glUseProgram(p);
  for (const Caster& c : s.casters) {
    set(p, "u_light_view_proj", at(glm::dmat4(light_clip), c.origin));
    set(p, "u_light", local_light(c, glm::dvec4(f.light.position)));
    glBindTextureUnit(2, c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glBindSampler(1, 0);
  f.timer.end();
  return true;
}

}  // namespace

bool esm_passes(Frame& f) {
  if (!silhouette_faces(f, esm_face, GL_RGBA32F)) return false;
  f.lookup = "lookup_esm.frag";
  return true;
}

}  // namespace render
