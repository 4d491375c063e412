// light_matrix.cpp: the per-frame light matrices of geom/focus.h: the focus
// body's inputs (V, S, L, receivers), the light's kind in post-perspective
// space, the virtual camera shift, and the PSM / LiSPSM / uniform matrices.
//
// References:
//   seed 002_147d3d07b97c563e.txt, Stamminger & Drettakis, "Perspective Shadow
//   Maps": Sect. 3 (lights in post-perspective space: a point light in front
//   of the viewer stays a point light, one behind becomes an inverted point
//   light, one on the camera plane a directional light; a directional light
//   becomes a point light on the infinity plane, inverted when it shines from
//   behind), Sect. 4.1 (H), Sect. 4.2 (virtual camera shift: move the
//   viewpoint back until H lies in front of it), Sect. 6 (near plane as far
//   as possible).
//   Wimmer, Scherzer, Purgathofer, "Light Space Perspective Shadow Maps"
//   (EGSR 2004): the warp frustum along the view direction projected into the
//   light's image plane, n_opt = (z_n + sqrt(z_n z_f)) / sin(gamma) with
//   z_f = z_n + d sin(gamma) (the general, non-orthogonal form, as in its
//   reference code), so the warp fades continuously to none as gamma -> 0.
//   For point and spot lights, LiSPSM is applied in the light's own
//   post-perspective space, where the light is directional (Wimmer Sect. 5).
//
// Every matrix is built as a chain C (world -> a clip space where all of H
// has w > 0 and z/w grows away from the light along a light ray) followed by
// the fit F that maps H's image onto the unit cube (z flipped for an inverted
// point light, so the ordinary depth test is right for every light kind).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "focus_body.h"
#include "focus_math.h"
#include "geom/focus.h"

