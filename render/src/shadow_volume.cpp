// shadow_volume.cpp: stencil shadow volumes (Arneson; Kenzel 2013, Sect. 5;
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

// May some point of the camera's near-plane rectangle lie inside this
// caster's shadow volume? Depth-pass counts the volume faces from the near
// plane to the visible surface, so it is exact only where the count on the
// near plane is zero (Arneson, depth-pass vs depth-fail). A point p lies in
// the volume only if the segment from p to the light meets the caster, so
// every such point lies in the convex hull of the
// near rectangle and the light (for a directional light, the rectangle swept
// to infinity towards the light): the light may lie on either side of the
// near plane, or on it. The eye joins the rectangle (with GL_DEPTH_CLAMP the
// volume between the eye and the near plane is rasterized too). The test is
// the separating-axis test of that hull against the caster's box grown by a
// relative margin: the axes are the box's, the normals of every plane through
// three hull points (or two and the light's direction) and the cross products
// of the box's axes with every hull edge, which include the faces and edge
// pairs of both; an axis found separating proves the two disjoint, none found
// answers "may" (conservative).
bool near_rect_may_be_in_volume(const Caster& c, const glm::dvec3 (&hull)[6], int points, const glm::dvec4& light) {
  const glm::dvec3 lo(c.lo), hi(c.hi), centre = (lo + hi) * 0.5;
  double scale = glm::length(hi - lo);
  for (int i = 0; i < points; ++i) scale = std::max(scale, glm::length(hull[i] - centre));
  const glm::dvec3 half = (hi - lo) * 0.5 + glm::dvec3(1e-6 * scale);
  const bool infinite = light.w == 0;
  const glm::dvec3 d(light);  // towards a directional light
  auto separates = [&](const glm::dvec3& a) {
    const double len = glm::length(a);
    if (!(len > 1e-300)) return false;
    const double b = glm::dot(centre, a), r = glm::dot(half, glm::abs(a));
    double h0 = glm::dot(hull[0], a), h1 = h0;
    for (int i = 1; i < points; ++i) h0 = std::min(h0, glm::dot(hull[i], a)), h1 = std::max(h1, glm::dot(hull[i], a));
    if (infinite) {
      const double s = glm::dot(d, a);
      if (s > 0) h1 = INFINITY;
      if (s < 0) h0 = -INFINITY;
    }
    return h1 < b - r || h0 > b + r;
  };
  const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const glm::dvec3& a : axes)
    if (separates(a)) return false;
  for (int i = 0; i < points; ++i)
    for (int j = i + 1; j < points; ++j) {
      const glm::dvec3 e = hull[j] - hull[i];
      for (const glm::dvec3& a : axes)
        if (separates(glm::cross(a, e))) return false;
      if (infinite && separates(glm::cross(e, d))) return false;
      for (int k = j + 1; k < points; ++k)
        if (separates(glm::cross(e, hull[k] - hull[i]))) return false;
    }
  if (infinite)
    for (const glm::dvec3& a : axes)
      if (separates(glm::cross(a, d))) return false;
  return true;
}

// The points whose hull holds every near-plane point's segment to the light:
// the eye, the near rectangle's corners and a point light (world, double).
int near_hull(const Frame& f, glm::dvec3 (&hull)[6]) {
  const glm::dvec3 eye(f.view.eye), forward = glm::normalize(glm::dvec3(f.view.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(f.view.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double n = f.view.near_plane, h = n * std::tan(glm::radians(double(f.view.fovy_deg)) * 0.5);
  const double w = h * double(f.aspect);
  hull[0] = eye;
  for (int k = 0; k < 4; ++k) hull[1 + k] = eye + forward * n + right * (k & 1 ? w : -w) + up * (k & 2 ? h : -h);
  const glm::dvec4 l(f.light.position);
  if (l.w == 0) return 5;
  hull[5] = glm::dvec3(l) / l.w;
  return 6;
}

// The stencil counts of every caster's volume.
bool volume_pass(Frame& f) {
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
  glm::dvec3 hull[6];
  const int hull_points = near_hull(f, hull);
  for (const Caster& c : s.casters) {
    const bool zfail = f.t == Technique::SvZFail ||
                       (f.t == Technique::Sv && near_rect_may_be_in_volume(c, hull, hull_points, glm::dvec4(light)));
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
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (!volume_pass(f)) return false;
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
