// inspection.cpp: the overlay drawn over the shaded frame (colour output
// only): the topology problems of the mesh (boundary, non-manifold and
// inconsistent edges, degenerate faces), the silhouette quads of the current
// light, and the focus body H of the focused shadow map (geom/focus.h).
#include <algorithm>
#include <cmath>

#include "state.h"

namespace render {

bool inspection_pass(Frame& f, geom::FocusMethod method) {
  State& s = f.s;
  const glm::dmat4& view_proj = f.view_proj;
  GLuint lines = program(s.programs, {"inspect.vert", "inspect.frag"}, f.error);
  GLuint quads = lines ? program(s.programs, {"esm_quad.vert", "inspect.frag"}, f.error) : 0;
  if (!quads) return false;
  f.timer.begin("inspection");
  glDisable(GL_STENCIL_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_POLYGON_OFFSET_LINE);
  glPolygonOffset(-1.0f, -4.0f);
  const glm::vec4 colours[4] = {
      {1.0f, 0.85f, 0.1f, 1}, {1.0f, 0.1f, 0.1f, 1}, {0.9f, 0.2f, 1.0f, 1}, {0.1f, 0.9f, 1.0f, 1}};
  glUseProgram(lines);
  set(lines, "u_matrix", glm::mat4(view_proj));
  for (const Caster& c : s.casters)
    for (int k = 0; k < 4; ++k) {
      set(lines, "u_colour", colours[k]);
      glBindVertexArray(c.lines_vao);
      glDrawArrays(GL_LINES, c.line_first[k], c.line_count[k]);
    }
  // Silhouette quads of the current light, extruded in the camera's clip space
  // (about 3 pixels wide); only the quads that open for this light have area.
  glUseProgram(quads);
  set(quads, "u_colour", glm::vec4(1.0f, 0.45f, 0.0f, 1));
  set(quads, "u_planes", 2);
  set(quads, "u_extrude_scale", 2.0f * 3.0f / (float(std::max(f.w, f.h)) * std::fabs(float(view_proj[1][1])) + 1e-30f));
  for (const Caster& c : s.casters) {
    set(quads, "u_light_view_proj", at(view_proj, c.origin));
    set(quads, "u_light", local_light(c, glm::dvec4(f.light.position)));
    glBindTextureUnit(2, c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
  // The focus body H of the focused shadow map, as a wireframe drawn over everything.
  const geom::FocusResult r = focus(s, f.view, float(f.w) / float(f.h), f.light, method, true);
  std::vector<float> edges;
  size_t first = 0;
  for (uint32_t n : r.face_sizes) {
    for (uint32_t k = 0; k < n && first + n <= r.face_indices.size(); ++k)
      for (uint32_t v : {r.face_indices[first + k], r.face_indices[first + (k + 1) % n]})
        if (size_t(v) * 3 + 2 < r.vertices.size())
          edges.insert(edges.end(), {float(r.vertices[3 * size_t(v)]), float(r.vertices[3 * size_t(v) + 1]),
                                     float(r.vertices[3 * size_t(v) + 2])});
    first += n;
  }
  Buffer buffer;
  VertexArray vao;
  upload(buffer, edges.data(), edges.size() * sizeof(float), "focus body H edges");
  glCreateVertexArrays(1, &vao.id);
  glVertexArrayVertexBuffer(vao, 0, buffer, 0, 3 * sizeof(float));
  attribute(vao, 0, 3, GL_FLOAT, 0, false);
  label(GL_VERTEX_ARRAY, vao, "focus body H");
  glDisable(GL_DEPTH_TEST);
  glUseProgram(lines);
  set(lines, "u_colour", glm::vec4(0.3f, 1.0f, 0.3f, 1));
  glBindVertexArray(vao);
  glDrawArrays(GL_LINES, 0, GLsizei(edges.size() / 3));
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_POLYGON_OFFSET_LINE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  f.timer.end();
  return true;
}

}  // namespace render
