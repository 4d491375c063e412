// soft.cpp: soft shadows of a disc light (FrameSettings::light_radius).
//  - edsm-soft (Kenzel 2013, Sect. 6 and Fig. 6.1; Bujnak 2004, Sect. 3.2): the edge
//    distance shadow map's passes (the depth map, then the edge quads of
//    edsm_edges.vert and edsm_soft_edges.geom / .frag: each as wide as the
//    widest penumbra its edge casts, kMaxReach texels at most); the lookup (shaders/lookup_edsm_soft.frag) turns the
//    signed edge distance into a light fraction with the disc's kernel (soft_light.frag).
//  - pcf-soft, the baseline: the depth map, then PCF with a kernel as wide as
//    the penumbra after a blocker search (shaders/lookup_pcf_soft.frag).
// Both estimate the penumbra the same way (soft_light.frag) and share its reach,
// as does esm-soft (esm_soft.cpp).
#include <algorithm>
#include <cmath>

#include "edge_pass.h"

namespace render {
namespace {

constexpr float kMaxReach = 32;  // texels: the edge quads' and the blocker search's widest reach

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

float soft_reach(const Frame& f, float projection) {
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
  return std::clamp(ndc * scale, 2.0f, kMaxReach);
}

bool edsm_soft_passes(Frame& f) {
  State& s = f.s;
  f.light_frame = light_frame(s, f.light);
  const glm::mat4 light_clip = f.light_frame.clip();
  GLuint p =
      edge_program(f, light_clip, 1.5f, GL_RG32F, {"edsm_edges.vert", "edsm_soft_edges.geom", "edsm_soft_edges.frag"});
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  set(p, "u_half_width", 2.0f);  // the hard edsm's
  set(p, "u_max_half_width", soft_reach(f));
  set(p, "u_light_proj", f.light_frame.proj);
  set(p, "u_light_radius", f.fs.light_radius);
  adjacency_edge_pass(f, p, "edge distance map", EdgeTarget::Distance);
  finish_map(f);
  // The lookup reads each texel's comparison at its exact centre (lookup_edsm_soft.frag).
  glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  f.second_texture = s.edge_map.color;
  f.lookup = "lookup_edsm_soft.frag";
  f.lookup_extra = "soft_light.frag";
  return true;
}

bool soft_shade(Frame& f, GLuint p) {
  set_soft_uniforms(f, p);
  return shade_scene(f);
}

bool pcf_soft_passes(Frame& f) {
  f.light_frame = light_frame(f.s, f.light);
  if (!depth_map_pass(f, f.light_frame.clip(), 3.5f, false)) return false;  // as pcf's; the lookup adds its plane bias
  finish_map(f);
  f.second_texture = f.s.shadow_map.depth;  // read again without comparison (the blocker search)
  f.lookup = "lookup_pcf_soft.frag";
  f.lookup_extra = "soft_light.frag";
  return true;
}

bool pcf_soft_shade(Frame& f, GLuint p) {
  set_soft_uniforms(f, p);
  set(p, "u_depth_map", 1);
  glBindSampler(1, depth_sampler(f.s));
  shade_scene(f);
  glBindSampler(1, 0);
  return true;
}

}  // namespace render
