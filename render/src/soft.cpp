// soft.cpp: soft shadows of a disc light (FrameSettings::light_radius).
//  - edsm-soft (Kenzel 2013, Sect. 6 and Fig. 6.1; Bujnak 2004, Sect. 3.2): the edge
//    distance shadow map's passes (the depth map, then the edge quads of
//    edsm_edges.vert and edsm_soft_edges.geom / .frag: each as wide as the
//    widest penumbra its edge casts, kMaxReach texels at most); the lookup (shaders/lookup_edsm_soft.frag) turns the
//    signed edge distance into a light fraction with the disc's kernel (soft_light.frag).
//  - pcf-soft, the baseline: pcf's depth maps (one fitted frustum or six
//    faces), then PCF with a kernel as wide as the penumbra after a blocker
//    search, every tap the receiver-plane test of shaders/depth_plane.frag
//    (shaders/lookup_pcf_soft.frag).
// Both estimate the penumbra the same way (soft_light.frag) and share its reach,
// as does esm-soft (esm_soft.cpp).
#include <algorithm>
#include <cmath>

#include "edge_pass.h"

namespace render {
namespace {

constexpr float kMaxReach = 32;  // texels: the edge quads' and the blocker search's widest reach

// pcf-soft's widest reach: its search and kernel take a fixed number of taps
// however far they reach, so it is bounded in map widths (kMaxReach texels of
// a 512 map, 1/16 of the map at every size), not in texels: a finer map must
// not narrow the penumbra, and a coarser one must not widen it (a wider reach
// at 256 than at 512 made the light-fraction error step up from 256 to 512 on
// the colonnade lit from behind and on the Quake 3 level).
float map_reach(const Frame& f) { return kMaxReach * float(f.n) / 512.0f; }

void set_soft_uniforms(Frame& f, GLuint p) {
  set(p, "u_light_proj", f.light_frame.proj);
  set(p, "u_light_radius", f.fs.light_radius);
  set(p, "u_map_size", float(f.n));
  set(p, "u_reach", soft_reach(f));
}

bool shade_scene(Frame& f) {
  f.timer.begin("shading");
  draw_scene(f.s);
  f.timer.end();
  return true;
}

}  // namespace

float soft_reach(const Frame& f) { return soft_reach(f, f.light_frame.proj[0][0]); }

float soft_reach(const Frame& f, float projection) { return soft_reach(f, projection, kMaxReach); }

float soft_reach(const Frame& f, float projection, float cap) {
  const State& s = f.s;
  const float R = std::max(f.fs.light_radius, 0.0f), r = std::max(s.bounds.w, 1e-6f);
  const float scale = projection * float(f.n) * 0.5f;  // NDC per unit -> texels
  float ndc = 0;
  if (f.light.position.w == 0) {
    ndc = std::tan(std::min(R, 1.5f)) * 2 * r;
  } else {
    const float d = glm::length(glm::vec3(s.bounds) - glm::vec3(f.light.position));
    const float near_side = std::max(d - r, r * 0.05f), far_side = d + r;
    ndc = R * (far_side - near_side) / (near_side * far_side);
  }
  return std::clamp(ndc * scale, 2.0f, cap);
}

namespace {

// edsm-soft's edge pass on the light clip matrix `light_clip` (a face of six,
// or the scene's frustum), each quad as wide as its edge's widest penumbra
// there: `far_side` is that frame's far side, a distance from a point light or
// a depth along the sun's rays (edsm_soft_edges.geom).
bool edsm_soft_edges(Frame& f, const glm::mat4& light_clip, float far_side, float cap) {
  GLuint p = edge_program(f, light_clip, 1.5f, GL_RG32F,
                          {"edsm_soft_edges.vert", "edsm_soft_edges.geom", "edsm_soft_edges.frag"});
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  set(p, "u_half_width", 2.0f);  // the hard edsm's
  set(p, "u_max_half_width", soft_reach(f, projection_scale(light_clip), cap));
  set(p, "u_light", f.light.position);  // input coordinates, as the adjacency buffers
  set(p, "u_far", far_side);
  set(p, "u_texel_scale", projection_scale(light_clip) * float(f.n) * 0.5f);
  set(p, "u_light_radius", f.fs.light_radius);
  adjacency_edge_pass(f, p, "edge distance map", EdgeTarget::Distance);
  return true;
}

// A face of six: its far side is the scene's.
bool edsm_soft_face(Frame& f, const glm::mat4& light_clip) {
  const glm::vec3 c(f.s.bounds), L = glm::vec3(f.light.position) / f.light.position.w;
  return edsm_soft_edges(f, light_clip, glm::length(c - L) + std::max(f.s.bounds.w, 1e-6f), map_reach(f));
}

}  // namespace

// edsm-soft: one map of the scene's frustum (light_frame), or, for a point
// light whose receivers need more than one frustum (light_fit.cpp), the six
// faces of esm's and edsm's light frames (silhouette_faces.cpp).
bool edsm_soft_passes(Frame& f) {
  State& s = f.s;
  f.lookup_extra = "soft_light.frag";
  if (f.light.position.w != 0 && fit_light_frames(f, face_guard()) == 6) {
    if (!silhouette_faces(f, edsm_soft_face, GL_RG32F)) return false;
    f.lookup = "lookup_edsm_soft_faces.frag";
    return true;
  }
  f.projection.clear(), f.faces = 0;
  f.light_frame = light_frame(s, f.light);
  const glm::mat4 light_clip = f.light_frame.clip();
  // The frame's far plane, as a distance from the light (perspective) or a
  // depth along the sun's rays (light_frame's orthographic frustum).
  const glm::mat4& P = f.light_frame.proj;
  const glm::vec3 c(s.bounds), L(f.light.position);
  const float r = std::max(s.bounds.w, 1e-6f);
  const float far_side = f.light.position.w != 0 ? P[3][2] / (P[2][2] + 1.0f)
                                                 : glm::dot(c, -glm::normalize(L)) + (P[3][2] - 1.0f) / P[2][2] - 2 * r;
  if (!edsm_soft_edges(f, light_clip, far_side, kMaxReach)) return false;
  finish_map(f);
  // The lookup reads each texel's comparison at its exact centre (lookup_edsm_soft.frag).
  glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  f.second_texture = s.edge_map.color;
  f.lookup = "lookup_edsm_soft.frag";
  return true;
}

bool soft_shade(Frame& f, GLuint p) {
  set_soft_uniforms(f, p);
  return shade_scene(f);
}

// pcf-soft draws pcf's light frames (light_fit.cpp: a fitted frustum, or six
// faces for a point light among its receivers) and depth maps.
bool pcf_soft_passes(Frame& f) {
  const int faces = fit_light_frames(f, face_guard());
  if (faces == 1) f.face_clip[0] = f.light_frame.clip();
  if (!depth_faces(f, faces, kMapSlope, false)) return false;
  f.lookup = "lookup_pcf_soft.frag";
  f.lookup_extra = "soft_light.frag";
  return true;
}

bool pcf_soft_shade(Frame& f, GLuint p) {
  // The reach along each axis of the map, at the faces' finest scale: a
  // fitted frustum's texels need not be square in the world.
  glm::vec2 scale(0);
  for (int i = 0; i < f.faces; ++i)
    if (f.face_clip[i] != glm::mat4(0.0f))
      for (int a = 0; a < 2; ++a) {
        const glm::mat4& m = f.face_clip[i];
        scale[a] = std::max(scale[a], glm::length(glm::vec3(m[0][a], m[1][a], m[2][a])));
      }
  set(p, "u_light_radius", f.fs.light_radius);
  set(p, "u_reach", glm::vec2(soft_reach(f, scale.x, map_reach(f)), soft_reach(f, scale.y, map_reach(f))));
  return shade_scene(f);
}

}  // namespace render
