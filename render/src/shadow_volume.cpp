// shadow_volume.cpp: stencil shadow volumes (seed 004; seed 001 Sect. 5;
// geom/shadow_volume.h): depth and ambient, the volume of every caster
// counted in the stencil buffer (shaders/shadow_volume.vert, volume.frag),
// depth-fail (sides and caps) or depth-pass (sides) chosen per caster as an
// engine does (sv) or forced (sv-zpass, sv-zfail), then lit shading where the
// count is zero. A static light's exact volume replaces the generic one.
#include <algorithm>
#include <cmath>

#include "state.h"

namespace render {
namespace {

// May the camera's near-plane rectangle lie inside this caster's shadow volume?
// Conservative (004, depth-pass vs depth-fail): the volume part that can contain
// the near rectangle lies within `radius` of the segment from the eye to the
// light (or the ray towards a directional light); test that segment against the
// caster's box grown by `radius` (slab test).
bool camera_may_be_in_volume(const Caster& c, const glm::vec3& eye, float radius, const glm::vec4& light) {
  const glm::vec3 lo = c.lo - glm::vec3(radius), hi = c.hi + glm::vec3(radius);
  const glm::vec3 d = light.w != 0 ? glm::vec3(light) / light.w - eye : glm::vec3(light);
  float t0 = 0, t1 = light.w != 0 ? 1.0f : 1e30f;
  for (int k = 0; k < 3; ++k) {
    if (std::fabs(d[k]) < 1e-30f) {
      if (eye[k] < lo[k] || eye[k] > hi[k]) return false;
      continue;
    }
    float a = (lo[k] - eye[k]) / d[k], b = (hi[k] - eye[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

// The stencil counts of every caster's volume.
bool volume_pass(Frame& f, float near_radius) {
  State& s = f.s;
  const glm::vec4 light = f.light.position;
  GLuint p = program(s.programs, {"shadow_volume.vert", "volume.frag"}, f.error);
  if (!p) return false;
  set(p, "u_planes", 2);
  bool any_exact = false;
  for (const Caster& c : s.casters) any_exact = any_exact || light_volume(c, light);
  f.timer.begin(any_exact ? "stencil volumes (exact for this static light)" : "stencil volumes");
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glStencilMask(0xff);
  glDepthMask(GL_FALSE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_DEPTH_CLAMP);
  glDepthFunc(GL_LESS);
  glUseProgram(p);
  for (const Caster& c : s.casters) {
    const bool zfail = f.t == Technique::SvZFail ||
                       (f.t == Technique::Sv && camera_may_be_in_volume(c, f.view.eye, near_radius, light));
    const Caster::LightVolume* exact = light_volume(c, light);
    const glm::dvec4 l = exact ? exact->light : glm::dvec4(light);
    set(p, "u_view_proj", at(f.view_proj, c.origin));
    set(p, "u_light", local_light(c, l));
    glBindTextureUnit(2, exact ? GLuint(exact->planes) : GLuint(c.sv_planes));
    if (zfail) {  // back faces increment, front faces decrement where the depth test fails
      glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
      glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
    } else {  // front faces increment, back faces decrement where it passes
      glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
      glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    }
    set(p, "u_caps", 0);
    glBindVertexArray(exact ? GLuint(exact->sides_vao) : GLuint(c.sides_vao));
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, exact ? exact->side_count : c.side_count);
    if (zfail) {
      set(p, "u_caps", 1);
      glBindVertexArray(exact ? GLuint(exact->caps_vao) : GLuint(c.caps_vao));
      glDrawArraysInstanced(GL_TRIANGLES, 0, 6, exact ? exact->cap_count : c.cap_count);
    }
  }
  glDisable(GL_DEPTH_CLAMP);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  f.timer.end();
  return true;
}

}  // namespace

bool volume_shade(Frame& f, GLuint p) {
  const State& s = f.s;
  // 1. depth and the unlit colour. The scene is pulled a little towards the
  //    camera (004: polygon offset) so that volume faces lying on a surface
  //    (the near cap of a lit face, side quads at its edges) count as behind
  //    it: a point is never shadowed by the face it lies on.
  f.timer.begin("depth + ambient");
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(0.0f, -8.0f);
  set(p, "u_ambient_only", 1);
  draw_scene(s);
  f.timer.end();
  // 2. stencil counts.
  const float near_half_h = f.view.near_plane * std::tan(glm::radians(f.view.fovy_deg) * 0.5f);
  const float near_radius = near_half_h * std::sqrt(1.0f + f.aspect * f.aspect);
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (!volume_pass(f, near_radius)) return false;
  // 3. lit where the count is zero.
  f.timer.begin("lit shading");
  glEnable(GL_POLYGON_OFFSET_FILL);  // the same offset as pass 1: GL_EQUAL holds
  glUseProgram(p);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glDepthFunc(GL_EQUAL);
  set(p, "u_ambient_only", 0);
  draw_scene(s);
  glDepthFunc(GL_LESS);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  f.timer.end();
  return true;
}

}  // namespace render