namespace geom {

using namespace focus;

namespace {

struct Frame {
  // camera
  M4 view, view_inv, proj;
  bool perspective = true;
  double cam_near = 0, cam_far = 0;  // far may be +inf
  V3 eye, view_dir;
  // light
  bool directional = false;
  V3 light_pos;      // point, spot
  V3 towards_light;  // directional: unit vector towards the light
  V3 light_axis;     // point, spot: the light frustum's axis (unit)
  double light_near = 0;
  // bodies
  std::vector<Plane> s_planes, l_planes, r_planes, hull_clip, v_planes, hull_clip_planes;
  Polytope receivers, body, scratch;
  std::vector<V3> r_verts, h_verts, hull_points;
  double eps = 0, scale = 1;
};

void set_fallback(FocusResult& out, FocusFallback f, const char* reason) {
  if (f > out.fallback) {
    out.fallback = f;
    out.reason = reason;
  }
}

double depth_of(const Frame& fr, V3 p) { return -mul_point(fr.view, p).z; }

// The centre of the bounding box of pts: unlike the vertex centroid it does not
// move when clipping leaves an extra vertex in the middle of an edge, so the
// axes chosen from it are stable from frame to frame.
V3 box_centre(const std::vector<V3>& pts) {
  V3 lo(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
  for (V3 p : pts) {
    lo = V3(std::fmin(lo.x, p.x), std::fmin(lo.y, p.y), std::fmin(lo.z, p.z));
    hi = V3(std::fmax(hi.x, p.x), std::fmax(hi.y, p.y), std::fmax(hi.z, p.z));
  }
  return (lo + hi) * 0.5;
}

// F * C, with F mapping the image of `pts` under C onto the unit cube. False
// when a point has w <= 0 or the result is not finite.
bool fit(const M4& chain, const std::vector<V3>& pts, bool flip_depth, M4& out) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (V3 p : pts) {
    V4 c = mul_point(chain, p);
    if (!(c.w > 0)) return false;
    double q[3] = {c.x / c.w, c.y / c.w, c.z / c.w};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::fmin(lo[k], q[k]);
      hi[k] = std::fmax(hi[k], q[k]);
    }
  }
  if (pts.empty()) return false;
  M4 f = M4::identity();
  for (int k = 0; k < 3; ++k) {
    double ext = hi[k] - lo[k];
    double floor_ext = 1e-12 * std::fmax(1.0, std::fmax(std::fabs(hi[k]), std::fabs(lo[k])));
    if (!(ext > floor_ext)) ext = floor_ext;  // a flat image: any finite scale maps it inside
    double s = 2 / ext, t = -(hi[k] + lo[k]) / ext;
    if (k == 2 && flip_depth) s = -s, t = -t;
    f.at(k, k) = s;
    f.at(k, 3) = t;
  }
  out = f * chain;
  return finite(out);
}

// Rows (x, y, axis) at `origin`: x = axis x hint, y = x x axis (GL's lookAt
// with -axis as its z). The third coordinate is the distance along `axis`.
M4 axis_frame(V3 origin, V3 axis, V3 hint) {
  V3 x = cross(axis, hint);
  if (length(x) < 1e-9 * length(hint) || length(hint) == 0) x = cross(axis, any_perpendicular(axis));
  x = normalize(x);
  return frame(x, cross(x, axis), axis, origin);
}

// A perspective along +z of a frame: w = z, z/w increasing in z over [n, f].
M4 perspective_z(double n, double f) {
  M4 p = M4::zero();
  p.at(0, 0) = 1;
  p.at(1, 1) = 1;
  p.at(2, 2) = (f + n) / (f - n);
  p.at(2, 3) = -2 * f * n / (f - n);
  p.at(3, 2) = 1;
  return p;
}

// The light's own projection (the uniform chain before its fit): an
// orthographic frame for a directional light, a perspective from the light
// along its axis for a point or spot light (every point of H is at least
// light_near along the axis: L contains that half-space).
M4 uniform_chain(const Frame& fr) {
  if (fr.directional) return axis_frame(fr.eye, -fr.towards_light, fr.view_dir);
  M4 basis = axis_frame(fr.light_pos, fr.light_axis, fr.view_dir);
  double n = HUGE_VAL, f = 0;
  for (V3 p : fr.h_verts) {
    double d = dot(p - fr.light_pos, fr.light_axis);
    n = std::fmin(n, d);
    f = std::fmax(f, d);
  }
  n = std::fmax(n, 0.5 * fr.light_near);
  if (!(f > n * (1 + 1e-9))) f = n * (1 + 1e-6) + 1e-300;
  return perspective_z(n, f) * basis;
}

bool uniform_matrix(const Frame& fr, M4& out) { return fit(uniform_chain(fr), fr.h_verts, false, out); }

// Kind of a homogeneous post-perspective light position (x, y, z, w) as seen
// from a set of post-perspective points of centre c and radius r.
LightKind kind_of(V4 l, V3 c, double r) {
  V3 dir = V3(l.x, l.y, l.z) - c * l.w;
  if (std::fabs(l.w) * r <= 1e-6 * length(dir)) return LightKind::Directional;
  return l.w > 0 ? LightKind::Point : LightKind::InvertedPoint;
}

bool psm_matrix(const Frame& fr, const FocusOptions& opt, FocusResult& out, M4& result) {
  // Depth ranges along the view axis: of H, and of the receivers R.
  double h_min = HUGE_VAL, h_max = -HUGE_VAL, r_min = HUGE_VAL, r_max = -HUGE_VAL;
  for (V3 p : fr.h_verts) {
    double d = depth_of(fr, p);
    h_min = std::fmin(h_min, d);
    h_max = std::fmax(h_max, d);
  }
  for (V3 p : fr.r_verts) {
    double d = depth_of(fr, p);
    r_min = std::fmin(r_min, d);
    r_max = std::fmax(r_max, d);
  }
  // The near plane pushed as far as the receivers allow (Sect. 6), but not
  // below psm_min_near_ratio of their far depth (a camera inside the scene
  // would otherwise spend the whole map on the first millimetre).
  double pushed = std::fmax(fr.cam_near, r_min);
  double target = std::fmax(pushed, opt.psm_min_near_ratio * r_max);
  if (target > pushed * (1 + 1e-9))
    set_fallback(out, FocusFallback::NearLimited,
                 "the receivers reach the camera's near plane (camera inside the scene): the virtual near plane is "
                 "held at psm_min_near_ratio of the receivers' far depth, which limits the warp");
  // Virtual camera shift (Sect. 4.2): back until H lies beyond the near plane.
  double shift = std::fmax(0.0, target - h_min);
  double n = h_min + shift, f = h_max + shift;
  if (!(f > n * (1 + 1e-9))) f = n * (1 + 1e-6);
  out.camera_shift = shift;
  out.psm_near = n;
  out.psm_far = f;
  M4 back = M4::identity();
  back.at(2, 3) = -shift;  // eye-space z' = z - shift: the eye moved back by `shift`
  M4 proj = M4::zero();
  proj.at(0, 0) = fr.proj.at(0, 0);
  proj.at(0, 2) = fr.proj.at(0, 2);
  proj.at(1, 1) = fr.proj.at(1, 1);
  proj.at(1, 2) = fr.proj.at(1, 2);
  proj.at(2, 2) = (f + n) / (n - f);
  proj.at(2, 3) = 2 * f * n / (n - f);
  proj.at(3, 2) = -1;
  M4 post = proj * back * fr.view;

  // H and the light in post-perspective space.
  thread_local std::vector<V3> hp;
  hp.clear();
  for (V3 p : fr.h_verts) {
    V4 q = mul_point(post, p);
    hp.push_back(V3(q.x / q.w, q.y / q.w, q.z / q.w));
  }
  V3 c = box_centre(hp);
  double r = 0;
  for (V3 q : hp) r = std::fmax(r, length(q - c));
  V4 l = fr.directional ? mul(post, fr.towards_light.x, fr.towards_light.y, fr.towards_light.z, 0)
                        : mul_point(post, fr.light_pos);
  LightKind kind = kind_of(l, c, r);
  out.psm_light_kind = kind;
  if (kind == LightKind::Directional) {
    V3 towards = normalize(V3(l.x, l.y, l.z) - c * l.w);
    return fit(axis_frame(c, -towards, V3(0, 1, 0)) * post, fr.h_verts, false, result);
  }
  V3 centre(l.x / l.w, l.y / l.w, l.z / l.w);
  V3 axis = normalize(c - centre);
  double dmin = HUGE_VAL, dmax = 0, tan_max = 0;
  for (V3 q : hp) {
    double d = dot(q - centre, axis);
    double side = length((q - centre) - axis * d);
    dmin = std::fmin(dmin, d);
    dmax = std::fmax(dmax, d);
    tan_max = std::fmax(tan_max, d > 0 ? side / d : HUGE_VAL);
  }
  const double tan80 = std::tan(80 * kPi / 180);
  if (!(dmin > 0) || !(tan_max <= tan80)) {
    set_fallback(out, FocusFallback::LightTooClose,
                 "the light in post-perspective space is too close to the focus body (field of view over 160 "
                 "degrees, as for a light nearly parallel to the view direction): uniform shadow map used");
    return false;
  }
  if (!(dmax > dmin * (1 + 1e-9))) dmax = dmin * (1 + 1e-6);
  M4 chain = perspective_z(dmin, dmax) * axis_frame(centre, axis, V3(0, 1, 0)) * post;
  // Inverted: rays converge on `centre`; the point nearest the real light is
  // the one farthest from it, so the fit flips depth.
  return fit(chain, fr.h_verts, kind == LightKind::InvertedPoint, result);
}

// LiSPSM in a space where the light is directional with travel direction
// `travel`: `pts` the body, `eye` and `view` the viewer there, z_near the
// receivers' nearest depth in those units. Returns the warp (chain before the
// fit) through `warp`; false when there is no warp (gamma = 0 or negligible).
bool lispsm_warp(const std::vector<V3>& pts, V3 travel, V3 eye, V3 view, double z_near, double n_scale, M4& warp,
                 double& n_used) {
  double sin_gamma = length(cross(view, travel));
  if (!(sin_gamma > 1e-9)) return false;
  M4 basis = axis_frame(eye, travel, view);  // y: the view direction projected ⟂ to the light
  double ymin = HUGE_VAL, ymax = -HUGE_VAL;
  for (V3 p : pts) {
    double y = mul_point(basis, p).y;
    ymin = std::fmin(ymin, y);
    ymax = std::fmax(ymax, y);
  }
  double d = ymax - ymin;
  if (!(d > 0)) return false;
  double z0 = std::fmax(z_near, 1e-12 * d), z1 = z0 + d * sin_gamma;
  double n = n_scale * (z0 + std::sqrt(z0 * z1)) / sin_gamma;
  if (!(n <= 1e4 * d)) return false;  // the warp differs from none by under 1e-4: none
  double f = n + d;
  M4 w = M4::zero();  // perspective looking down +y from (0, ymin - n, 0)
  w.at(0, 0) = 1;
  w.at(1, 1) = (f + n) / (f - n);
  w.at(1, 3) = (f + n) / (f - n) * (n - ymin) - 2 * f * n / (f - n);
  w.at(2, 2) = 1;
  w.at(3, 1) = 1;
  w.at(3, 3) = n - ymin;
  warp = w * basis;
  n_used = n;
  return true;
}

bool lispsm_matrix(const Frame& fr, const FocusOptions& opt, FocusResult& out, M4& result) {
  double r_min = HUGE_VAL;
  for (V3 p : fr.r_verts) r_min = std::fmin(r_min, depth_of(fr, p));
  V3 r_centre = box_centre(fr.r_verts);
  double z_near = std::fmax(fr.cam_near, r_min);
  M4 warp;
  double n_used = 0;
  bool warped;
  M4 chain;
  if (fr.directional) {
    warped = lispsm_warp(fr.h_verts, -fr.towards_light, fr.eye, fr.view_dir, z_near, opt.lispsm_n_scale, warp, n_used);
    chain = warp;
  } else {
    // In the light's post-perspective space the light is directional (+z).
    M4 u = uniform_chain(fr);
    thread_local std::vector<V3> q;
    q.clear();
    for (V3 p : fr.h_verts) {
      V4 c = mul_point(u, p);
      q.push_back(V3(c.x / c.w, c.y / c.w, c.z / c.w));
    }
    // The view direction at the receivers' centre, and the local scale there.
    double step = 1e-3 * std::fmax(fr.scale * 1e-6, length(fr.r_verts.front() - r_centre));
    V4 a = mul_point(u, r_centre), b = mul_point(u, r_centre + fr.view_dir * step);
    warped = false;
    if (a.w > 0 && b.w > 0) {
      V3 pa(a.x / a.w, a.y / a.w, a.z / a.w), pb(b.x / b.w, b.y / b.w, b.z / b.w);
      double local = length(pb - pa) / step;
      V3 view = normalize(pb - pa);
      double z_centre = depth_of(fr, r_centre);
      V3 eye = pa - view * (z_centre * local);
      warped =
          length(view) > 0 && lispsm_warp(q, V3(0, 0, 1), eye, view, z_near * local, opt.lispsm_n_scale, warp, n_used);
    }
    chain = warp * u;
  }
  if (!warped) {
    set_fallback(out, FocusFallback::ParallelLight,
                 "the light is (nearly) parallel to the view direction: LiSPSM's warp vanishes, uniform used");
    return false;
  }
  out.lispsm_n = n_used;
  return fit(chain, fr.h_verts, false, result);
}

bool finite3(const double* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

void box_planes(const double* lo, const double* hi, std::vector<Plane>& out) {
  for (int k = 0; k < 3; ++k) {
    V3 n(k == 0, k == 1, k == 2);
    out.push_back({n, -lo[k]});
    out.push_back({-n, hi[k]});
  }
}

// Fills `fr` from the inputs; false (with the reason) for invalid input.
bool setup(const CameraMatrices& cam, const Light& light, FocusBox box, const FocusOptions& opt, Frame& fr,
           FocusResult& out) {
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

  fr.directional = light.type == LightType::Directional;
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
      !std::isfinite(opt.lispsm_n_scale) || int(opt.method) > 2) {
    out.reason = "the options are out of range (psm_min_near_ratio in [0, 1), lispsm_n_scale > 0)";
    return false;
  }
  if (opt.receivers && (!finite3(opt.receivers->min) || !finite3(opt.receivers->max))) {
    out.reason = "the receiver bounds are not finite";
    return false;
  }

  // Scene bounds: swapped axes put right, zero extents inflated.
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
  diag = std::sqrt(diag);

  fr.s_planes.clear();
  box_planes(box.min, box.max, fr.s_planes);
  if (opt.casters.size() > 0) {
    thread_local std::vector<Plane> hull;
    if (hull_planes(opt.casters, hull))
      fr.s_planes.insert(fr.s_planes.end(), hull.begin(), hull.end());
    else
      set_fallback(out, FocusFallback::DegenerateScene,
                   "the casters span no volume (or hold a non-finite point): the scene box alone is S");
  }
  fr.r_planes.clear();
  if (opt.receivers) {
    FocusBox rb = *opt.receivers;
    for (int k = 0; k < 3; ++k)
      if (rb.min[k] > rb.max[k]) std::swap(rb.min[k], rb.max[k]);
    box_planes(rb.min, rb.max, fr.r_planes);
  }

  // Light frustum L (the near half-space of a point light is added later).
  fr.l_planes.clear();
  fr.light_pos = V3(light.position);
  fr.light_near = opt.light_near > 0 ? opt.light_near : 1e-3 * diag;
  if (fr.directional) {
    fr.towards_light = -normalize(V3(light.direction));
  } else {
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
  return true;
}

// Corners of V, cut at the far side of S (no receiver lies beyond it; this is
// what lets an infinite far plane work). False when V n S is empty.
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
constexpr double kNearFloor = 1e-3;

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

}  // namespace

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

bool compute_focus(const CameraMatrices& camera, const Light& light, const FocusBox& scene, const FocusOptions& options,
                   FocusResult& out) {
  return compute_focus_staged(camera, light, scene, options, out, nullptr);
}

bool focus::compute_focus_staged(const CameraMatrices& camera, const Light& light, const FocusBox& scene,
                                 const FocusOptions& options, FocusResult& out, StageTimes* times) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point mark = times ? Clock::now() : Clock::time_point();
  // Adds the time since the last mark to `slot`.
  auto lap = [&](double StageTimes::*slot) {
    if (!times) return;
    Clock::time_point now = Clock::now();
    times->*slot += std::chrono::duration<double>(now - mark).count();
    mark = now;
  };
  M4 id = M4::identity();
  std::copy(id.m, id.m + 16, out.matrix);
  out.method = FocusMethod::Uniform;
  out.fallback = FocusFallback::None;
  out.reason = "";
  out.light_kind = out.psm_light_kind = LightKind::Directional;
  out.needs_cube_map = out.near_floor_cut = false;
  out.camera_shift = out.psm_near = out.psm_far = out.lispsm_n = out.light_near = 0;
  out.light_axis[0] = out.light_axis[1] = out.light_axis[2] = 0;
  out.vertices.clear();
  out.face_sizes.clear();
  out.face_indices.clear();
  try {
    thread_local Frame fr;
    if (!setup(camera, light, scene, options, fr, out)) {
      out.fallback = FocusFallback::InvalidInput;
      return false;
    }
    // The light's kind in the real camera's post-perspective space (Sect. 3).
    if (fr.perspective) {
      double w = fr.directional ? dot(fr.towards_light, fr.view_dir) : depth_of(fr, fr.light_pos);
      double size = fr.directional ? 1.0 : length(fr.light_pos - fr.eye) + fr.scale;
      out.light_kind = std::fabs(w) <= 1e-9 * size ? LightKind::Directional
                       : w > 0                     ? LightKind::Point
                                                   : LightKind::InvertedPoint;
    } else {
      out.light_kind = fr.directional ? LightKind::Directional : LightKind::Point;
    }
    out.psm_light_kind = out.light_kind;
    lap(&StageTimes::setup);

    // R = V n S n L (n receiver bounds).
    V3 corners[8];
    bool visible = view_frustum(fr, corners);
    if (visible) {
      frustum_polytope(corners, fr.receivers);
      clip_polytope(fr.receivers, fr.s_planes.data(), fr.s_planes.size(), fr.eps, fr.scratch);
      clip_polytope(fr.receivers, fr.l_planes.data(), fr.l_planes.size(), fr.eps, fr.scratch);
      clip_polytope(fr.receivers, fr.r_planes.data(), fr.r_planes.size(), fr.eps, fr.scratch);
    } else {
      fr.receivers.clear();
    }
    if (!fr.directional && !fr.receivers.empty()) near_plane_cut(fr, light, options, out);
    unique_vertices(fr.receivers, fr.eps, fr.r_verts);
    lap(&StageTimes::receivers);
    // H = conv(R u {l}) n S n L.
    if (!fr.receivers.empty()) {
      double reach = -HUGE_VAL;
      if (fr.directional)
        for (int i = 0; i < 8; ++i) {
          V3 s(i & 1 ? fr.s_planes[1].d : -fr.s_planes[0].d, i & 2 ? fr.s_planes[3].d : -fr.s_planes[2].d,
               i & 4 ? fr.s_planes[5].d : -fr.s_planes[4].d);
          reach = std::fmax(reach, dot(s, fr.towards_light));
        }
      std::vector<Plane>& clip = fr.hull_clip;
      clip.assign(fr.s_planes.begin(), fr.s_planes.end());
      clip.insert(clip.end(), fr.l_planes.begin(), fr.l_planes.end());
      // R's candidate planes: V's faces and the receiver bounds.
      fr.v_planes.clear();
      V3 vc(0, 0, 0);
      for (V3 c : corners) vc = vc + c * 0.125;
      static const int face_corners[6][3] = {{0, 1, 2}, {4, 6, 5}, {0, 3, 7}, {1, 5, 6}, {0, 4, 5}, {3, 2, 6}};
      for (const auto& f : face_corners) {
        V3 n = cross(corners[f[1]] - corners[f[0]], corners[f[2]] - corners[f[0]]);
        if (!(length(n) > 0)) continue;
        Plane p = plane_through(corners[f[0]], normalize(n));
        if (p.eval(vc) < 0) p = {-p.n, -p.d};
        fr.v_planes.push_back(p);
      }
      fr.v_planes.insert(fr.v_planes.end(), fr.r_planes.begin(), fr.r_planes.end());
      double lo[3], hi[3];
      for (int k = 0; k < 3; ++k) lo[k] = -fr.s_planes[2 * k].d, hi[k] = fr.s_planes[2 * k + 1].d;
      V3 box[8];
      for (int i = 0; i < 8; ++i) {
        int b = (i & 3) == 1 || (i & 3) == 2 ? 1 : 0, t = (i & 3) >= 2 ? 1 : 0;  // frustum_polytope's corner order
        box[i] = V3(b ? hi[0] : lo[0], t ? hi[1] : lo[1], i >= 4 ? lo[2] : hi[2]);
      }
      V3 axis = fr.directional ? fr.towards_light : fr.light_axis;
      if (!focus_by_planes(fr.r_verts, fr.directional ? fr.towards_light : fr.light_pos, fr.directional, axis,
                           fr.v_planes.data(), fr.v_planes.size(), clip.data(), clip.size(), box, fr.eps,
                           fr.hull_clip_planes, fr.body, fr.scratch, times))
        focus_hull(fr.receivers, fr.directional ? fr.towards_light : fr.light_pos, fr.directional, reach, clip.data(),
                   clip.size(), fr.eps, fr.hull_points, fr.body, fr.scratch, times);
    } else {
      fr.body.clear();
    }
    if (times) mark = Clock::now();  // focus_hull timed itself
    unique_vertices(fr.body, fr.eps, fr.h_verts);
    if (fr.h_verts.empty() || fr.r_verts.empty()) {
      // Nothing visible to shadow. A finite matrix over S n L (or S) all the same.
      set_fallback(out, FocusFallback::EmptyFocus,
                   "the focus body is empty: no visible point lies in the scene bounds and the light's frustum");
      double lo[3], hi[3];
      for (int k = 0; k < 3; ++k) lo[k] = -fr.s_planes[2 * k].d, hi[k] = fr.s_planes[2 * k + 1].d;
      V3 c[8];
      for (int i = 0; i < 8; ++i) c[i] = V3(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]);
      frustum_polytope(c, fr.body);
      if (light.type == LightType::Spot && fr.receivers.empty())  // no receiver set the near plane's floor
        fr.l_planes.push_back(plane_through(fr.light_pos + fr.light_axis * fr.light_near, fr.light_axis));
      Polytope lit = fr.body;
      clip_polytope(lit, fr.l_planes.data(), fr.l_planes.size(), fr.eps, fr.scratch);
      if (!fr.directional && light.type == LightType::Point) fr.light_axis = fr.view_dir;
      unique_vertices(lit.empty() ? fr.body : lit, fr.eps, fr.h_verts);
      M4 m;
      bool ok = !lit.empty() && uniform_matrix(fr, m);
      if (!ok) {  // the light's side of S: an orthographic view of S along the light's axis
        V3 axis = fr.directional ? -fr.towards_light : fr.light_axis;
        unique_vertices(fr.body, fr.eps, fr.h_verts);
        ok = fit(axis_frame(fr.eye, axis, fr.view_dir), fr.h_verts, false, m);
      }
      if (ok) std::copy(m.m, m.m + 16, out.matrix);
      fr.h_verts.clear();
      return true;
    }
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
    if (!fr.directional) {
      for (int k = 0; k < 3; ++k) out.light_axis[k] = fr.light_axis[k];
      // The map's near plane: H's nearest point. At the floor, H was cut there
      // (casters next to the light, or receivers): say so.
      double nearest = HUGE_VAL;
      for (V3 p : fr.h_verts) nearest = std::fmin(nearest, dot(p - fr.light_pos, fr.light_axis));
      out.light_near = std::fmax(nearest, fr.light_near);
      if (nearest <= fr.light_near + 4 * fr.eps) out.near_floor_cut = true;
    }
    lap(&StageTimes::faces);

    M4 m;
    bool done = false;
    if (options.method != FocusMethod::Uniform && !fr.perspective) {
      set_fallback(out, FocusFallback::OrthographicCamera,
                   "the camera is orthographic: there is no perspective to warp, uniform used");
    } else if (options.method == FocusMethod::Psm) {
      done = psm_matrix(fr, options, out, m);
      if (done) out.method = FocusMethod::Psm;
    } else if (options.method == FocusMethod::Lispsm) {
      done = lispsm_matrix(fr, options, out, m);
      if (done) out.method = FocusMethod::Lispsm;
    }
    if (!done) {
      out.method = FocusMethod::Uniform;
      done = uniform_matrix(fr, m);
    }
    if (done) std::copy(m.m, m.m + 16, out.matrix);
    lap(&StageTimes::matrix);
    return true;
  } catch (...) {  // allocation failure: never past the library boundary
    std::copy(id.m, id.m + 16, out.matrix);
    out.fallback = FocusFallback::InvalidInput;
    out.reason = "out of memory";
    return false;
  }
}

}  // namespace geom
