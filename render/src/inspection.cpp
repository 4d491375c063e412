// inspection.cpp: the overlay drawn over the shaded frame (colour output
// only): the topology problems of the mesh (boundary, non-manifold and
// inconsistent edges, degenerate faces), the silhouette quads of the current
// light, and the focus body H of the focused shadow maps (psm, lispsm,
// uniform: geom/focus.h).
//
// Order, so that no topology problem hides: the silhouette quads (orange,
// about 3 pixels, no depth write), the focus body (green, 2 pixels, over
// everything), then the problems as screen-space quads (shaders/inspect.geom)
// from the least to the most serious: degenerate faces' edges (cyan),
// inconsistent (magenta), boundary (yellow), non-manifold (red, widest). The
// problems are depth-tested against the scene with their depth pulled towards
// the eye (inspect.geom), so an edge shows on the faces it bounds and hides
// behind a wall in front of it.
#include <algorithm>
#include <cmath>

#include "geom/topology.h"
#include "geom/weld.h"
#include "state.h"

namespace render {
namespace {

const glm::vec3 kColours[6] = {
    {1.0f, 0.85f, 0.1f},  // boundary
    {1.0f, 0.1f, 0.1f},   // non-manifold
    {0.9f, 0.2f, 1.0f},   // inconsistent
    {0.1f, 0.9f, 1.0f},   // degenerate faces
    {1.0f, 0.45f, 0.0f},  // silhouette quads
    {0.3f, 1.0f, 0.3f},   // focus body H
};

// Caster line ranges (casters.cpp): 0 boundary, 1 non-manifold, 2 inconsistent, 3 degenerate faces.
struct LineStyle {
  int range;
  float width;
};
const LineStyle kOrder[4] = {{3, 3.0f}, {2, 3.0f}, {0, 3.0f}, {1, 4.0f}};

void set_wide(GLuint p, const Frame& f, float width, float pull) {
  set(p, "u_viewport", glm::vec2(float(f.w), float(f.h)));
  set(p, "u_width", width);
  set(p, "u_depth_pull", pull);
}

}  // namespace

void inspection_colour(InspectKind kind, float rgb[3]) {
  const glm::vec3 c = kColours[int(kind)];
  rgb[0] = c.r, rgb[1] = c.g, rgb[2] = c.b;
}

bool inspection_counts(State& s, InspectionCounts& out, std::string& error) {
  if (!build_casters(s, error)) return false;
  out = InspectionCounts();
  out.casters = s.casters.size();
  for (const Caster& c : s.casters) {  // two vertices per edge, three edges (six vertices) per degenerate face
    out.drawn.boundary_edges += uint64_t(c.line_count[0] / 2);
    out.drawn.non_manifold_edges += uint64_t(c.line_count[1] / 2);
    out.drawn.inconsistent_edges += uint64_t(c.line_count[2] / 2);
    out.drawn.degenerate_faces += uint64_t(c.line_count[3] / 6);
  }
  const geom::Scene& scene = s.scene;
  const geom::WeldResult w = geom::weld(geom::positions_of(scene.positions.data(), scene.vertex_count()),
                                        scene.indices.data(), scene.indices.size());
  geom::TopologyOptions options;
  options.dihedral_angles = false;
  const geom::TopologyStats t = geom::build_topology(geom::positions_of(w.positions.data(), w.positions.size() / 3),
                                                     w.indices.data(), w.indices.size() / 3, options)
                                    .stats;
  out.report.boundary_edges = t.boundary_edges, out.report.non_manifold_edges = t.non_manifold_edges;
  out.report.inconsistent_edges = t.inconsistent_edges;
  out.report.degenerate_faces = t.collapsed_triangles + t.zero_area_triangles;
  return true;
}

bool inspection_pass(Frame& f, geom::FocusMethod method) {
  State& s = f.s;
  const glm::dmat4& view_proj = f.view_proj;
  GLuint lines = program(s.programs, {"inspect.vert", "inspect.geom", "inspect.frag"}, f.error);
  GLuint quads = lines ? program(s.programs, {"esm_quad.vert", "inspect.frag"}, f.error) : 0;
  if (!quads) return false;
  f.timer.begin("inspection");
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  // Silhouette quads of the current light, extruded in the camera's clip space
  // (about 3 pixels wide); only the quads that open for this light have area.
  glUseProgram(quads);
  set(quads, "u_colour", glm::vec4(kColours[int(InspectKind::Silhouette)], 1));
  set(quads, "u_planes", 2);
  set(quads, "u_extrude_scale", 2.0f * 3.0f / (float(std::max(f.w, f.h)) * std::fabs(float(view_proj[1][1])) + 1e-30f));
  for (const Caster& c : s.casters) {
    set(quads, "u_light_view_proj", at(view_proj, c.origin));
    set(quads, "u_light", local_light(c, glm::dvec4(f.light.position)));
    glBindTextureUnit(2, c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
  glBindTextureUnit(2, 0);
  // The focus body H of a focused shadow map, as a wireframe drawn over everything.
  geom::FocusResult r;
  if (f.focused) r = focus(s, f.view, float(f.w) / float(f.h), f.light, method, true);
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
  glUseProgram(lines);
  set(lines, "u_matrix", glm::mat4(view_proj));
  if (!edges.empty()) {
    Buffer buffer;
    VertexArray vao;
    upload(buffer, edges.data(), edges.size() * sizeof(float), "focus body H edges");
    glCreateVertexArrays(1, &vao.id);
    glVertexArrayVertexBuffer(vao, 0, buffer, 0, 3 * sizeof(float));
    attribute(vao, 0, 3, GL_FLOAT, 0, false);
    label(GL_VERTEX_ARRAY, vao, "focus body H");
    glDisable(GL_DEPTH_TEST);
    set_wide(lines, f, 2.0f, 0.0f);
    set(lines, "u_colour", glm::vec4(kColours[int(InspectKind::FocusBody)], 1));
    glBindVertexArray(vao);
    glDrawArrays(GL_LINES, 0, GLsizei(edges.size() / 3));
    glEnable(GL_DEPTH_TEST);
  }
  // The topology problems on top, the most serious last.
  for (const LineStyle& style : kOrder) {
    set_wide(lines, f, style.width, 0.004f);
    set(lines, "u_colour", glm::vec4(kColours[style.range], 1));
    for (const Caster& c : s.casters) {
      if (!c.line_count[style.range]) continue;
      glBindVertexArray(c.lines_vao);
      glDrawArrays(GL_LINES, c.line_first[style.range], c.line_count[style.range]);
    }
  }
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  f.timer.end();
  return true;
}

}  // namespace render
