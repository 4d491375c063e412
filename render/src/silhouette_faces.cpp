// silhouette_faces.cpp: the light frames of esm and edsm (issue 18). One map
// with the frustum fitted to what the camera sees (light_fit.cpp), or, for a
// point light whose receivers need more than one frustum, six cube faces (seed
// 000, Sect. 4: a point light as six maps), each with its own depth map and
// edge map. A face is drawn by the technique's own 2D passes into the 2D
// targets and copied into layer i of a 2D-array depth texture and a 2D-array
// edge texture; the lookup (shaders/lookup_faces.frag) takes the face of the
// sample's largest axis.
//
// Seams: each face's frustum is wider than 90 degrees by kGuard texels on every
// side (tan(fov / 2) = 1 + 2 kGuard / N), so the samples a face receives lie at
// least kGuard texels inside its map: the 2 x 2 footprint (one texel) and the
// edge quads (ESM 2.5 texels, EDSM 2 texels) around them are the face's own,
// and a silhouette crossing a seam is drawn whole in both faces.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "state.h"

namespace render {
namespace {

constexpr float kGuard = 4.0f;  // texels beyond the 90-degree face on each side

void ensure_arrays(State& s, int n, int layers, GLenum edge_format) {
  if (s.face_n == n && s.face_layers == layers && s.face_format == edge_format) return;
  s.face_depth = Texture(), s.face_edges = Texture();
  s.face_n = n, s.face_layers = layers, s.face_format = edge_format;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &s.face_depth.id);
  glTextureStorage3D(s.face_depth, 1, GL_DEPTH_COMPONENT32F, n, n, layers);
  glTextureParameteri(s.face_depth, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(s.face_depth, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTextureParameteri(s.face_depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.face_depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(s.face_depth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(s.face_depth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  label(GL_TEXTURE, s.face_depth, "silhouette map faces: depth");
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &s.face_edges.id);
  glTextureStorage3D(s.face_edges, 1, edge_format, n, n, layers);
  glTextureParameteri(s.face_edges, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.face_edges, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  label(GL_TEXTURE, s.face_edges, "silhouette map faces: edges");
}

// Face i looks along +X -X +Y -Y +Z -Z from the light, with the guard band.
glm::mat4 face_matrix(const glm::vec3& L, int i, int n, float near_plane, float far_plane) {
  static const glm::vec3 axis[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  const float fov = 2 * std::atan(1 + 2 * kGuard / float(n));
  return glm::perspective(fov, 1.0f, near_plane, far_plane) * glm::lookAt(L, L + axis[i], up[i]);
}

void copy_face(State& s, int n, int layer) {
  glCopyImageSubData(s.shadow_map.depth, GL_TEXTURE_2D, 0, 0, 0, 0, s.face_depth, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer,
                     n, n, 1);
  glCopyImageSubData(s.edge_map.color, GL_TEXTURE_2D, 0, 0, 0, 0, s.face_edges, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, n,
                     n, 1);
}

}  // namespace

bool silhouette_faces(Frame& f, bool (*draw_face)(Frame& f, const glm::mat4& light_clip), GLenum edge_format) {
  State& s = f.s;
  const int n = f.n;
  LightFrame fitted;
  if (fitted_light_frame(f, fitted)) {
    f.faces = 1;
    f.light_frame = fitted;
    f.face_clip[0] = fitted.clip();
  } else {
    f.faces = 6;
    const glm::vec3 L(f.light.position);
    const float d = glm::length(glm::vec3(s.bounds) - L), r = s.bounds.w;
    const float near_plane = std::max(r * 1e-3f, (d - r) * 0.5f), far_plane = (d + r) * 1.01f;
    for (int i = 0; i < 6; ++i) f.face_clip[i] = face_matrix(L, i, n, near_plane, far_plane);
    f.light_frame.proj = f.face_clip[4], f.light_frame.view = glm::mat4(1);
  }
  ensure_arrays(s, n, f.faces, edge_format);  // before the faces: edsm's second edge pass reads its layer
  for (int i = 0; i < f.faces; ++i) {
    if (!draw_face(f, f.face_clip[i])) return false;
    copy_face(s, n, i);
  }
  f.shadow_texture = s.face_depth;
  f.second_texture = s.face_edges;
  return true;
}

}  // namespace render
