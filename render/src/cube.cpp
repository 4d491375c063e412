// cube.cpp: the omnidirectional shadow map of a point or spot light
// (Gerasimov 2004, Sect. 12.3-12.4): an R32F cube of squared distances and a cube depth buffer
// for the z-test, all six faces rendered in one layered pass
// (shaders/cube_distance.*); the lookup is shaders/lookup_cube.frag. The
// distances carry a slope-scaled bias in the light's own distance units
// (kCubeSlope texels of slope) instead of Gerasimov's multiplicative one,
// which hides a fixed share of the distance at every size.
// Measured (geombench, 640x480, error_visible in % at 512 / 1024 / 2048 / 4096;
// in brackets the 3% multiplicative bias): near-plane 0.177 / 0.107 / 0.072 /
// 0.038 (0.148 / 0.168 / 0.183 / 0.195); heavy error_self 0.40 / 0.10 / 0.053
// / 0.026 (0.56 / 0.15 / 0.084 / 0.085); slope factors 1.5 and 4 were worse
// (acne on pipes and behind at 1.5, 1.4x near-plane's error at 4).
#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "state.h"

namespace render {
namespace {

// The cube pass's slope-scaled bias in texels of distance slope
// (shaders/cube_distance.frag): the lookup's four taps reach about 1.6 texels
// to the side of the sample (sqrt(3) / N in direction), and the nearest texel
// half a diagonal more; a receiver's own stored surface there must not be in
// front of it.
constexpr float kCubeSlope = 2.5f;

void ensure_cube(State& s, int n) {
  Target& t = s.cube;
  if (t.width == n) return;
  t = Target();
  t.width = t.height = n;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &t.color.id);
  glTextureStorage2D(t.color, 1, GL_R32F, n, n);
  glTextureParameteri(t.color, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.color, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  label(GL_TEXTURE, t.color, "cube squared distance");
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, n, n);
  label(GL_TEXTURE, t.depth, "cube depth");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.color, 0);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  label(GL_FRAMEBUFFER, t.fbo, "cube map");
}

}  // namespace

bool cube_passes(Frame& f) {
  State& s = f.s;
  const int n = f.n;
  if (f.light.position.w == 0) {
    f.error = "technique cube needs a point or spot light (--light X,Y,Z,1)";
    return false;
  }
  ensure_cube(s, n);
  const glm::vec3 L(f.light.position);
  const float d = glm::length(glm::vec3(s.bounds) - L), r = s.bounds.w;
  const float near_plane = std::max(r * 1e-3f, (d - r) * 0.5f), far_plane = (d + r) * 1.01f;
  // The six faces, GL order +X -X +Y -Y +Z -Z (geom/focus.h, Gerasimov 2004).
  const double position[3] = {L.x, L.y, L.z};
  double faces[6][16];
  geom::focus_cube_faces(position, near_plane, far_plane, faces);
  GLuint p = program(s.programs, {"cube_distance.vert", "cube_distance.geom", "cube_distance.frag"}, f.error);
  if (!p) return false;
  for (int i = 0; i < 6; ++i) {
    const std::string name = "u_face[" + std::to_string(i) + "]";
    set(p, name.c_str(), at(glm::make_mat4(faces[i]), s.origin));
  }
  set(p, "u_light_position", glm::vec3(glm::dvec3(L) - s.origin));
  set(p, "u_slope", kCubeSlope);
  f.timer.begin("cube map");
  glBindFramebuffer(GL_FRAMEBUFFER, s.cube.fbo);
  glViewport(0, 0, n, n);
  const float far_value = 3.0e38f;
  glClearNamedFramebufferfv(s.cube.fbo, GL_COLOR, 0, &far_value);
  glClear(GL_DEPTH_BUFFER_BIT);
  glUseProgram(p);
  draw_scene(s);
  f.timer.end();
  f.shadow_texture = s.cube.color;
  f.lookup = "lookup_cube.frag";
  f.projection = "cube map";
  return true;
}

}  // namespace render
