// edsm.cpp: the edge distance shadow map (Kenzel 2013, Sect. 4.2.1): the depth
// map, then a geometry shader finds the silhouette edges of each caster's
// triangles with adjacency (geom/adjacency.h) and writes the nearest edge's
// line and depth (shaders/edsm_edges.*); a second pass over the same edges
// peels the second nearest (the thesis's future work, Sect. 6.1: two edges per
// texel for Sect. 5.2's closely spaced edges and receivers' outlines). The
// lookup is shaders/lookup_edsm.frag. Cost of the second pass, llvmpipe, load
// about 7.5 (one frame, geombench): jenga@512 depth map 16.5 ms, first edge
// pass 99.7 ms, second 102.7 ms; at 2048 88 / 461 / 495 ms; the default
// scene's six faces at 512 20 / 26 / 16 ms (the second pass draws the same
// edges again: the geometry shader runs twice).
#include "edge_pass.h"

namespace render {

namespace {

// One face: the depth map, then the two-edge map beside it.
bool edsm_face(Frame& f, const glm::mat4& light_clip) {
  // Bias factor 2: the lookup compares a 2 x 2 footprint (taps one texel away).
  GLuint p = edge_program(f, light_clip, 2.0f, GL_RGBA32UI, {"edsm_edges.vert", "edsm_edges.geom", "edsm_edges.frag"});
  if (!p) return false;
  State& s = f.s;
  int layer = 0;  // this face's layer of s.face_edges (silhouette_faces.cpp has made it)
  while (layer + 1 < f.faces && f.face_clip[layer] != light_clip) ++layer;
  set(p, "u_matrix", light_clip);
  set(p, "u_half_width", 2.0f);
  set(p, "u_peel", 0);
  set(p, "u_first", 2);
  set(p, "u_layer", layer);
  adjacency_edge_pass(f, p, "edge distance map", EdgeTarget::EdgePair);
  // The first edges into the face's layer, read there by the second pass.
  glCopyImageSubData(s.edge_map.color, GL_TEXTURE_2D, 0, 0, 0, 0, s.face_edges, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer,
                     f.n, f.n, 1);
  glBindTextureUnit(2, s.face_edges);
  set(p, "u_peel", 1);
  adjacency_edge_pass(f, p, "edge distance map, second edge", EdgeTarget::EdgeSecond);
  glBindTextureUnit(2, 0);
  return true;
}

}  // namespace

bool edsm_passes(Frame& f) {
  if (!silhouette_faces(f, edsm_face, GL_RGBA32UI)) return false;
  f.lookup = "lookup_edsm.frag";
  return true;
}

}  // namespace render
