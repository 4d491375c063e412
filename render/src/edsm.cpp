// edsm.cpp: the edge distance shadow map (Kenzel 2013, Sect. 4.2.1): the depth
// map, then the silhouette edges' lines and depths beside it
// (shaders/edsm_edges.frag); a second pass over the same edges peels the
// second nearest (the thesis's future work, Sect. 6.1: two edges per texel for
// Sect. 5.2's closely spaced edges and receivers' outlines). The lookup is
// shaders/lookup_edsm.frag. Two ways to find the silhouette edges, the same
// edges written:
//  - edsm: a compute pass tests each baked candidate edge once per frame
//    (geom/esm_quads.h records, both face planes; silhouette_edges.cpp) and
//    every edge pass draws the silhouette edges alone (shaders/edsm_quad.vert),
//    no geometry shader;
//  - edsm-gs, the thesis's: a geometry shader over every caster triangle with
//    adjacency (geom/adjacency.h; shaders/edsm_edges.vert, .geom), run twice
//    per face (once per peeled edge).
#include "edge_pass.h"

namespace render {

namespace {

// One face: the depth map, then the two-edge map beside it, the edges drawn
// from the baked records (`gs` false) or by the geometry shader.
bool edsm_face(Frame& f, const glm::mat4& light_clip, bool gs) {
  // Bias factor 2: the lookup compares a 2 x 2 footprint (taps one texel away).
  const std::vector<std::string> files =
      gs ? std::vector<std::string>{"edsm_edges.vert", "edsm_edges.geom", "edsm_edges.frag"}
         : std::vector<std::string>{"edsm_quad.vert", "edsm_edges.frag"};
  GLuint p = edge_program(f, light_clip, 2.0f, GL_RGBA32UI, files);
  if (!p) return false;
  State& s = f.s;
  int layer = 0;  // this face's layer of s.face_edges (silhouette_faces.cpp has made it)
  while (layer + 1 < f.faces && f.face_clip[layer] != light_clip) ++layer;
  if (gs) set(p, "u_matrix", light_clip);
  set(p, "u_half_width", 2.0f);
  set(p, "u_peel", 0);
  set(p, "u_first", 2);
  set(p, "u_layer", layer);
  auto pass = [&](const char* label, EdgeTarget target) {
    if (gs) return adjacency_edge_pass(f, p, label, target);
    begin_edge_pass(f, p, label, target);
    draw_silhouette_quads(f, p, light_clip);
    end_edge_pass(f, target);
  };
  pass("edge distance map", EdgeTarget::EdgePair);
  // The first edges into the face's layer, read there by the second pass.
  glCopyImageSubData(s.edge_map.color, GL_TEXTURE_2D, 0, 0, 0, 0, s.face_edges, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer,
                     f.n, f.n, 1);
  glBindTextureUnit(2, s.face_edges);
  set(p, "u_peel", 1);
  pass("edge distance map, second edge", EdgeTarget::EdgeSecond);
  glBindTextureUnit(2, 0);
  return true;
}

bool edsm_vs_face(Frame& f, const glm::mat4& light_clip) { return edsm_face(f, light_clip, false); }
bool edsm_gs_face(Frame& f, const glm::mat4& light_clip) { return edsm_face(f, light_clip, true); }

}  // namespace

bool edsm_passes(Frame& f) {
  if (f.t == Technique::Edsm && !find_silhouettes(f)) return false;
  if (!silhouette_faces(f, f.t == Technique::EdsmGs ? edsm_gs_face : edsm_vs_face, GL_RGBA32UI)) return false;
  f.lookup = "lookup_edsm.frag";
  return true;
}

}  // namespace render
