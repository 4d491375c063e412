// cube_faces.cpp: the six 90-degree view-projection matrices of an
// omnidirectional (cube map) shadow, and their fit to what each face must hold.
//
// References:
//   Gerasimov 2004, "Omnidirectional Shadow Mapping" (GPU Gems, ch. 12),
//   Sect. 12.3.3: "The field of view must be 90 degrees ... view matrices from
//   the up, down, east, west, north, and south vectors". Face orientation
//   follows the OpenGL cube-map face table (spec 4.5, Table 8.19): +X looks
//   down +x with up -y, -X down -x with up -y, +Y down +y with up +z, -Y down
//   -y with up -z, +Z down +z with up -y, -Z down -z with up -y.
//   Stamminger and Drettakis 2002, "Perspective Shadow Maps", Sect. 1 (an
//   omnidirectional point light needs several maps; the focusing of a spot
//   light carries over to each) and Sect. 4.1 (H = conv(V u {l}) n S n L):
//   each face is focused as a spot light whose frustum is the face's square
//   pyramid, H_i = conv(R_i u {l}) n S n L_i with R_i the receivers in the
//   face's direction. Its near and far planes are H_i's nearest and farthest
//   points along the face's axis (near at least the floor of geom/focus.h).
#include <cmath>

#include "focus_frame.h"
#include "geom/focus.h"

