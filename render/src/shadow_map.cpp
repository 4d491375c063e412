// shadow_map.cpp: ssm and pcf, and the depth map every map technique starts
// from (esm, edsm, the focused maps), drawn with a slope-scaled bias (Kenzel
// 2013, Sect. 1.2; Arneson, glPolygonOffset). ssm, pcf, the focused maps, and
// edsm and esm-exact where their edges cannot decide, compare it with the
// receiver's plane at each texel's centre (shaders/depth_plane.frag; Dou et
// al. 2014); the others compare in hardware at the sample's depth. ssm's and pcf's lookup (the nearest texel,
// or 3 x 3 bilinear taps one texel apart) is shaders/lookup_shadow_faces.frag.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "state.h"

namespace render {
namespace {

// The 2D shadow map: a DEPTH_COMPONENT32F texture with comparison (sampler2DShadow).
void ensure_shadow_map(State& s, int n) {
  Target& t = s.shadow_map;
  if (t.width == n) return;
  t = Target();
  t.width = t.height = n;
  glCreateTextures(GL_TEXTURE_2D, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, n, n);
  glTextureParameteri(t.depth, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(t.depth, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTextureParameteri(t.depth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.depth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  label(GL_TEXTURE, t.depth, "shadow map depth");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  glNamedFramebufferDrawBuffer(t.fbo, GL_NONE);
  label(GL_FRAMEBUFFER, t.fbo, "shadow map");
}

glm::vec3 any_perpendicular(glm::vec3 d) {
  return std::fabs(d.y) < 0.9f * glm::length(d) ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

}  // namespace

FrameLight frame_light(const geom::Light& light) {
  double h[4];
  geom::light_homogeneous(light, h);
  FrameLight f;
  f.position = glm::vec4(float(h[0]), float(h[1]), float(h[2]), float(h[3]));
  if (light.type == geom::LightType::Spot) {
    f.spot = true;
    f.spot_direction = glm::vec3(float(light.direction[0]), float(light.direction[1]), float(light.direction[2]));
    f.spot_angle = float(light.outer_cone);
  }
  return f;
}

// The single shadow map's light frame, covering the scene's bounding sphere:
// orthographic for a directional light, perspective for a point light (aimed
// at the sphere) and for a spot light (aimed along its axis, the cone's full
// angle as field of view).
LightFrame light_frame(const State& s, const FrameLight& light) {
  const glm::vec3 c(s.bounds), L(light.position);
  const float r = std::max(s.bounds.w, 1e-6f);
  LightFrame f;
  if (light.position.w == 0) {
    const glm::vec3 dir = glm::normalize(L);
    f.view = glm::lookAt(c + dir * (2 * r), c, any_perpendicular(dir));
    f.proj = glm::ortho(-r, r, -r, r, r * 0.5f, r * 3.5f);
    return f;
  }
  const float d = glm::length(c - L);
  const float near_plane = std::max(d - r, r * 1e-3f), far_plane = d + r;
  glm::vec3 axis = d > 1e-6f * r ? (c - L) / d : glm::vec3(0, -1, 0);
  float fov = d > r ? std::min(2 * std::asin(r / d) * 1.02f, glm::radians(170.0f)) : glm::radians(170.0f);
  if (light.spot) {
    axis = glm::normalize(light.spot_direction);
    fov = std::min(2 * light.spot_angle * 1.02f, glm::radians(170.0f));
  }
  f.view = glm::lookAt(L, L + axis, any_perpendicular(axis));
  f.proj = glm::perspective(fov, 1.0f, near_plane, far_plane);
  return f;
}

glm::vec4 local_light(const State& s, const FrameLight& light) {
  return glm::vec4(glm::dvec3(light.position) - s.origin * double(light.position.w), light.position.w);
}

// The linear light depth of the focused maps spans the scene's bounding sphere
// (1% margin) along the light's rays.
glm::vec2 light_depth_range(const State& s, const FrameLight& light) {
  const glm::dvec3 c = glm::dvec3(glm::vec3(s.bounds)) - s.origin;
  const double r = std::max(double(s.bounds.w), 1e-6) * 1.01;
  double lo = 0, hi = 0;
  if (light.position.w == 0) {
    const glm::dvec3 towards(glm::vec3(light.position));
    const double m = -glm::dot(c, towards) / std::max(glm::length(towards), 1e-300);  // a zero direction: finite
    lo = m - r, hi = m + r;
  } else {
    const double d = glm::length(c - glm::dvec3(glm::vec3(local_light(s, light))));
    lo = std::max(0.0, d - r), hi = d + r;
  }
  return glm::vec2(float(lo), float(1.0 / (hi - lo)));
}

// `slope` is the slope-scaled bias factor (0: none): the depth slope of one
// texel covers a lookup at the texel's own centre; a filter whose taps reach k
// texels away needs about k + 1 of them. The lookups that test the receiver's
// plane (shaders/depth_plane.frag) keep it for concave creases: there a
// texel's centre falls on the other face, in front of the receiver's plane,
// and the offset pushes that face back. With `linear_light` (the focused maps,
// whose matrix warps depth) the map stores the linear light depth of
// shaders/light_depth.frag with the bias computed in it (depth_linear.frag);
// otherwise the matrix's own depth with glPolygonOffset's bias.
bool depth_map_pass(Frame& f, const glm::mat4& light_clip, float slope, bool linear_light, const char* pass) {
  State& s = f.s;
  const int n = f.n;
  ensure_shadow_map(s, n);
  GLuint p = linear_light ? program(s.programs, {"depth.vert", "depth_linear.frag", "light_depth.frag"}, f.error)
                          : program(s.programs, {"depth.vert", "depth.frag"}, f.error);
  if (!p) return false;
  set(p, "u_matrix", at(glm::dmat4(light_clip), s.origin));
  if (linear_light) {
    set(p, "u_light", local_light(s, f.light));
    set(p, "u_depth_range", light_depth_range(s, f.light));
    set(p, "u_bias_slope", slope);
    set(p, "u_bias_constant", slope > 0 ? 1.0f / 65536.0f : 0.0f);  // about 3e-5 of the scene's diameter
  }
  f.timer.begin(pass);
  glBindFramebuffer(GL_FRAMEBUFFER, s.shadow_map.fbo);
  glViewport(0, 0, n, n);
  glClear(GL_DEPTH_BUFFER_BIT);
  // Casters before the near plane still occlude (focused maps: the depth written
  // is linear; fitted frusta: their near plane is H's nearest point).
  glEnable(GL_DEPTH_CLAMP);
  if (!linear_light && slope > 0) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(slope, 4.0f);  // slope-scaled depth bias (Kenzel 2013, Sect. 1.2; Arneson, glPolygonOffset)
  }
  glUseProgram(p);
  draw_scene(s);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_DEPTH_CLAMP);
  f.timer.end();
  return true;
}

void finish_map(Frame& f) {
  const GLint filter = f.t == Technique::Ssm ? GL_NEAREST : GL_LINEAR;
  glTextureParameteri(f.s.shadow_map.depth, GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(f.s.shadow_map.depth, GL_TEXTURE_MAG_FILTER, filter);
  f.shadow_texture = f.s.shadow_map.depth;
}

// The edge target of esm / edsm: an N x N float colour texture + its own depth.
void ensure_edge_map(State& s, int n, GLenum format) {
  Target& t = s.edge_map;
  if (t.width == n && t.height == int(format)) return;
  t = Target();
  t.width = n, t.height = int(format);  // height field keeps the format: one target serves both
  glCreateTextures(GL_TEXTURE_2D, 1, &t.color.id);
  glTextureStorage2D(t.color, 1, format, n, n);
  glTextureParameteri(t.color, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.color, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  label(GL_TEXTURE, t.color, "edge map");
  glCreateTextures(GL_TEXTURE_2D, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, n, n);
  label(GL_TEXTURE, t.depth, "edge map priority depth");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.color, 0);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  label(GL_FRAMEBUFFER, t.fbo, "edge map");
}

GLuint depth_sampler(State& s) {
  if (!s.depth_sampler) {
    glCreateSamplers(1, &s.depth_sampler.id);
    glSamplerParameteri(s.depth_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(s.depth_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(s.depth_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    label(GL_SAMPLER, s.depth_sampler, "depth without comparison");
  }
  return s.depth_sampler;
}

// ssm: one depth map (offset kMapSlope), the nearest texel tested against the
// receiver's plane; pcf: the same with 3 x 3 bilinear taps. The light frustum
// is fitted to what the camera sees (light_fit.cpp); a point light that needs
// more than one frustum gets six faces, each its own depth map, and the frame
// says so ("6 faces"). Both are layers of one 2D array
// (shaders/lookup_shadow_faces.frag).
bool shadow_map_passes(Frame& f) {
  const int faces = fit_light_frames(f, face_guard());
  if (faces == 1) f.face_clip[0] = f.light_frame.clip();
  if (!depth_faces(f, faces, kMapSlope, false)) return false;
  f.lookup = "lookup_shadow_faces.frag";
  return true;
}

}  // namespace render
