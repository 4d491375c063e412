// cli/view_check.h (tools/common, library geom::cli): the one validation of a
// light and a camera, whatever they came from (a baked file's lights section,
// a glTF or other scene file, a flag, a focus frame), before any of it reaches
// the float pipeline (GL), the ray-cast reference (Embree) or the focus
// matrices. Finiteness is not enough: a light at 2e18 is finite and aborts
// Embree, a direction of 1e20 overflows a float when it is squared, a near
// plane of 1e-7 under a far plane of 100 leaves no depth to draw with.
//
// The limits (docs/reliability.md):
//   coordinates (eye, target, light position)  |x| <= kMaxCoordinate (1e15),
//       the limit of the baked reader's float validation (geom/baked_reader.h);
//   directions (up, a directional or spot light's direction): length within
//       [kMinDirection, kMaxCoordinate] (1e-15 .. 1e15);
//   the eye and the target at least kMinViewLength (1e-6) times their larger
//       magnitude apart (a float resolves 6e-8 of it), the up vector at least
//       kMinUpAngle (1e-6 rad) away from the view direction;
//   fovy within [kMinFovy, kMaxFovy] (0.001 .. 179.9 degrees), aspect within
//       [1e-5, 1e5];
//   0 < near < far <= 2 x kMaxCoordinate, and, where the image is drawn with a
//       24-bit depth buffer, far / near <= kMaxDepthRatio (2^20): beyond that
//       the far plane's depth is within a few steps of the cleared depth and
//       the image comes out empty;
//   a spot's cone within (0, 90] degrees; a light's range within [0, 2 x kMaxCoordinate].
#pragma once
#include <cmath>
#include <cstdio>
#include <string>

#include "geom/baked_reader.h"
#include "geom/scene.h"

namespace cli {

constexpr double kMaxCoordinate = geom::baked::kMaxCoordinate;
constexpr double kMinDirection = geom::baked::kMinDirection;
constexpr double kMinViewLength = 1e-6;
constexpr double kMinUpAngle = 1e-6;
constexpr double kMinFovy = 0.001, kMaxFovy = 179.9;
constexpr double kMinAspect = 1e-5, kMaxAspect = 1e5;
constexpr double kMaxDepthRatio = 1048576;  // 2^20

namespace detail {
inline std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}
inline double length3(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
inline bool check_point(const char* what, const double p[3], std::string& error) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(p[k]) || std::fabs(p[k]) > kMaxCoordinate)
      return error = std::string(what) + " coordinate " + num(p[k]) + " is not a finite number within +-" +
                     num(kMaxCoordinate),
             false;
  return true;
}
inline bool check_direction(const char* what, const double d[3], std::string& error) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(d[k]) || std::fabs(d[k]) > kMaxCoordinate)
      return error = std::string(what) + " component " + num(d[k]) + " is not a finite number within +-" +
                     num(kMaxCoordinate),
             false;
  const double l = length3(d);
  if (!(l >= kMinDirection))
    return error = std::string(what) + " has length " + num(l) + ", under " + num(kMinDirection) + " (no direction)",
           false;
  return true;
}
}  // namespace detail

// A light: its position (point, spot), direction (directional, spot), cone and
// range within the limits above. `what` names it in the error ("--light",
// "FILE: light 0", "light").
inline bool check_light(const geom::Light& l, const std::string& what, std::string& error) {
  std::string e;
  bool ok = true;
  if (l.type != geom::LightType::Directional) ok = detail::check_point("position", l.position, e);
  if (ok && l.type != geom::LightType::Point) ok = detail::check_direction("direction", l.direction, e);
  if (ok && l.type == geom::LightType::Spot && !(l.outer_cone > 0 && l.outer_cone <= 1.5707963267948966))
    ok = false, e = "spot cone " + detail::num(l.outer_cone) + " rad is not within (0, pi/2]";
  if (ok && !(l.range >= 0 && l.range <= 2 * kMaxCoordinate))
    ok = false, e = "range " + detail::num(l.range) + " is not within [0, " + detail::num(2 * kMaxCoordinate) + "]";
  if (!ok) error = what + ": " + e;
  return ok;
}

