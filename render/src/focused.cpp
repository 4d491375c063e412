// focused.cpp: the focused shadow maps psm (seed 002), lispsm (Wimmer et al.
// 2004) and uniform: the light matrix of geom/focus.h computed per frame for
// the map's x and y, and a linear light depth with its own bias
// (shaders/light_depth.frag, depth_linear.frag, lookup_focused.frag). A point
// light among the receivers cannot be covered by one map: an engine renders a
// cube map for it instead (FocusResult::needs_cube_map), and so does this.
#include "state.h"

namespace render {
namespace {

glm::mat4 to_mat4(const double m[16]) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = float(m[c * 4 + r]);
  return out;
}

geom::FocusMethod method_of(Technique t) {
  return t == Technique::Psm      ? geom::FocusMethod::Psm
         : t == Technique::Lispsm ? geom::FocusMethod::Lispsm
                                  : geom::FocusMethod::Uniform;
}

}  // namespace

geom::FocusResult focus(const State& s, const View& view, float aspect, const FrameLight& light,
                        geom::FocusMethod method, bool faces) {
  const double eye[3] = {view.eye.x, view.eye.y, view.eye.z}, target[3] = {view.target.x, view.target.y, view.target.z},
               up[3] = {view.up.x, view.up.y, view.up.z};
  const geom::CameraMatrices camera =
      geom::camera_look_at(eye, target, up, view.fovy_deg, aspect, view.near_plane, view.far_plane);
  // The frame's light as the passes see it (floats); no range (the shading has none).
  geom::Light l;
  const glm::vec3 L(light.position);
  if (light.position.w == 0) {
    l.type = geom::LightType::Directional;
    for (int k = 0; k < 3; ++k) l.direction[k] = -L[k];
  } else {
    l.type = light.spot ? geom::LightType::Spot : geom::LightType::Point;
    for (int k = 0; k < 3; ++k) l.position[k] = L[k], l.direction[k] = light.spot_direction[k];
    l.outer_cone = light.spot_angle;
  }
  geom::FocusBox box;
  for (int k = 0; k < 3; ++k) box.min[k] = s.scene_lo[k], box.max[k] = s.scene_hi[k];
  geom::FocusOptions options;
  options.method = method;
  options.faces = faces;  // H's faces only for the inspection wireframe
  geom::FocusResult result;
  geom::compute_focus(camera, l, box, options, result);
  return result;
}

bool focused_passes(Frame& f) {
  f.focused = true;
  f.timer.begin("focus (CPU)");
  const geom::FocusResult r = focus(f.s, f.view, f.aspect, f.light, method_of(f.t));
  f.timer.end();
  if (r.needs_cube_map) {
    f.t = Technique::Cube;  // the pass is then named "cube map (...)"
    return cube_passes(f);
  }
  f.light_frame.proj = to_mat4(r.matrix), f.light_frame.view = glm::mat4(1);
  if (!depth_map_pass(f, f.light_frame.clip(), 3.0f, true)) return false;  // bilinear lookup: 2 texels
  finish_map(f);
  f.lookup = "lookup_focused.frag";
  return true;
}

}  // namespace render
