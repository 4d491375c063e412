// sssm.cpp: shadow silhouette maps (Sen, Cammarano and Hanrahan 2003, the
// baseline Kenzel 2013 compares EDSM with): the depth map, then a geometry shader
// finds the silhouette edges of each caster's triangles with adjacency
// (geom/adjacency.h) and stores one point on the silhouette per cell of a
// second map offset by half a texel (shaders/sssm_edges.*); the lookup,
// shaders/lookup_sssm.frag, rebuilds the boundary from the 3 x 3 neighbourhood.
#include "edge_pass.h"

namespace render {

namespace {

// One face (silhouette_faces.cpp): the depth map, then the silhouette map beside it.
bool sssm_face(Frame& f, const glm::mat4& light_clip) {
  // The point (2 x snorm16), the edge depth's bits.
  GLuint p = edge_program(f, light_clip, 1.5f, GL_RG32UI, {"sssm_edges.vert", "sssm_edges.geom", "sssm_edges.frag"});
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  adjacency_edge_pass(f, p, "silhouette map", EdgeTarget::Silhouette);
  return true;
}

}  // namespace

// The light frames of edsm (silhouette_faces.cpp): the frustum fitted to what
// the camera sees, or six cube faces where a point light's receivers need more.
bool sssm_passes(Frame& f) {
  if (!silhouette_faces(f, sssm_face, GL_RG32UI)) return false;
  f.lookup = "lookup_sssm.frag";
  return true;
}

}  // namespace render
