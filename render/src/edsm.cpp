// edsm.cpp: the edge distance shadow map (seed 001, Sect. 4.2.1): the depth
// map, then a geometry shader finds the silhouette edges of each caster's
// triangles with adjacency (geom/adjacency.h) and writes the distance to the
// nearest one (shaders/edsm_edges.*); the lookup is shaders/lookup_edsm.frag.
#include "state.h"

namespace render {

namespace {

// One face: the depth map, then the edge distance map beside it.
bool edsm_face(Frame& f, const glm::mat4& light_clip) {
  State& s = f.s;
  const int n = f.n;
  // Bias factor 2: the lookup compares a 2 x 2 footprint (taps one texel away).
  if (!depth_map_pass(f, light_clip, 2.0f, false)) return false;
  ensure_edge_map(s, n, GL_RG32F);
  GLuint p = program(s.programs, {"edsm_edges.vert", "edsm_edges.geom", "edsm_edges.frag"}, f.error);
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  set(p, "u_map_size", float(n));
  set(p, "u_half_width", 2.0f);
  set(p, "u_depth", 1);
  f.timer.begin("edge distance map");
  glBindFramebuffer(GL_FRAMEBUFFER, s.edge_map.fbo);
  glViewport(0, 0, n, n);
  const float none[4] = {3.0e38f, 0, 0, 0};
  glClearNamedFramebufferfv(s.edge_map.fbo, GL_COLOR, 0, none);
  glClear(GL_DEPTH_BUFFER_BIT);
  glBindTextureUnit(1, s.shadow_map.depth);
  glBindSampler(1, depth_sampler(s));
  glUseProgram(p);
  for (const Caster& c : s.casters) {
    glBindVertexArray(c.adjacency_vao);
    glDrawElements(GL_TRIANGLES_ADJACENCY, c.adjacency_count, GL_UNSIGNED_INT, nullptr);
  }
  glBindSampler(1, 0);
  f.timer.end();
  return true;
}

}  // namespace

bool edsm_passes(Frame& f) {
  if (!silhouette_faces(f, edsm_face, GL_RG32F)) return false;
  f.lookup = "lookup_edsm.frag";
  return true;
}

}  // namespace render
