// focused.cpp: the focused shadow maps psm (Stamminger and Drettakis 2002),
// lispsm (Wimmer et al. 2004) and uniform: the light matrix of geom/focus.h
// computed per frame for the map's x and y, and a linear light depth with a
// slope-scaled bias, its lookup testing the receiver's plane (shaders/light_depth.frag,
// depth_linear.frag, lookup_focused_faces.frag, depth_plane.frag).
// A point light among the receivers, or one whose receivers need a cone over
// kMaxConeDeg, cannot be covered well by one map: geom/focus.h fits six faces
// to it, each focused by the method as a spot light whose frustum is the
// face's pyramid (Stamminger and Drettakis 2002, Sect. 1: the ideas carry
// over to an omnidirectional light as several maps); they are drawn into a
// 2D array and looked up by shaders/lookup_focused_faces.frag.
#include <cstdio>

#include "state.h"

namespace render {
namespace {

geom::FocusMethod method_of(Technique t) {
  return t == Technique::Psm      ? geom::FocusMethod::Psm
         : t == Technique::Lispsm ? geom::FocusMethod::Lispsm
                                  : geom::FocusMethod::Uniform;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

// "psm near=0.8", "lispsm n=3.2", "uniform", "uniform (fallback: parallel_light)".
std::string describe(geom::FocusMethod requested, geom::FocusMethod used, geom::FocusFallback fallback, double psm_near,
                     double lispsm_n) {
  std::string out = geom::focus_method_name(used);
  if (used == geom::FocusMethod::Psm) out += " near=" + number(psm_near);
  if (used == geom::FocusMethod::Lispsm) out += " n=" + number(lispsm_n);
  if (fallback != geom::FocusFallback::None && fallback != geom::FocusFallback::LightInsideView)
    out += std::string(used != requested ? " (fallback: " : " (") + geom::focus_fallback_name(fallback) + ")";
  return out;
}

// "6 faces: lispsm x4 + uniform x2 (1 empty)" (no comma: a CSV field as it is).
std::string describe_faces(const geom::FocusResult& r) {
  int count[3] = {0, 0, 0}, empty = 0;
  for (const geom::FocusFace& face : r.cube_faces) face.empty ? ++empty : ++count[int(face.method)];
  std::string out = "6 faces:";
  const char* sep = " ";
  for (int m = 0; m < 3; ++m)
    if (count[m]) {
      out += sep + std::string(geom::focus_method_name(geom::FocusMethod(m))) + " x" + std::to_string(count[m]);
      sep = " + ";
    }
  if (empty) out += " (" + std::to_string(empty) + " empty)";
  return out;
}

}  // namespace

std::string describe_focus(geom::FocusMethod requested, const geom::FocusResult& r) {
  return describe(requested, r.method, r.fallback, r.psm_near, r.lispsm_n);
}

geom::FocusResult focus(const State& s, const View& view, float aspect, const FrameLight& light,
                        geom::FocusMethod method, bool faces, double cube_cone) {
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
  options.cube_cone_degrees = cube_cone;
  geom::FocusResult result;
  geom::compute_focus(camera, l, box, options, result);
  return result;
}

bool focused_passes(Frame& f) {
  f.focused = true;
  const geom::FocusMethod method = method_of(f.t);
  f.timer.begin("focus (CPU)");
  const geom::FocusResult r = focus(f.s, f.view, f.aspect, f.light, method, false, kMaxConeDeg);
  f.timer.end();
  if (r.cube) {
    bool first = true;
    for (int i = 0; i < 6; ++i) {
      const geom::FocusFace& face = r.cube_faces[i];
      f.face_clip[i] = face.empty ? glm::mat4(0.0f) : to_mat4(face.focused);
      if (!face.empty && first) f.light_frame.proj = f.face_clip[i], f.light_frame.view = glm::mat4(1), first = false;
    }
    if (!depth_faces(f, 6, 3.0f, true)) return false;
    f.lookup = "lookup_focused_faces.frag";
    f.projection = describe_faces(r);
    return true;
  }
  f.light_frame.proj = to_mat4(r.matrix), f.light_frame.view = glm::mat4(1);
  f.face_clip[0] = f.light_frame.clip();
  if (!depth_faces(f, 1, 3.0f, true)) return false;
  f.lookup = "lookup_focused_faces.frag";
  f.projection = describe_focus(method, r);
  return true;
}

}  // namespace render
