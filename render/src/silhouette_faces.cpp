// silhouette_faces.cpp: the light frames of the map techniques drawn as one
// fitted frustum or six faces (light_fit.cpp, focused.cpp), and the 2D-array
// textures their faces are gathered into. esm, edsm, sssm and esm-soft
// (Bujnak 2004, Sect. 4: a point light as six maps) draw each face's depth map and
// edge map with their own 2D passes and copy them into layer i of a 2D-array
// depth texture and a 2D-array edge texture; ssm, pcf and the focused maps
// draw one or six depth maps the same way (depth_faces). The lookup (shaders/lookup_faces.frag)
// takes the face of the sample's largest axis.
//
// Seams: each 90-degree face is wider by a guard band of kGuard texels on
// every side (light_fit.cpp), so the samples a face receives lie at least
// kGuard texels inside its map: the 2 x 2 footprint (one texel), pcf's taps
// and the edge quads (ESM 2.5 texels, EDSM 2 texels) around them are the
// face's own, and a silhouette crossing a seam is drawn whole in both faces.
// A face with nothing to hold (geom/focus.h FocusFace::empty) has the zero
// matrix and is not drawn.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "state.h"

namespace render {
namespace {

constexpr float kGuard = 4.0f;  // texels beyond the 90-degree face on each side

// The 2D arrays of `layers` faces: depth (compared), and edges unless edge_format is 0.
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
  label(GL_TEXTURE, s.face_depth, "map faces: depth");
  if (!edge_format) return;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &s.face_edges.id);
  glTextureStorage3D(s.face_edges, 1, edge_format, n, n, layers);
  glTextureParameteri(s.face_edges, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.face_edges, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  label(GL_TEXTURE, s.face_edges, "map faces: edges");
}

void copy_depth(State& s, int n, int layer) {
  glCopyImageSubData(s.shadow_map.depth, GL_TEXTURE_2D, 0, 0, 0, 0, s.face_depth, GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer,
                     n, n, 1);
}

bool drawn(const glm::mat4& m) { return m != glm::mat4(0.0f); }  // an empty face's zero matrix: not drawn

// Face i looks along +X -X +Y -Y +Z -Z from the light, with the guard band,
// over the scene's bounding sphere in depth: esm's, sssm's and the soft
// techniques' edge passes are tuned to this depth range, not to the faces'
// fitted one.
glm::mat4 sphere_face(const State& s, const glm::vec3& L, int i, int n) {
  static const glm::vec3 axis[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  const float d = glm::length(glm::vec3(s.bounds) - L), r = s.bounds.w;
  const float near_plane = std::max(r * 1e-3f, (d - r) * 0.5f), far_plane = (d + r) * 1.01f;
  const float fov = 2 * std::atan(1 + 2 * kGuard / float(n));
  return glm::perspective(fov, 1.0f, near_plane, far_plane) * glm::lookAt(L, L + axis[i], up[i]);
}

// Whether technique t's lookup falls back to ssm's own test where its edges
// cannot decide (shaders/lookup_edsm.frag, lookup_esm_exact.frag). Such a
// technique draws ssm's faces (light_fit.cpp's fitted near and far), so that
// the fallback compares the same depth map as ssm and the edges can only
// remove ssm's errors. The scene sphere's depth range (its near plane at 1e-3
// of the radius when the light is inside the sphere) gives a coarser depth
// map than ssm's: ssm's test on it, geombench scan at 256 (640x480, 1 frame),
// 687 wrong pixels against ssm's 652.
bool ssm_faces(Technique t) {
  return t == Technique::Edsm || t == Technique::EdsmGs || t == Technique::EdsmLispsm || t == Technique::EsmExact;
}

}  // namespace

bool silhouette_faces(Frame& f, bool (*draw_face)(Frame& f, const glm::mat4& light_clip), GLenum edge_format) {
  State& s = f.s;
  const int n = f.n;
  f.faces = fit_light_frames(f, kGuard);
  if (f.faces == 1) f.face_clip[0] = f.light_frame.clip();
  for (int i = 0; f.faces == 6 && !ssm_faces(f.t) && i < 6; ++i)
    if (drawn(f.face_clip[i])) f.face_clip[i] = sphere_face(s, glm::vec3(f.light.position), i, n);
  ensure_arrays(s, n, f.faces, edge_format);  // before the faces: edsm's second edge pass reads its layer
  glTextureParameteri(s.face_depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.face_depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  for (int i = 0; i < f.faces; ++i) {
    if (!drawn(f.face_clip[i])) continue;
    if (!draw_face(f, f.face_clip[i])) return false;
    copy_depth(s, n, i);
    glCopyImageSubData(s.edge_map.color, GL_TEXTURE_2D, 0, 0, 0, 0, s.face_edges, GL_TEXTURE_2D_ARRAY, 0, 0, 0, i, n, n,
                       1);
  }
  f.shadow_texture = s.face_depth;
  f.second_texture = s.face_edges;
  return true;
}

float face_guard() { return kGuard; }

bool depth_faces(Frame& f, int faces, float slope, bool linear_light) {
  State& s = f.s;
  ensure_arrays(s, f.n, faces, 0);
  for (int i = 0; i < faces; ++i) {
    if (!drawn(f.face_clip[i])) continue;
    static const char* names[6] = {"depth map +X", "depth map -X", "depth map +Y",
                                   "depth map -Y", "depth map +Z", "depth map -Z"};
    if (!depth_map_pass(f, f.face_clip[i], slope, linear_light, faces == 1 ? "depth map" : names[i])) return false;
    copy_depth(s, f.n, i);
  }
  glTextureParameteri(s.face_depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.face_depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  f.faces = faces;
  f.shadow_texture = s.face_depth;
  return true;
}

}  // namespace render
