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
  // With a casters' hull: S as a body (the box cut by the hull's planes, once
  // per frame), which R and H start from instead of clipping by S's planes.
  bool s_hull = false;
  Polytope s_body;
  std::vector<V3> r_verts, h_verts, hull_points;
  double eps = 0, scale = 1;
  V3 box[8];                // S's corners in frustum_polytope's order
  Polytope all_receivers;   // point, spot: R before L's near plane cut it
  size_t range_planes = 0;  // l_planes before the near plane: the range (and a spot's cone)
  double cone_cos = 1;      // point, spot: the cosine of the widest ray of H from the light around its axis
  // cube_faces.cpp's working memory
  std::vector<Plane> face_planes, face_clip;
  Polytope face_receivers;
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

// S's eight corners in frustum_polytope's order (0-3 at S's largest z, then the smallest).
inline void scene_corners(const Frame& fr, V3 out[8]) {
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = -fr.s_planes[2 * k].d, hi[k] = fr.s_planes[2 * k + 1].d;
  for (int i = 0; i < 8; ++i) {
    int b = (i & 3) == 1 || (i & 3) == 2 ? 1 : 0, t = (i & 3) >= 2 ? 1 : 0;
    out[i] = V3(b ? hi[0] : lo[0], t ? hi[1] : lo[1], i >= 4 ? lo[2] : hi[2]);
  }
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
// `ease` scales their warp distance (PSM's virtual near plane, LiSPSM's n):
// 1 is the paper's warp, larger is weaker.
bool uniform_matrix(const Frame& fr, M4& out);
bool psm_matrix(const Frame& fr, const FocusOptions& opt, double ease, FocusResult& out, M4& result);
bool lispsm_matrix(const Frame& fr, const FocusOptions& opt, double ease, FocusResult& out, M4& result);
// The matrix of opt.method with its fallbacks (uniform where the camera is
// orthographic or the method cannot warp); sets out.method. False only when
// not even the uniform fit is finite.
bool method_matrix(const Frame& fr, const FocusOptions& opt, FocusResult& out, M4& result);

// cube_faces.cpp
// Point light: the six faces of out.cube_faces fitted to H's part in each
// direction (geom/focus.h FocusFace), from fr.all_receivers; sets out.cube.
// Uses fr's h_verts, r_verts, light_axis and light_near as working memory.
void cube_focus(Frame& fr, const FocusOptions& opt, FocusResult& out);

}  // namespace focus
}  // namespace geom
