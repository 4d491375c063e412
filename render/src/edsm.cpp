// edsm.cpp: the edge distance shadow map (seed 001, Sect. 4.2.1): the depth
// map, then a geometry shader finds the silhouette edges of each caster's
// triangles with adjacency (geom/adjacency.h) and writes the distance to the
// nearest one (shaders/edsm_edges.*); the lookup is shaders/lookup_edsm.frag.
#include "edge_pass.h"

namespace render {

namespace {

// One face: the depth map, then the edge distance map beside it.
bool edsm_face(Frame& f, const glm::mat4& light_clip) {
  // Bias factor 2: the lookup compares a 2 x 2 footprint (taps one texel away).
  GLuint p = edge_program(f, light_clip, 2.0f, GL_RG32F, {"edsm_edges.vert", "edsm_edges.geom", "edsm_edges.frag"});
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  set(p, "u_half_width", 2.0f);
  adjacency_edge_pass(f, p, "edge distance map", EdgeTarget::Distance);
  return true;
}

}  // namespace

bool edsm_passes(Frame& f) {
  if (!silhouette_faces(f, edsm_face, GL_RG32F)) return false;
  f.lookup = "lookup_edsm.frag";
  return true;
}

}  // namespace render
