// cube_faces.cpp: the six 90-degree view-projection matrices of an
// omnidirectional (cube map) shadow, seed 003_478065b2696af70d.txt
// (Gerasimov, "Omnidirectional Shadow Mapping", Sect. 12.3.3: "The field of
// view must be 90 degrees ... view matrices from the up, down, east, west,
// north, and south vectors"). Face orientation follows the OpenGL cube-map
// face table (spec 4.5, Table 8.19): +X looks down +x with up -y, -X down -x
// with up -y, +Y down +y with up +z, -Y down -y with up -z, +Z down +z with
// up -y, -Z down -z with up -y.
#include <cmath>

#include "focus_math.h"
#include "geom/focus.h"

namespace geom {

using namespace focus;

void focus_cube_faces(const double position[3], double near_dist, double far_dist, double matrices[6][16]) {
  static const double looks[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const double ups[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  V3 eye(position);
  bool ok = finite(eye) && std::isfinite(near_dist) && std::isfinite(far_dist) && near_dist > 0 && far_dist > near_dist;
  if (!ok) {  // documented misuse: identity matrices, never NaN
    eye = V3(0, 0, 0);
    near_dist = 1;
    far_dist = 2;
  }
  // gluPerspective(90 degrees, 1, near, far): cot(45 degrees) = 1.
  M4 proj = M4::zero();
  proj.at(0, 0) = 1;
  proj.at(1, 1) = 1;
  proj.at(2, 2) = (far_dist + near_dist) / (near_dist - far_dist);
  proj.at(2, 3) = 2 * far_dist * near_dist / (near_dist - far_dist);
  proj.at(3, 2) = -1;
  for (int f = 0; f < 6; ++f) {
    V3 fwd(looks[f]), up(ups[f]);
    V3 side = cross(fwd, up);  // gluLookAt: s = f x up, u = s x f, rows s, u, -f
    M4 view = frame(side, cross(side, fwd), -fwd, eye);
    M4 m = ok ? proj * view : M4::identity();
    for (int i = 0; i < 16; ++i) matrices[f][i] = m.m[i];
  }
}

int focus_cube_face_of(const double direction[3]) {
  double ax = std::fabs(direction[0]), ay = std::fabs(direction[1]), az = std::fabs(direction[2]);
  if (!(std::isfinite(ax) && std::isfinite(ay) && std::isfinite(az))) return -1;
  if (ax == 0 && ay == 0 && az == 0) return -1;
  int axis = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  return 2 * axis + (std::signbit(direction[axis]) ? 1 : 0);
}

}  // namespace geom
