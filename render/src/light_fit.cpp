// light_fit.cpp: the light frustum of the single-map techniques (ssm, pcf, esm,
// edsm), fitted to what the camera sees (issue 18): geom/focus.h's body H
// (every point that can cast a shadow onto a visible receiver) and its uniform
// focused matrix (no warp), whose depth range starts at H's nearest point. A
// point light whose receivers need more than one frustum can cover well (H
// wider than kMaxConeDeg from the light, or receivers behind the light:
// FocusResult::needs_cube_map) is drawn as cube faces by the caller.
#include <cmath>

#include "state.h"

namespace render {
namespace {

constexpr double kMaxConeDeg = 120;  // full angle of the widest single frustum worth drawing

glm::mat4 to_mat4(const double m[16]) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = float(m[c * 4 + r]);
  return out;
}

}  // namespace

bool fitted_light_frame(Frame& f, LightFrame& out) {
  f.timer.begin("focus (CPU)");
  const geom::FocusResult r = focus(f.s, f.view, f.aspect, f.light, geom::FocusMethod::Uniform);
  f.timer.end();
  if (r.fallback == geom::FocusFallback::InvalidInput) {
    out = light_frame(f.s, f.light);  // the scene-wide frustum
    return true;
  }
  if (r.needs_cube_map) return false;
  if (f.light.position.w != 0 && !f.light.spot) {  // the cone H needs from the light
    const glm::dvec3 L(glm::vec3(f.light.position)), axis(r.light_axis[0], r.light_axis[1], r.light_axis[2]);
    double min_cos = 1;
    for (size_t i = 0; i + 2 < r.vertices.size(); i += 3) {
      const glm::dvec3 d = glm::dvec3(r.vertices[i], r.vertices[i + 1], r.vertices[i + 2]) - L;
      const double len = glm::length(d);
      if (len > 1e-9 * (1 + glm::length(L))) min_cos = std::min(min_cos, glm::dot(d, axis) / len);
    }
    if (min_cos < std::cos(kMaxConeDeg * 0.5 * M_PI / 180)) return false;
  }
  out.proj = to_mat4(r.matrix), out.view = glm::mat4(1);
  return true;
}

float projection_scale(const glm::mat4& clip) {
  const float sx = glm::length(glm::vec3(clip[0][0], clip[1][0], clip[2][0]));
  const float sy = glm::length(glm::vec3(clip[0][1], clip[1][1], clip[2][1]));
  return std::max(std::min(sx, sy), 1e-30f);
}

}  // namespace render