// A look-at camera. `far_plane` may be +infinity when `infinite_far` allows
// it; `depth_buffer`: drawn with a depth buffer (the far / near limit holds).
struct ViewCheck {
  const double* eye;
  const double* target;
  const double* up;
  double fovy_deg, aspect, near_plane, far_plane;
  bool infinite_far = false, depth_buffer = true;
};

inline bool check_view(const ViewCheck& v, const std::string& what, std::string& error) {
  std::string e;
  auto fail = [&](const std::string& m) { return error = what + ": " + m, false; };
  if (!detail::check_point("eye", v.eye, e) || !detail::check_point("target", v.target, e) ||
      !detail::check_direction("up", v.up, e))
    return fail(e);
  const double f[3] = {v.target[0] - v.eye[0], v.target[1] - v.eye[1], v.target[2] - v.eye[2]};
  const double fl = detail::length3(f), scale = std::fmax(detail::length3(v.eye), detail::length3(v.target));
  if (!(fl > 0) || fl < kMinViewLength * scale)
    return fail("the eye and the target are " + detail::num(fl) + " apart, too close to give a view direction at " +
                detail::num(scale) + " from the origin");
  const double ul = detail::length3(v.up);
  const double c[3] = {f[1] * v.up[2] - f[2] * v.up[1], f[2] * v.up[0] - f[0] * v.up[2],
                       f[0] * v.up[1] - f[1] * v.up[0]};
  if (!(detail::length3(c) >= kMinUpAngle * fl * ul))
    return fail("the up vector is parallel to the view direction (eye to target): no image orientation");
  if (!(v.fovy_deg >= kMinFovy && v.fovy_deg <= kMaxFovy))
    return fail("fovy " + detail::num(v.fovy_deg) + " is not within " + detail::num(kMinFovy) + ".." +
                detail::num(kMaxFovy) + " degrees");
  if (!(v.aspect >= kMinAspect && v.aspect <= kMaxAspect))
    return fail("aspect " + detail::num(v.aspect) + " is not within " + detail::num(kMinAspect) + ".." +
                detail::num(kMaxAspect));
  const bool infinite = v.infinite_far && std::isinf(v.far_plane) && v.far_plane > 0;
  if (!(v.near_plane > 0 && v.near_plane <= 2 * kMaxCoordinate) ||
      !(infinite || (v.far_plane > v.near_plane && v.far_plane <= 2 * kMaxCoordinate)))
    return fail("need 0 < near < far <= " + detail::num(2 * kMaxCoordinate) + " (near " + detail::num(v.near_plane) +
                ", far " + detail::num(v.far_plane) + ")");
  if (v.depth_buffer && !infinite && v.far_plane / v.near_plane > kMaxDepthRatio)
    return fail("near " + detail::num(v.near_plane) + " is too small for far " + detail::num(v.far_plane) +
                ": a 24-bit depth buffer resolves far / near up to " + detail::num(kMaxDepthRatio) +
                " (the image would be empty); use near >= " + detail::num(v.far_plane / kMaxDepthRatio));
  return true;
}

// geomview's and geombench's camera (floats; aspect from its size; drawn with depth).
inline bool check_camera(const geom::Camera& c, const std::string& what, std::string& error) {
  const double eye[3] = {c.eye[0], c.eye[1], c.eye[2]}, target[3] = {c.target[0], c.target[1], c.target[2]},
               up[3] = {c.up[0], c.up[1], c.up[2]};
  const double aspect = c.height > 0 ? double(c.width) / c.height : 0;
  return check_view({eye, target, up, c.fovy_deg, aspect, c.near_plane, c.far_plane, false, true}, what, error);
}

}  // namespace cli
