// light_fit.cpp: the light frames of the single-map techniques (ssm, pcf,
// esm, edsm, sssm, esm-soft), fitted to what the camera sees: geom/focus.h's
// focus body H (every point that can cast a shadow onto a visible receiver)
// and its uniform focused matrix (no warp); edsm-lispsm's is LiSPSM's warp of
// the same H (Wimmer et al. 2004), uniform where geom/focus.h finds no warp
// that helps. A point light whose receivers
// need more than one frustum can cover well (H wider than kMaxConeDeg from
// the light, or receivers beside and behind it: FocusResult::needs_cube_map)
// gets six 90-degree faces instead, each with the near and far planes that
// geom/focus.h fits to its part of H (Gerasimov 2004, Sect. 12.3.3), widened
// by a guard band of a few texels so that filter taps and edge quads near a
// seam stay inside the face (silhouette_faces.cpp).
#include <cmath>

#include "state.h"

namespace render {

glm::mat4 to_mat4(const double m[16]) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = float(m[c * 4 + r]);
  return out;
}

int fit_light_frames(Frame& f, float guard) {
  f.timer.begin("focus (CPU)");
  const geom::FocusMethod method =
      f.t == Technique::EdsmLispsm ? geom::FocusMethod::Lispsm : geom::FocusMethod::Uniform;
  const geom::FocusResult r = focus(f.s, f.view, f.aspect, f.light, method, false, kMaxConeDeg);
  f.timer.end();
  if (r.fallback == geom::FocusFallback::InvalidInput) {
    f.light_frame = light_frame(f.s, f.light);  // the scene-wide frustum
    f.projection = "scene frustum (focus: invalid input)";
    return 1;
  }
  if (!r.cube) {
    f.light_frame.proj = to_mat4(r.matrix), f.light_frame.view = glm::mat4(1);
    f.projection = method == geom::FocusMethod::Uniform ? "fitted frustum" : describe_focus(method, r);
    return 1;
  }
  const float widen = 1.0f / (1.0f + 2.0f * guard / float(f.n));  // tan(fov / 2) = 1 + 2 guard / N
  int empty = 0;
  for (int i = 0; i < 6; ++i) {
    const geom::FocusFace& face = r.cube_faces[i];
    if (face.empty) {
      f.face_clip[i] = glm::mat4(0.0f);  // nothing to draw; a lookup there (none is) finds w = 0: lit
      ++empty;
      continue;
    }
    // The fitted depth range with room on both sides: a receiver on the far
    // plane (a floor under a light looking down) would meet z/w's coarsest
    // steps there, where its depth and the map's round apart (acne).
    double faces[6][16];
    const double position[3] = {f.light.position.x, f.light.position.y, f.light.position.z};
    geom::focus_cube_faces(position, face.near * 0.5, face.far * 2, faces);
    glm::mat4 m = to_mat4(faces[i]);
    for (int c = 0; c < 4; ++c) m[c][0] *= widen, m[c][1] *= widen;
    f.face_clip[i] = m;
  }
  for (int i = 5; i >= 0; --i)  // the soft techniques' reach reads a face's scale: a non-empty one
    if (!r.cube_faces[i].empty) f.light_frame.proj = f.face_clip[i], f.light_frame.view = glm::mat4(1);
  f.projection = empty ? "6 faces (" + std::to_string(empty) + " empty)" : "6 faces";
  return 6;
}

float projection_scale(const glm::mat4& clip) {
  const float sx = glm::length(glm::vec3(clip[0][0], clip[1][0], clip[2][0]));
  const float sy = glm::length(glm::vec3(clip[0][1], clip[1][1], clip[2][1]));
  return std::max(std::min(sx, sy), 1e-30f);
}

}  // namespace render
