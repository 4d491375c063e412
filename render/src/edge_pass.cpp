// edge_pass.cpp: the edge pass of the silhouette-map techniques (edge_pass.h).
#include "edge_pass.h"

#include <type_traits>

namespace render {
namespace {

// s.edge_map's colour (n x n, `format`) set to `value`: copied from a texture
// cleared once to it (s.edge_blank). A software rasterizer (Mesa's llvmpipe)
// clears 8- and 16-byte texels one memcpy per texel (the default scene at 1024:
// 36 of edsm's 97 ms of shadow-pass CPU time); the copy moves whole rows, the
// same bytes. On a GPU the clear itself is cheaper.
template <class T>
void clear_colour(Frame& f, const T (&value)[4]) {
  State& s = f.s;
  const GLenum format = GLenum(s.edge_map.height);  // ensure_edge_map keeps the format there
  if (s.gpu_timers) {
    if constexpr (std::is_same_v<T, GLuint>)
      glClearNamedFramebufferuiv(s.edge_map.fbo, GL_COLOR, 0, value);
    else
      glClearNamedFramebufferfv(s.edge_map.fbo, GL_COLOR, 0, value);
    return;
  }
  if (!s.edge_blank || s.edge_blank_n != f.n || s.edge_blank_format != format) {
    s.edge_blank = Texture();
    glCreateTextures(GL_TEXTURE_2D, 1, &s.edge_blank.id);
    glTextureStorage2D(s.edge_blank, 1, format, f.n, f.n);
    label(GL_TEXTURE, s.edge_blank, "edge map clear value");
    s.edge_blank_n = f.n, s.edge_blank_format = format;
    const bool two = format == GL_RG32F || format == GL_RG32UI;
    if constexpr (std::is_same_v<T, GLuint>)
      glClearTexImage(s.edge_blank, 0, two ? GL_RG_INTEGER : GL_RGBA_INTEGER, GL_UNSIGNED_INT, value);
    else
      glClearTexImage(s.edge_blank, 0, two ? GL_RG : GL_RGBA, GL_FLOAT, value);
  }
  glCopyImageSubData(s.edge_blank, GL_TEXTURE_2D, 0, 0, 0, 0, s.edge_map.color, GL_TEXTURE_2D, 0, 0, 0, 0, f.n, f.n, 1);
}

}  // namespace

GLuint edge_program(Frame& f, const glm::mat4& light_clip, float slope, GLenum format,
                    const std::vector<std::string>& files) {
  if (!depth_map_pass(f, light_clip, slope, false)) return 0;
  ensure_edge_map(f.s, f.n, format);
  GLuint p = program(f.s.programs, files, f.error);
  if (!p) return 0;
  set(p, "u_map_size", float(f.n));
  set(p, "u_depth", 1);
  return p;
}

void begin_edge_pass(Frame& f, GLuint p, const char* label, EdgeTarget target) {
  State& s = f.s;
  f.timer.begin(label);
  glBindFramebuffer(GL_FRAMEBUFFER, s.edge_map.fbo);
  glViewport(0, 0, f.n, f.n);
  switch (target) {
    case EdgeTarget::Distance: {
      const float none[4] = {3.0e38f, 0, 0, 0};
      clear_colour(f, none);
      glClear(GL_DEPTH_BUFFER_BIT);
      break;
    }
    case EdgeTarget::EdgePair: {
      const GLuint none[4] = {0, 0xFFFFFFFFu, 0, 0xFFFFFFFFu};
      clear_colour(f, none);
      glClearDepth(1.0);
      glClear(GL_DEPTH_BUFFER_BIT);
      break;
    }
    case EdgeTarget::EdgeSecond:
      glClearDepth(1.0);
      glClear(GL_DEPTH_BUFFER_BIT);
      break;
    case EdgeTarget::Silhouette: {
      const GLuint centre[4] = {0, 0, 0, 0};  // the default point: the cell's centre; no edge depth
      clear_colour(f, centre);
      glClearDepth(1.0);
      glClear(GL_DEPTH_BUFFER_BIT);
      break;
    }
    case EdgeTarget::ExtendedMax: {
      const float zero[4] = {0, 0, 0, 0};
      clear_colour(f, zero);
      glDisable(GL_DEPTH_TEST);
      glEnable(GL_BLEND);
      glBlendEquation(GL_MAX);  // 000 Sect. 4.1: MAX of the inverted distance and of the edge depth
      break;
    }
  }
  glBindTextureUnit(1, s.shadow_map.depth);
  glBindSampler(1, depth_sampler(s));
  glUseProgram(p);
}

void end_edge_pass(Frame& f, EdgeTarget target) {
  if (target == EdgeTarget::ExtendedMax) {
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
  }
  glBindSampler(1, 0);
  f.timer.end();
}

void draw_adjacency(const State& s) {
  for (const Caster& c : s.casters) {
    glBindVertexArray(c.adjacency_vao);
    glDrawElements(GL_TRIANGLES_ADJACENCY, c.adjacency_count, GL_UNSIGNED_INT, nullptr);
  }
}

void adjacency_edge_pass(Frame& f, GLuint p, const char* label, EdgeTarget target) {
  begin_edge_pass(f, p, label, target);
  draw_adjacency(f.s);
  end_edge_pass(f, target);
}

void draw_esm_quads(Frame& f, GLuint p, const glm::mat4& light_clip, int planes_unit) {
  set(p, "u_planes", planes_unit);
  for (const Caster& c : f.s.casters) {
    set(p, "u_light_view_proj", at(glm::dmat4(light_clip), c.origin));
    set(p, "u_light", local_light(c, glm::dvec4(f.light.position)));
    glBindTextureUnit(GLuint(planes_unit), c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
}

bool esm_quad_pass(Frame& f, const glm::mat4& light_clip, float slope, float texels, const std::string& frag) {
  GLuint p = edge_program(f, light_clip, slope, GL_RGBA32F, {"esm_quad.vert", frag});
  if (!p) return false;
  set(p, "u_extrude_scale", 2.0f * texels / (float(f.n) * projection_scale(light_clip)));
  set(p, "u_planes", 2);
  begin_edge_pass(f, p, "extended map quads", EdgeTarget::ExtendedMax);
  draw_esm_quads(f, p, light_clip);
  end_edge_pass(f, EdgeTarget::ExtendedMax);
  return true;
}

}  // namespace render
