// light_matrix.cpp: the per-frame light matrices of geom/focus.h: the light's
// kind in post-perspective space, the virtual camera shift, and the PSM /
// LiSPSM / uniform matrices of the focus body H (focus_frame.h).
//
// References:
//   Stamminger and Drettakis 2002, "Perspective Shadow
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
#include <cmath>
#include <vector>

#include "focus_frame.h"

namespace geom {
namespace focus {
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

// GL's lookAt with -axis as its z: the third coordinate is the distance along `axis`.
M4 axis_frame(V3 origin, V3 axis, V3 hint) {
  V3 x = cross(axis, hint);
  if (length(x) < 1e-9 * length(hint) || length(hint) == 0) x = cross(axis, any_perpendicular(axis));
  x = normalize(x);
  return frame(x, cross(x, axis), axis, origin);
}

// A perspective along +z of a frame: w = z, z/w increasing in z over [n, f].
static M4 perspective_z(double n, double f) {
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
static M4 uniform_chain(const Frame& fr) {
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
static LightKind kind_of(V4 l, V3 c, double r) {
  V3 dir = V3(l.x, l.y, l.z) - c * l.w;
  if (std::fabs(l.w) * r <= 1e-6 * length(dir)) return LightKind::Directional;
  return l.w > 0 ? LightKind::Point : LightKind::InvertedPoint;
}

// PSM's post-perspective transform (Stamminger and Drettakis 2002, Sect. 4):
// the camera's projection with its near plane pushed as far as the receivers
// allow and the virtual camera shifted back until H lies beyond it.
static M4 psm_post_perspective(const Frame& fr, const FocusOptions& opt, double ease, FocusResult& out) {
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
  // `ease` > 1 moves it further back, to ease times that near distance:
  // a weaker warp, f/n closer to 1 (uniform in the limit).
  double shift = std::fmax(0.0, target - h_min);
  shift += (ease - 1) * (h_min + shift);
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
  return proj * back * fr.view;
}

bool psm_matrix(const Frame& fr, const FocusOptions& opt, double ease, FocusResult& out, M4& result) {
  const M4 post = psm_post_perspective(fr, opt, ease, out);
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
static bool lispsm_warp(const std::vector<V3>& pts, V3 travel, V3 eye, V3 view, double z_near, double n_scale, M4& warp,
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

bool lispsm_matrix(const Frame& fr, const FocusOptions& opt, double ease, FocusResult& out, M4& result) {
  double r_min = HUGE_VAL;
  for (V3 p : fr.r_verts) r_min = std::fmin(r_min, depth_of(fr, p));
  V3 r_centre = box_centre(fr.r_verts);
  double z_near = std::fmax(fr.cam_near, r_min);
  M4 warp;
  double n_used = 0;
  bool warped;
  M4 chain;
  if (fr.directional) {
    warped = lispsm_warp(fr.h_verts, -fr.towards_light, fr.eye, fr.view_dir, z_near, ease * opt.lispsm_n_scale, warp,
                         n_used);
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
      warped = length(view) > 0 &&
               lispsm_warp(q, V3(0, 0, 1), eye, view, z_near * local, ease * opt.lispsm_n_scale, warp, n_used);
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

// A warp's gain over the unwarped map: the least, over sample points of R
// (its vertices, its centre, and the points halfway between them), of the
// ratio of the two maps' resolutions there, each measured as the length in
// the map of a small step along the camera's right, up and view directions:
// summed, or (`per_direction`) each direction on its own, leaving out those
// the unwarped map resolves at under a quarter of its best one at that point
// (such as a step along the light). A warp trades resolution far away for
// resolution near the eye (Stamminger and Drettakis 2002, Sect. 3; Wimmer et
// al. 2004, Sect. 4), and in one direction for another; where it leaves some
// receiver much more coarsely resolved than the unwarped map does, it is
// worse than no warp for that frame. LiSPSM under a directional light, whose
// warp eases, is judged per direction (on random frames of the bundled scene
// the summed test let through warps worse than uniform more often); the
// others by the sum, which kept psm's and point-light lispsm's warps on
// geombench's near-plane and behind scenes and the bundled scene's faces.
static double warp_gain(const Frame& fr, const M4& warped, const M4& uniform, bool per_direction) {
  V4 r4 = mul(fr.view_inv, 1, 0, 0, 0), u4 = mul(fr.view_inv, 0, 1, 0, 0);
  const V3 dirs[3] = {normalize(V3(r4.x, r4.y, r4.z)), normalize(V3(u4.x, u4.y, u4.z)), fr.view_dir};
  auto lengths_at = [&](const M4& m, V3 p, double step, double out[3]) {
    V4 a = mul_point(m, p);
    if (!(a.w > 0)) return false;
    for (int k = 0; k < 3; ++k) {
      V4 b = mul_point(m, p + dirs[k] * step);
      if (!(b.w > 0)) return false;
      out[k] = std::hypot(b.x / b.w - a.x / a.w, b.y / b.w - a.y / a.w);
    }
    return true;
  };
  V3 c = box_centre(fr.r_verts);
  double gain = HUGE_VAL;
  auto at = [&](V3 p) {
    double step = 1e-4 * std::fmax(depth_of(fr, p), fr.cam_near), w[3], u[3];
    if (!lengths_at(uniform, p, step, u)) return;
    if (!lengths_at(warped, p, step, w)) {
      gain = 0;
      return;
    }
    if (!per_direction) {
      double ws = w[0] + w[1] + w[2], us = u[0] + u[1] + u[2];
      if (us > 0) gain = std::fmin(gain, ws / us);
      return;
    }
    double best = std::fmax(u[0], std::fmax(u[1], u[2]));
    for (int k = 0; k < 3; ++k)
      if (best > 0 && u[k] >= 0.25 * best) gain = std::fmin(gain, w[k] / u[k]);
  };
  at(c);
  for (V3 p : fr.r_verts) at(p), at((p + c) * 0.5);
  return gain;
}

// The warp of opt.method at strength `ease` (1: the paper's; larger: weaker),
// its parameters written to `out`.
static bool warp_matrix(const Frame& fr, const FocusOptions& opt, double ease, FocusResult& out, M4& result) {
  return opt.method == FocusMethod::Psm ? psm_matrix(fr, opt, ease, out, result)
                                        : lispsm_matrix(fr, opt, ease, out, result);
}

// LiSPSM under a directional light: the strongest warp, from the paper's own (ease 1) towards none in
// steps of kEaseStep in its warp distance n, whose gain over the unwarped map
// is at least opt.min_warp_gain: a warp trades resolution far away for
// resolution near the eye, and a weaker warp trades less of it (Wimmer et al.
// 2004, Sect. 4.3: as n grows towards infinity the warp fades to uniform
// shadow mapping). Not PSM: moving its virtual camera back weakens the warp,
// but the light's post-perspective direction turns towards the view axis as
// it does (depth keeps its scale while x and y shrink), so the map does not
// tend to the unwarped one; on geombench's wide-depth alley the gain of such
// eased PSM warps peaked at 0.44 (8 times the near distance) and fell to 0.04,
// and on random frames of the bundled scene they were worse than uniform more
// often than the paper's warp or none. Nor a point or spot light, whose
// LiSPSM works in the light's post-perspective space: there eased warps were
// worse than uniform by more than 1.1x + 2 pixels in 6 of 48 cells of
// geombench's run (behind, the bundled scene, quake3, scan), where the
// paper's warp or none holds in all. False when even the weakest fails.
static bool eased_warp(const Frame& fr, const FocusOptions& opt, const M4& uniform, FocusResult& out, M4& result) {
  if (opt.method != FocusMethod::Lispsm || !fr.directional) return false;
  constexpr double kEaseStep = 2, kEaseMax = 256;
  for (double ease = kEaseStep; ease <= kEaseMax; ease *= kEaseStep) {
    FocusResult trial;
    M4 m;
    if (!warp_matrix(fr, opt, ease, trial, m) || !(warp_gain(fr, m, uniform, true) >= opt.min_warp_gain)) continue;
    result = m;
    out.camera_shift = trial.camera_shift, out.psm_near = trial.psm_near, out.psm_far = trial.psm_far;
    out.psm_light_kind = trial.psm_light_kind, out.lispsm_n = trial.lispsm_n;
    return true;
  }
  return false;
}

bool method_matrix(const Frame& fr, const FocusOptions& opt, FocusResult& out, M4& result) {
  bool done = false;
  if (opt.method != FocusMethod::Uniform && !fr.perspective) {
    set_fallback(out, FocusFallback::OrthographicCamera,
                 "the camera is orthographic: there is no perspective to warp, uniform used");
  } else if (opt.method != FocusMethod::Uniform) {
    done = warp_matrix(fr, opt, 1, out, result);
    if (done) out.method = opt.method;
  }
  M4 uniform;
  if (done && opt.min_warp_gain > 0 && uniform_matrix(fr, uniform) &&
      warp_gain(fr, result, uniform, opt.method == FocusMethod::Lispsm && fr.directional) < opt.min_warp_gain &&
      !eased_warp(fr, opt, uniform, out, result)) {
    set_fallback(out, FocusFallback::WarpNoGain,
                 "the warp (LiSPSM's eased ones too) would resolve some visible receiver more coarsely than the "
                 "unwarped map: uniform used");
    out.method = FocusMethod::Uniform;
    result = uniform;
    return true;
  }
  if (!done) {
    out.method = FocusMethod::Uniform;
    done = uniform_matrix(fr, result);
  }
  return done;
}

}  // namespace focus
}  // namespace geom
