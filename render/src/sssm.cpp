// sssm.cpp: shadow silhouette maps (Sen, Cammarano and Hanrahan 2003, the
// baseline Kenzel 2013 compares EDSM with): the depth map, then the silhouette
// edges (sssm: the baked candidate edges tested once per frame,
// silhouette_edges.cpp, shaders/sssm_quad.vert; sssm-gs: a geometry shader
// over each caster's triangles with adjacency, geom/adjacency.h) store one
// point on the silhouette per cell of a second map offset by half a texel
// (shaders/sssm_edges.*); the lookup,
// shaders/lookup_sssm.frag, rebuilds the boundary from the 3 x 3 neighbourhood.
#include "edge_pass.h"

namespace render {

namespace {

// One face (silhouette_faces.cpp): the depth map, then the silhouette map
// beside it, its edges from the frame's silhouette list (`gs` false,
// silhouette_edges.cpp) or from the geometry shader over every triangle.
bool sssm_face(Frame& f, const glm::mat4& light_clip, bool gs) {
  // The point (2 x snorm16), the edge depth's bits.
  const std::vector<std::string> files =
      gs ? std::vector<std::string>{"sssm_edges.vert", "sssm_edges.geom", "sssm_edges.frag"}
         : std::vector<std::string>{"sssm_quad.vert", "sssm_edges.frag"};
  GLuint p = edge_program(f, light_clip, 1.5f, GL_RG32UI, files);
  if (!p) return false;
  if (gs) {
    set(p, "u_matrix", light_clip);
    adjacency_edge_pass(f, p, "silhouette map", EdgeTarget::Silhouette);
    return true;
  }
  begin_edge_pass(f, p, "silhouette map", EdgeTarget::Silhouette);
  draw_silhouette_quads(f, p, light_clip);
  end_edge_pass(f, EdgeTarget::Silhouette);
  return true;
}

bool sssm_vs_face(Frame& f, const glm::mat4& light_clip) { return sssm_face(f, light_clip, false); }
bool sssm_gs_face(Frame& f, const glm::mat4& light_clip) { return sssm_face(f, light_clip, true); }

}  // namespace

// The light frames of edsm (silhouette_faces.cpp): the frustum fitted to what
// the camera sees, or six cube faces where a point light's receivers need more.
// sssm: the silhouette edges found once per frame (silhouette_edges.cpp);
// sssm-gs: the geometry shader over every triangle with adjacency.
bool sssm_passes(Frame& f) {
  const bool gs = f.t == Technique::SssmGs;
  if (!gs && !find_silhouettes(f)) return false;
  if (!silhouette_faces(f, gs ? sssm_gs_face : sssm_vs_face, GL_RG32UI)) return false;
  f.lookup = "lookup_sssm.frag";
  return true;
}

}  // namespace render
