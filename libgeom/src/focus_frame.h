// focus_frame.h (private): one frame of compute_focus as its steps share it
// (geom/focus.h): the inputs as half-spaces and bodies (focus_frame.cpp: the
// inputs checked, S, L, V, the near plane), and the light matrices built from
// them (light_matrix.cpp: uniform, PSM, LiSPSM). compute_focus.cpp runs the
// steps. Working memory: one Frame per thread, reused frame after frame.
#pragma once
#include <cmath>
#include <vector>

#include "focus_body.h"
#include "focus_math.h"
#include "geom/focus.h"

namespace geom {
namespace focus {

struct Frame {
  // camera
  M4 view, view_inv, proj;
  bool perspective = true;
  double cam_near = 0, cam_far = 0;  // far may be +inf
  V3 eye, view_dir;
  // light
  bool directional = false;
  V3 light_pos;           // point, spot
  V3 towards_light;       // directional: unit vector towards the light
  V3 light_axis;          // point, spot: the light frustum's axis (unit)
  double light_near = 0;  // point, spot: L's near plane, at the floor (near_plane_cut)
  // bodies
  std::vector<Plane> s_planes, l_planes, r_planes, hull_clip, v_planes, hull_clip_planes;
  Polytope receivers, body, scratch;
  std::vector<V3> r_verts, h_verts, hull_points;
  double eps = 0, scale = 1;
};

inline void set_fallback(FocusResult& out, FocusFallback f, const char* reason) {
  if (f > out.fallback) {
    out.fallback = f;
    out.reason = reason;
  }
}

inline double depth_of(const Frame& fr, V3 p) { return -mul_point(fr.view, p).z; }

// The centre of the bounding box of pts: unlike the vertex centroid it does not
// move when clipping leaves an extra vertex in the middle of an edge, so the
// axes chosen from it are stable from frame to frame.
inline V3 box_centre(const std::vector<V3>& pts) {
  V3 lo(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
  for (V3 p : pts) {
    lo = V3(std::fmin(lo.x, p.x), std::fmin(lo.y, p.y), std::fmin(lo.z, p.z));
    hi = V3(std::fmax(hi.x, p.x), std::fmax(hi.y, p.y), std::fmax(hi.z, p.z));
  }
  return (lo + hi) * 0.5;
}

// focus_frame.cpp
// Fills `fr` from the inputs; false (with the reason in `out`) for invalid input.
bool setup(const CameraMatrices& cam, const Light& light, FocusBox box, const FocusOptions& opt, Frame& fr,
           FocusResult& out);
// Corners of V, cut at the far side of S (no receiver lies beyond it; this is
// what lets an infinite far plane work). False when V n S is empty.
bool view_frustum(const Frame& fr, V3 corners[8]);
// Point, spot: L's near half-space at its floor, R (fr.receivers) cut by it.
void near_plane_cut(Frame& fr, const Light& light, const FocusOptions& opt, FocusResult& out);

// light_matrix.cpp
// F * C, with F mapping the image of `pts` under C onto the unit cube (depth
// flipped when asked). False when a point has w <= 0 or the result is not finite.
bool fit(const M4& chain, const std::vector<V3>& pts, bool flip_depth, M4& out);
// Rows (x, y, axis) at `origin`: x = axis x hint, y = x x axis.
M4 axis_frame(V3 origin, V3 axis, V3 hint);
// The uniform (unwarped) matrix of H (fr.h_verts), PSM's and LiSPSM's; the
// last two false (with the fallback set in `out`) when they cannot warp.
bool uniform_matrix(const Frame& fr, M4& out);
bool psm_matrix(const Frame& fr, const FocusOptions& opt, FocusResult& out, M4& result);
bool lispsm_matrix(const Frame& fr, const FocusOptions& opt, FocusResult& out, M4& result);

}  // namespace focus
}  // namespace geom
