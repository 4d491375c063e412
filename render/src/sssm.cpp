// sssm.cpp: shadow silhouette maps (Sen, Cammarano and Hanrahan 2003, the
// baseline seed 001 compares EDSM with): the depth map, then a geometry shader
// finds the silhouette edges of each caster's triangles with adjacency
// (geom/adjacency.h) and stores one point on the silhouette per cell of a
// second map offset by half a texel (shaders/sssm_edges.*); the lookup,
// shaders/lookup_sssm.frag, rebuilds the boundary from the 3 x 3 neighbourhood.
#include <cstdlib>

#include "state.h"

namespace render {

bool sssm_passes(Frame& f) {
  State& s = f.s;
  const int n = f.n;
  f.light_frame = light_frame(s, f.light);
  const glm::mat4 light_clip = f.light_frame.clip();
  if (!depth_map_pass(f, light_clip, 1.5f, false)) return false;
  ensure_edge_map(s, n, GL_RG32UI);  // the point (2 x snorm16), the edge depth's bits
  GLuint p = program(s.programs, {"sssm_edges.vert", "sssm_edges.geom", "sssm_edges.frag"}, f.error);
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  set(p, "u_map_size", float(n));
  set(p, "u_depth", 1);
  f.timer.begin("silhouette map");
  glBindFramebuffer(GL_FRAMEBUFFER, s.edge_map.fbo);
  glViewport(0, 0, n, n);
  const GLuint centre[4] = {0, 0, 0, 0};  // the default point: the cell's centre; no edge depth
  glClearNamedFramebufferuiv(s.edge_map.fbo, GL_COLOR, 0, centre);
  glClearDepth(1.0);
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
  f.lookup = "lookup_sssm.frag";
  return true;
}

// The shading: GEOM_SSSM_PAPER=1 in the environment draws the paper's lookup
// without the receiver test (lookup_sssm.frag), to measure the deviation.
bool sssm_shade(Frame& f, GLuint p) {
  const char* paper = std::getenv("GEOM_SSSM_PAPER");
  set(p, "u_sssm_paper", paper && paper[0] == '1' ? 1 : 0);
  f.timer.begin("shading");
  draw_scene(f.s);
  f.timer.end();
  return true;
}

}  // namespace render