namespace geom {

using namespace focus;

namespace {

const double kLooks[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const double kUps[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

// Face f's gluPerspective(90 degrees, 1, near, far) * gluLookAt (0 < near < far).
M4 face_matrix(V3 eye, int f, double near_dist, double far_dist) {
  M4 proj = M4::zero();  // cot(45 degrees) = 1
  proj.at(0, 0) = 1;
  proj.at(1, 1) = 1;
  proj.at(2, 2) = (far_dist + near_dist) / (near_dist - far_dist);
  proj.at(2, 3) = 2 * far_dist * near_dist / (near_dist - far_dist);
  proj.at(3, 2) = -1;
  V3 fwd(kLooks[f]), up(kUps[f]);
  V3 side = cross(fwd, up);  // gluLookAt: s = f x up, u = s x f, rows s, u, -f
  return proj * frame(side, cross(side, fwd), -fwd, eye);
}

void copy16(const M4& m, double out[16]) {
  for (int i = 0; i < 16; ++i) out[i] = m.m[i];
}

// H_i (fr.body, its vertices in fr.h_verts) of the receivers fr.face_receivers
// and the half-spaces fr.face_clip (S, the range, the pyramid, the floor);
// `pyramid` the four planes through the light. False when H_i is empty.
bool face_body(Frame& fr, V3 axis, const Plane pyramid[4]) {
  unique_vertices(fr.face_receivers, fr.eps, fr.r_verts);
  if (fr.r_verts.empty()) return false;
  fr.face_planes.assign(fr.v_planes.begin(), fr.v_planes.end());
  fr.face_planes.insert(fr.face_planes.end(), pyramid, pyramid + 4);
  if (!focus_by_planes(fr.r_verts, fr.light_pos, false, axis, fr.face_planes.data(), fr.face_planes.size(),
                       fr.face_clip.data(), fr.face_clip.size(), fr.box, fr.eps, fr.hull_clip_planes, fr.body,
                       fr.scratch))
    focus_hull(fr.face_receivers, fr.light_pos, false, 0, fr.face_clip.data(), fr.face_clip.size(), fr.eps,
               fr.hull_points, fr.body, fr.scratch);
  unique_vertices(fr.body, fr.eps, fr.h_verts);
  return !fr.h_verts.empty();
}

}  // namespace

void focus_cube_faces(const double position[3], double near_dist, double far_dist, double matrices[6][16]) {
  V3 eye(position);
  bool ok = finite(eye) && std::isfinite(near_dist) && std::isfinite(far_dist) && near_dist > 0 && far_dist > near_dist;
  for (int f = 0; f < 6; ++f) copy16(ok ? face_matrix(eye, f, near_dist, far_dist) : M4::identity(), matrices[f]);
}

namespace focus {

void cube_focus(Frame& fr, const FocusOptions& opt, FocusResult& out) {
  out.cube = true;
  // The floor of every face's near plane: FocusOptions::light_near, or 1e-3
  // of the farthest receiver's distance from the light (depth precision).
  unique_vertices(fr.all_receivers, fr.eps, fr.r_verts);
  double farthest = 0;
  for (V3 p : fr.r_verts) farthest = std::fmax(farthest, length(p - fr.light_pos));
  double floor = opt.light_near > 0 ? opt.light_near : 1e-3 * farthest;
  if (!(floor > fr.eps)) floor = std::fmax(fr.light_near, 2 * fr.eps);
  thread_local FocusResult scratch;
  for (int f = 0; f < 6; ++f) {
    FocusFace& face = out.cube_faces[f];
    V3 axis(kLooks[f]);
    // The face's closed square pyramid: dot(d, axis) >= |dot(d, b)| for the other two axes b.
    Plane pyramid[4];
    int k = 0;
    for (int b = 0; b < 3; ++b) {
      if (axis[b] != 0) continue;
      V3 e(b == 0, b == 1, b == 2);
      pyramid[k++] = plane_through(fr.light_pos, normalize(axis + e));
      pyramid[k++] = plane_through(fr.light_pos, normalize(axis - e));
    }
    Plane floor_plane = plane_through(fr.light_pos + axis * floor, axis);
    fr.face_clip.assign(fr.s_planes.begin(), fr.s_planes.end());
    fr.face_clip.insert(fr.face_clip.end(), fr.l_planes.begin(), fr.l_planes.begin() + fr.range_planes);
    fr.face_clip.insert(fr.face_clip.end(), pyramid, pyramid + 4);
    fr.face_clip.push_back(floor_plane);
    fr.face_receivers = fr.all_receivers;
    clip_polytope(fr.face_receivers, pyramid, 4, fr.eps, fr.scratch);
    clip_polytope(fr.face_receivers, floor_plane, fr.eps, fr.scratch);
    if (fr.face_receivers.empty() || !face_body(fr, axis, pyramid)) continue;  // empty: nothing to render
    double n = HUGE_VAL, far_d = 0;
    for (V3 p : fr.h_verts) {
      double d = dot(p - fr.light_pos, axis);
      n = std::fmin(n, d);
      far_d = std::fmax(far_d, d);
    }
    n = std::fmax(n, floor);
    if (!(far_d > n * (1 + 1e-9))) far_d = n * (1 + 1e-6);
    face.empty = false;
    face.near = n;
    face.far = far_d;
    copy16(face_matrix(fr.light_pos, f, n, far_d), face.matrix);
    // The requested method on H_i, the face's pyramid as the light's frustum.
    fr.light_axis = axis;
    fr.light_near = floor;
    scratch.fallback = FocusFallback::None;
    scratch.reason = "";
    M4 m;
    if (method_matrix(fr, opt, scratch, m)) copy16(m, face.focused);
    face.method = scratch.method;
    face.fallback = scratch.fallback;
    face.reason = scratch.reason;
    face.lispsm_n = scratch.method == FocusMethod::Lispsm ? scratch.lispsm_n : 0;
    face.psm_near = scratch.method == FocusMethod::Psm ? scratch.psm_near : 0;
  }
}

}  // namespace focus

int focus_cube_face_of(const double direction[3]) {
  double ax = std::fabs(direction[0]), ay = std::fabs(direction[1]), az = std::fabs(direction[2]);
  if (!(std::isfinite(ax) && std::isfinite(ay) && std::isfinite(az))) return -1;
  if (ax == 0 && ay == 0 && az == 0) return -1;
  int axis = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  return 2 * axis + (std::signbit(direction[axis]) ? 1 : 0);
}

}  // namespace geom
