// focus_frame.cpp: the inputs of one focus frame (geom/focus.h) as the focus
// body's steps take them (focus_frame.h): the inputs checked, the scene
// bounds S (and the casters' hull), the light frustum L, the view frustum V
// cut at S's far side, and L's near plane, placed with the receivers.
//
// References: Stamminger and Drettakis 2002,
// "Perspective Shadow Maps", Sect. 4.1 (H = conv(V u {l}) n S n L, here with
// the receiver region R = V n S n L in V's place).
#include "focus_frame.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace geom {
namespace focus {

static bool finite3(const double* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

static void box_planes(const double* lo, const double* hi, std::vector<Plane>& out) {
  for (int k = 0; k < 3; ++k) {
    V3 n(k == 0, k == 1, k == 2);
    out.push_back({n, -lo[k]});
    out.push_back({-n, hi[k]});
  }
}

// The camera: view and projection checked, near and far, eye and view direction.
static bool camera_setup(const CameraMatrices& cam, Frame& fr, FocusResult& out) {
  fr.view = M4::from(cam.view);
  fr.proj = M4::from(cam.projection);
  if (!finite(fr.view) || !finite(fr.proj) || !invert(fr.view, fr.view_inv)) {
    out.reason = "camera matrices are not finite or the view matrix is singular";
    return false;
  }
  const M4& p = fr.proj;
  if (p.at(3, 0) != 0 || p.at(3, 1) != 0 || p.at(0, 1) != 0 || p.at(1, 0) != 0 || p.at(2, 0) != 0 || p.at(2, 1) != 0) {
    out.reason = "the projection is not an OpenGL perspective or orthographic matrix";
    return false;
  }
  double a = p.at(2, 2), b = p.at(2, 3);
  if (p.at(3, 2) == -1 && p.at(3, 3) == 0) {
    fr.perspective = true;
    fr.cam_near = b / (a - 1);
    fr.cam_far = a == -1 ? HUGE_VAL : b / (a + 1);
  } else if (p.at(3, 2) == 0 && p.at(3, 3) == 1 && p.at(0, 2) == 0 && p.at(1, 2) == 0) {
    fr.perspective = false;
    fr.cam_near = (b + 1) / a;
    fr.cam_far = (b - 1) / a;
  } else {
    out.reason = "the projection is not an OpenGL perspective or orthographic matrix";
    return false;
  }
  if (!(fr.cam_near > 0 || (!fr.perspective && std::isfinite(fr.cam_near))) || !(fr.cam_far > fr.cam_near) ||
      p.at(0, 0) == 0 || p.at(1, 1) == 0) {
    out.reason = "the projection has no valid near / far planes (need 0 < near < far)";
    return false;
  }
  V4 e = mul(fr.view_inv, 0, 0, 0, 1), v = mul(fr.view_inv, 0, 0, -1, 0);
  fr.eye = V3(e.x, e.y, e.z);
  fr.view_dir = normalize(V3(v.x, v.y, v.z));
  return true;
}

// The light, the scene bounds and the options: finite and in range.
static bool inputs_valid(const Light& light, const FocusBox& box, const FocusOptions& opt, FocusResult& out) {
  if (!finite3(light.position) || !finite3(light.direction) || !std::isfinite(light.range) || light.range < 0 ||
      !std::isfinite(opt.light_near) || opt.light_near < 0 || !std::isfinite(light.outer_cone) ||
      (light.type == LightType::Spot && !(light.outer_cone > 0)) ||
      (light.type != LightType::Point && !(length(V3(light.direction)) > 0))) {
    out.reason = "the light has a non-finite or zero direction, position, range, near or angle";
    return false;
  }
  if (!finite3(box.min) || !finite3(box.max)) {
    out.reason = "the scene bounds are not finite";
    return false;
  }
  if (!(opt.psm_min_near_ratio >= 0 && opt.psm_min_near_ratio < 1) || !(opt.lispsm_n_scale > 0) ||
      !(opt.min_warp_gain >= 0 && opt.min_warp_gain <= 1) || !std::isfinite(opt.lispsm_n_scale) ||
      int(opt.method) > 2) {
    out.reason =
        "the options are out of range (psm_min_near_ratio in [0, 1), lispsm_n_scale > 0, min_warp_gain in [0, 1])";
    return false;
  }
  if (opt.receivers && (!finite3(opt.receivers->min) || !finite3(opt.receivers->max))) {
    out.reason = "the receiver bounds are not finite";
    return false;
  }
  return true;
}

// Scene bounds: swapped axes put right, zero extents inflated; the frame's
// scale and tolerance. Returns the box's diagonal.
static double scene_bounds(FocusBox& box, const Light& light, Frame& fr, FocusResult& out) {
  double ext = 0, mac = max_abs(fr.eye);
  bool swapped = false;
  for (int k = 0; k < 3; ++k) {
    if (box.min[k] > box.max[k]) std::swap(box.min[k], box.max[k]), swapped = true;
    ext = std::fmax(ext, box.max[k] - box.min[k]);
    mac = std::fmax(mac, std::fmax(std::fabs(box.min[k]), std::fabs(box.max[k])));
  }
  if (!fr.directional) mac = std::fmax(mac, max_abs(V3(light.position)));
  double min_ext = std::fmax(1e-6 * ext, 1e-9 * std::fmax(mac, 1.0));
  bool inflated = false;
  for (int k = 0; k < 3; ++k)
    if (box.max[k] - box.min[k] < min_ext) {
      double mid = 0.5 * (box.min[k] + box.max[k]);
      box.min[k] = mid - 0.5 * min_ext;
      box.max[k] = mid + 0.5 * min_ext;
      inflated = true;
    }
  if (swapped || inflated)
    set_fallback(out, FocusFallback::DegenerateScene,
                 swapped ? "the scene bounds have min > max on some axis: swapped"
                         : "the scene bounds have zero size on some axis: inflated to a minimal extent");
  ext = std::fmax(ext, min_ext);
  fr.scale = std::fmax(mac, ext);
  fr.eps = 1e-12 * mac + 1e-9 * ext;
  double diag = 0;
  for (int k = 0; k < 3; ++k) diag += (box.max[k] - box.min[k]) * (box.max[k] - box.min[k]);
  return std::sqrt(diag);
}

// S as a body: the box cut by the hull's planes (s_planes after the box's
// six). Static casters give the same planes frame after frame: the body of
// the last planes and tolerance is kept per thread and reused while they are
// equal, value for value (the same body the clips would make again).
static void s_body(Frame& fr) {
  thread_local std::vector<Plane> planes;
  thread_local double eps = -1;
  thread_local Polytope body;
  const auto same = [&](const Plane& a, const Plane& b) {
    return a.n.x == b.n.x && a.n.y == b.n.y && a.n.z == b.n.z && a.d == b.d;
  };
  if (eps == fr.eps && planes.size() == fr.s_planes.size() &&
      std::equal(planes.begin(), planes.end(), fr.s_planes.begin(), same)) {
    fr.s_body = body;
    return;
  }
  V3 corners[8];
  scene_corners(fr, corners);
  frustum_polytope(corners, fr.s_body);
  clip_polytope(fr.s_body, fr.s_planes.data() + 6, fr.s_planes.size() - 6, fr.eps, fr.scratch);
  planes = fr.s_planes;
  eps = fr.eps;
  body = fr.s_body;
}

// S: the box's planes, then the casters' hull (precomputed, or from the
// points); the receiver bounds' planes. False for a non-finite hull plane.
static bool scene_planes(const FocusBox& box, const FocusOptions& opt, Frame& fr, FocusResult& out) {
  fr.s_planes.clear();
  box_planes(box.min, box.max, fr.s_planes);
  fr.s_hull = false;
  if (opt.caster_hull.size() > 0) {
    for (size_t i = 0; i < opt.caster_hull.size(); ++i) {
      const FocusPlane& h = opt.caster_hull[i];
      Plane q{V3(h.n[0], h.n[1], h.n[2]), h.d};
      if (!finite(q.n) || !std::isfinite(q.d) || !(length(q.n) > 0)) {
        out.reason = "a caster hull plane is not finite or has no normal";
        return false;
      }
      fr.s_planes.push_back(q);
    }
  } else if (opt.casters.size() > 0) {
    thread_local std::vector<Plane> hull;
    if (hull_planes(opt.casters, hull))
      fr.s_planes.insert(fr.s_planes.end(), hull.begin(), hull.end());
    else
      set_fallback(out, FocusFallback::DegenerateScene,
                   "the casters span no volume (or hold a non-finite point): the scene box alone is S");
  }
  if (fr.s_planes.size() > 6) {
    s_body(fr);
    fr.s_hull = true;
  }
  fr.r_planes.clear();
  if (opt.receivers) {
    FocusBox rb = *opt.receivers;
    for (int k = 0; k < 3; ++k)
      if (rb.min[k] > rb.max[k]) std::swap(rb.min[k], rb.max[k]);
    box_planes(rb.min, rb.max, fr.r_planes);
  }
  return true;
}

// Light frustum L (the near half-space of a point light is added later).
static void light_frustum(const Light& light, const FocusOptions& opt, double diag, Frame& fr) {
  fr.l_planes.clear();
  fr.light_pos = V3(light.position);
  fr.light_near = opt.light_near > 0 ? opt.light_near : 1e-3 * diag;
  if (fr.directional) {
    fr.towards_light = -normalize(V3(light.direction));
    return;
  }
  if (light.range > 0) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = fr.light_pos[k] - light.range, hi[k] = fr.light_pos[k] + light.range;
    box_planes(lo, hi, fr.l_planes);
  }
  if (light.type == LightType::Spot) {
    V3 axis = normalize(V3(light.direction));
    fr.light_axis = axis;
    double angle = std::fmin(light.outer_cone, 89.9 * kPi / 180);
    double s = std::sin(angle), c = std::cos(angle);
    V3 b1 = any_perpendicular(axis), b2 = cross(axis, b1);
    for (V3 side : {b1, -b1, b2, -b2}) fr.l_planes.push_back(plane_through(fr.light_pos, axis * s - side * c));
    // L's near plane comes with the receivers (near_plane_cut), where its floor is known.
  }
}

bool setup(const CameraMatrices& cam, const Light& light, FocusBox box, const FocusOptions& opt, Frame& fr,
           FocusResult& out) {
  if (!camera_setup(cam, fr, out)) return false;
  fr.directional = light.type == LightType::Directional;
  if (!inputs_valid(light, box, opt, out)) return false;
  const double diag = scene_bounds(box, light, fr, out);
  if (!scene_planes(box, opt, fr, out)) return false;
  light_frustum(light, opt, diag, fr);
  return true;
}

bool view_frustum(const Frame& fr, V3 corners[8]) {
  double far_s = -HUGE_VAL;
  // The box planes are n.x + d >= 0 with n = +e_k (d = -lo) and -e_k (d = hi).
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = -fr.s_planes[2 * k].d, hi[k] = fr.s_planes[2 * k + 1].d;
  for (int i = 0; i < 8; ++i) {
    V3 s(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]);
    far_s = std::fmax(far_s, depth_of(fr, s));
  }
  double n = fr.cam_near, f = std::fmin(fr.cam_far, far_s + 4 * fr.eps);
  if (!(f > n)) return false;
  const M4& p = fr.proj;
  double depth[2] = {n, f};
  for (int i = 0; i < 8; ++i) {
    static const int sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    double d = depth[i / 4];
    double x, y;
    if (fr.perspective) {
      x = (sx[i % 4] + p.at(0, 2)) * d / p.at(0, 0);
      y = (sy[i % 4] + p.at(1, 2)) * d / p.at(1, 1);
    } else {
      x = (sx[i % 4] - p.at(0, 3)) / p.at(0, 0);
      y = (sy[i % 4] - p.at(1, 3)) / p.at(1, 1);
    }
    V4 w = mul(fr.view_inv, x, y, -d, 1);
    corners[i] = V3(w.x, w.y, w.z);
  }
  return true;
}

