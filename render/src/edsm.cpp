// edsm.cpp: the edge distance shadow map (seed 001, Sect. 4.2.1): the depth
// map, then a geometry shader finds the silhouette edges of each caster's
// triangles with adjacency (geom/adjacency.h) and writes the distance to the
// nearest one (shaders/edsm_edges.*); the lookup is shaders/lookup_edsm.frag.
#include "state.h"

namespace render {

bool edsm_passes(Frame& f) {
  State& s = f.s;
  const int n = f.n;
  f.light_frame = light_frame(s, f.light);
  const glm::mat4 light_clip = f.light_frame.clip();
  if (!depth_map_pass(f, light_clip, 1.5f, false)) return false;
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
  finish_map(f);
  f.second_texture = s.edge_map.color;
  f.lookup = "lookup_edsm.frag";
  return true;
}

}  // namespace render
