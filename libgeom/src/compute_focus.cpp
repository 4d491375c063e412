// compute_focus.cpp: the per-frame computation of geom/focus.h: the light's
// kind in the camera's post-perspective space (Stamminger and
// Drettakis 2002, Sect. 3), R = V n S n L and H = conv(R u {l}) n S n L (Sect. 4.1) by the
// steps of focus_body.h and focus_frame.h, H's faces, and the matrix of the
// requested method (light_matrix.cpp), with the fallbacks geom/focus.h lists.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "focus_body.h"
#include "focus_frame.h"
#include "geom/focus.h"

namespace geom {

using namespace focus;

const char* focus_method_name(FocusMethod m) {
  return m == FocusMethod::Psm ? "psm" : m == FocusMethod::Lispsm ? "lispsm" : "uniform";
}
const char* light_kind_name(LightKind k) {
  return k == LightKind::Point ? "point" : k == LightKind::InvertedPoint ? "inverted_point" : "directional";
}
const char* focus_fallback_name(FocusFallback f) {
  switch (f) {
    case FocusFallback::None:
      return "none";
    case FocusFallback::NearLimited:
      return "near_limited";
    case FocusFallback::WarpNoGain:
      return "warp_no_gain";
    case FocusFallback::ParallelLight:
      return "parallel_light";
    case FocusFallback::LightTooClose:
      return "light_too_close";
    case FocusFallback::OrthographicCamera:
      return "orthographic_camera";
    case FocusFallback::LightInsideView:
      return "light_inside_view";
    case FocusFallback::DegenerateScene:
      return "degenerate_scene";
    case FocusFallback::EmptyFocus:
      return "empty_focus";
    case FocusFallback::InvalidInput:
      return "invalid_input";
  }
  return "unknown";
}

// R's candidate planes (V's faces and the receiver bounds) into fr.v_planes,
// and S's corners in frustum_polytope's order into `box`.
static void view_and_box(Frame& fr, const V3 corners[8], V3 box[8]) {
  fr.v_planes.clear();
  V3 vc(0, 0, 0);
  for (int i = 0; i < 8; ++i) vc = vc + corners[i] * 0.125;
  static const int face_corners[6][3] = {{0, 1, 2}, {4, 6, 5}, {0, 3, 7}, {1, 5, 6}, {0, 4, 5}, {3, 2, 6}};
  for (const auto& f : face_corners) {
    V3 n = cross(corners[f[1]] - corners[f[0]], corners[f[2]] - corners[f[0]]);
    if (!(length(n) > 0)) continue;
    Plane p = plane_through(corners[f[0]], normalize(n));
    if (p.eval(vc) < 0) p = {-p.n, -p.d};
    fr.v_planes.push_back(p);
  }
  fr.v_planes.insert(fr.v_planes.end(), fr.r_planes.begin(), fr.r_planes.end());
  scene_corners(fr, box);
}

// Nothing visible to shadow: a finite matrix over S n L (or S) all the same.
static void empty_focus(Frame& fr, const Light& light, FocusResult& out) {
  set_fallback(out, FocusFallback::EmptyFocus,
               "the focus body is empty: no visible point lies in the scene bounds and the light's frustum");
  V3 c[8];
  scene_corners(fr, c);
  Polytope box;
  frustum_polytope(c, box);
  if (light.type == LightType::Spot && fr.receivers.empty())  // no receiver set the near plane's floor
    fr.l_planes.push_back(plane_through(fr.light_pos + fr.light_axis * fr.light_near, fr.light_axis));
  Polytope lit = box;
  clip_polytope(lit, fr.l_planes.data(), fr.l_planes.size(), fr.eps, fr.scratch);
  V3 axis_before = fr.light_axis;
  if (!fr.directional && light.type == LightType::Point) fr.light_axis = fr.view_dir;
  unique_vertices(lit.empty() ? box : lit, fr.eps, fr.h_verts);
  M4 m;
  bool ok = !lit.empty() && uniform_matrix(fr, m);
  if (!ok) {  // the light's side of S: an orthographic view of S along the light's axis
    V3 axis = fr.directional ? -fr.towards_light : fr.light_axis;
    unique_vertices(box, fr.eps, fr.h_verts);
    ok = fit(axis_frame(fr.eye, axis, fr.view_dir), fr.h_verts, false, m);
  }
  if (ok) std::copy(m.m, m.m + 16, out.matrix);
  fr.h_verts.clear();
  fr.light_axis = axis_before;
}

// The light's kind in the real camera's post-perspective space (Sect. 3).
static LightKind post_perspective_kind(const Frame& fr) {
  if (!fr.perspective) return fr.directional ? LightKind::Directional : LightKind::Point;
  double w = fr.directional ? dot(fr.towards_light, fr.view_dir) : depth_of(fr, fr.light_pos);
  double size = fr.directional ? 1.0 : length(fr.light_pos - fr.eye) + fr.scale;
  return std::fabs(w) <= 1e-9 * size ? LightKind::Directional : w > 0 ? LightKind::Point : LightKind::InvertedPoint;
}

// R = V n S n L (n receiver bounds) into fr.receivers and its vertices into
// fr.r_verts; a point or spot light's near plane placed with it.
static void receiver_region(Frame& fr, const Light& light, const FocusOptions& options, FocusResult& out) {
  V3 corners[8];
  if (view_frustum(fr, corners)) {
    view_and_box(fr, corners, fr.box);
    if (fr.s_hull) {  // S's body cut by V's faces (v_planes before the receiver bounds)
      fr.receivers = fr.s_body;
      clip_polytope(fr.receivers, fr.v_planes.data(), fr.v_planes.size() - fr.r_planes.size(), fr.eps, fr.scratch);
    } else {
      frustum_polytope(corners, fr.receivers);
      clip_polytope(fr.receivers, fr.s_planes.data(), fr.s_planes.size(), fr.eps, fr.scratch);
    }
    clip_polytope(fr.receivers, fr.l_planes.data(), fr.l_planes.size(), fr.eps, fr.scratch);
    clip_polytope(fr.receivers, fr.r_planes.data(), fr.r_planes.size(), fr.eps, fr.scratch);
  } else {
    fr.receivers.clear();
  }
  // A point light's cube faces start from R before L's near plane cuts it.
  fr.all_receivers = fr.receivers;
  fr.range_planes = fr.l_planes.size();
  if (!fr.directional && !fr.receivers.empty()) near_plane_cut(fr, light, options, out);
  unique_vertices(fr.receivers, fr.eps, fr.r_verts);
}

// H = conv(R u {l}) n S n L into fr.body (empty when R is).
static void focus_body(Frame& fr, StageTimes* times) {
  if (fr.receivers.empty()) {
    fr.body.clear();
    return;
  }
  double reach = -HUGE_VAL;
  if (fr.directional)
    for (int i = 0; i < 8; ++i) reach = std::fmax(reach, dot(fr.box[i], fr.towards_light));
  std::vector<Plane>& clip = fr.hull_clip;
  clip.assign(fr.s_planes.begin(), fr.s_planes.end());
  clip.insert(clip.end(), fr.l_planes.begin(), fr.l_planes.end());
  const V3 light = fr.directional ? fr.towards_light : fr.light_pos;
  const V3 axis = fr.directional ? fr.towards_light : fr.light_axis;
  // With S's body as the start, only L's planes are left to clip by.
  const size_t skip = fr.s_hull ? fr.s_planes.size() : 0;
  if (!focus_by_planes(fr.r_verts, light, fr.directional, axis, fr.v_planes.data(), fr.v_planes.size(),
                       clip.data() + skip, clip.size() - skip, fr.box, fr.eps, fr.hull_clip_planes, fr.body, fr.scratch,
                       times, fr.s_hull ? &fr.s_body : nullptr))
    focus_hull(fr.receivers, light, fr.directional, reach, clip.data(), clip.size(), fr.eps, fr.hull_points, fr.body,
               fr.scratch, times);
}

// H for the caller (its faces, or its vertices alone), fr.h_verts its extreme
// points, and for a point or spot light the map's near plane: H's nearest
// point (at the floor H was cut there: casters next to the light, or
// receivers, and the result says so) and the cone H needs from the light.
static void body_output(Frame& fr, const FocusOptions& options, FocusResult& out) {
  if (options.faces) {
    index_polytope(fr.body, fr.eps, out.vertices, out.face_sizes, out.face_indices);
  } else {
    for (V3 p : fr.h_verts) out.vertices.insert(out.vertices.end(), {p.x, p.y, p.z});
  }
  if (options.faces && out.vertices.size() >= 12) {  // the hull's vertices: extreme points only
    fr.h_verts.clear();
    for (size_t i = 0; i + 2 < out.vertices.size(); i += 3)
      fr.h_verts.push_back(V3(out.vertices[i], out.vertices[i + 1], out.vertices[i + 2]));
  }
  if (fr.directional) return;
  for (int k = 0; k < 3; ++k) out.light_axis[k] = fr.light_axis[k];
  double nearest = HUGE_VAL;
  for (V3 p : fr.h_verts) {
    V3 d = p - fr.light_pos;
    nearest = std::fmin(nearest, dot(d, fr.light_axis));
    if (length(d) > fr.eps) fr.cone_cos = std::fmin(fr.cone_cos, dot(d, fr.light_axis) / length(d));
  }
  out.light_near = std::fmax(nearest, fr.light_near);
  if (nearest <= fr.light_near + 4 * fr.eps) out.near_floor_cut = true;
}

// The single-frustum computation (H, the light's kind, the matrix) into `out`,
// which compute_focus has reset. False for invalid input.
static bool single_focus(const CameraMatrices& camera, const Light& light, const FocusBox& scene,
                         const FocusOptions& options, Frame& fr, FocusResult& out) {
  StageTimes* times = options.stage_times;
  using Clock = std::chrono::steady_clock;
  Clock::time_point mark = times ? Clock::now() : Clock::time_point();
  // Adds the time since the last mark to `slot`.
  auto lap = [&](double StageTimes::*slot) {
    if (!times) return;
    Clock::time_point now = Clock::now();
    times->*slot += std::chrono::duration<double>(now - mark).count();
    mark = now;
  };
  if (!setup(camera, light, scene, options, fr, out)) {
    out.fallback = FocusFallback::InvalidInput;
    return false;
  }
  out.light_kind = out.psm_light_kind = post_perspective_kind(fr);
  lap(&StageTimes::setup);
  receiver_region(fr, light, options, out);
  lap(&StageTimes::receivers);
  focus_body(fr, times);
  if (times) mark = Clock::now();  // focus_body timed itself
  unique_vertices(fr.body, fr.eps, fr.h_verts);
  fr.cone_cos = 1;
  if (fr.h_verts.empty() || fr.r_verts.empty()) {
    empty_focus(fr, light, out);
    return true;
  }
  body_output(fr, options, out);
  lap(&StageTimes::faces);
  M4 m;
  if (method_matrix(fr, options, out, m)) std::copy(m.m, m.m + 16, out.matrix);
  lap(&StageTimes::matrix);
  return true;
}

bool compute_focus(const CameraMatrices& camera, const Light& light, const FocusBox& scene, const FocusOptions& options,
                   FocusResult& out) {
  M4 id = M4::identity();
  std::copy(id.m, id.m + 16, out.matrix);
  out.method = FocusMethod::Uniform;
  out.fallback = FocusFallback::None;
  out.reason = "";
  out.light_kind = out.psm_light_kind = LightKind::Directional;
  out.needs_cube_map = out.near_floor_cut = out.cube = false;
  out.camera_shift = out.psm_near = out.psm_far = out.lispsm_n = out.light_near = 0;
  out.light_axis[0] = out.light_axis[1] = out.light_axis[2] = 0;
  out.vertices.clear();
  out.face_sizes.clear();
  out.face_indices.clear();
  for (FocusFace& f : out.cube_faces)
    f = FocusFace(), std::copy(id.m, id.m + 16, f.matrix), std::copy(id.m, id.m + 16, f.focused);
  try {
    thread_local Frame fr;
    if (!single_focus(camera, light, scene, options, fr, out)) return false;
    const double wide = options.cube_cone_degrees > 0 ? std::cos(0.5 * options.cube_cone_degrees * kPi / 180) : -2;
    if (light.type == LightType::Point && (out.needs_cube_map || fr.cone_cos < wide)) {
      using Clock = std::chrono::steady_clock;
      Clock::time_point t0 = options.stage_times ? Clock::now() : Clock::time_point();
      cube_focus(fr, options, out);
      if (options.stage_times) options.stage_times->cube += std::chrono::duration<double>(Clock::now() - t0).count();
    }
    return true;
  } catch (...) {  // allocation failure: never past the library boundary
    std::copy(id.m, id.m + 16, out.matrix);
    out.fallback = FocusFallback::InvalidInput;
    out.reason = "out of memory";
    out.cube = false;
    return false;
  }
}

}  // namespace geom