// L's near half-space, at the floor of the map's near plane (FocusOptions::
// light_near, or kNearFloor of the farthest receiver along the axis: depth
// precision), and R cut by it. A point light's axis points from the light to
// the receivers' centre. Receivers nearer than the floor (behind or beside a
// point light, or at a spot's apex) are cut and the result says so
// (near_floor_cut; a point light then needs its cube faces). H is cut by the
// same plane (L's half-spaces); the map's near plane is then H's nearest
// point (uniform_chain), the nearest that must be covered.
static constexpr double kNearFloor = 1e-3;

void near_plane_cut(Frame& fr, const Light& light, const FocusOptions& opt, FocusResult& out) {
  unique_vertices(fr.receivers, fr.eps, fr.r_verts);
  if (light.type == LightType::Point) {
    V3 c = box_centre(fr.r_verts);
    fr.light_axis = length(c - fr.light_pos) > fr.eps ? normalize(c - fr.light_pos) : fr.view_dir;
  }
  double nearest = HUGE_VAL, farthest = 0;
  for (V3 p : fr.r_verts) {
    double d = dot(p - fr.light_pos, fr.light_axis);
    nearest = std::fmin(nearest, d);
    farthest = std::fmax(farthest, d);
  }
  double floor = opt.light_near > 0 ? opt.light_near : kNearFloor * farthest;
  if (!(floor > fr.eps)) floor = fr.light_near;  // every receiver at or behind the light: the scene's scale
  fr.light_near = floor;
  if (nearest < floor - fr.eps) {
    out.near_floor_cut = true;
    if (light.type == LightType::Point) {
      out.needs_cube_map = true;
      set_fallback(out, FocusFallback::LightInsideView,
                   "the point light lies among or beside the receivers: one shadow map covers only the "
                   "half-space facing them; render its cube faces (focus_cube_faces)");
    }
  }
  Plane near_plane = plane_through(fr.light_pos + fr.light_axis * fr.light_near, fr.light_axis);
  fr.l_planes.push_back(near_plane);
  clip_polytope(fr.receivers, near_plane, fr.eps, fr.scratch);
}

}  // namespace focus
}  // namespace geom
