// scene.cpp: the conversions of geom/scene.h's Light and Camera: the
// homogeneous light the shaders take, and a camera's matrices
// (gluLookAt + gluPerspective, OpenGL's clip space).
#include "geom/scene.h"

#include <cmath>

#include "focus_math.h"

namespace geom {

using namespace focus;

void light_homogeneous(const Light& light, double out[4]) {
  if (light.type == LightType::Directional) {
    for (int k = 0; k < 3; ++k) out[k] = -light.direction[k];
    out[3] = 0;
  } else {
    for (int k = 0; k < 3; ++k) out[k] = light.position[k];
    out[3] = 1;
  }
}

Light light_from_homogeneous(const double h[4]) {
  Light l;
  if (h[3] == 0) {
    l.type = LightType::Directional;
    for (int k = 0; k < 3; ++k) l.direction[k] = -h[k];
  } else {
    l.type = LightType::Point;
    for (int k = 0; k < 3; ++k) l.position[k] = h[k] / h[3];
  }
  return l;
}

Light light_from_scene(const std::vector<Light>& lights) {
  if (!lights.empty()) return lights.front();
  const double towards[4] = {0.4f, 1.0f, 0.6f, 0};
  return light_from_homogeneous(towards);
}

CameraMatrices camera_look_at(const double eye[3], const double target[3], const double up[3], double fovy_degrees,
                              double aspect, double near_dist, double far_dist) {
  CameraMatrices cam;
  V3 e(eye), fwd = normalize(V3(target) - e);
  V3 side = normalize(cross(fwd, V3(up)));
  M4 view = frame(side, cross(side, fwd), -fwd, e);
  double t = 1 / std::tan(fovy_degrees * kPi / 360);
  M4 proj = M4::zero();
  proj.at(0, 0) = t / aspect;
  proj.at(1, 1) = t;
  proj.at(3, 2) = -1;
  if (std::isinf(far_dist)) {
    proj.at(2, 2) = -1;
    proj.at(2, 3) = -2 * near_dist;
  } else {
    proj.at(2, 2) = (far_dist + near_dist) / (near_dist - far_dist);
    proj.at(2, 3) = 2 * far_dist * near_dist / (near_dist - far_dist);
  }
  // Degenerate input (eye == target, up parallel to the view) leaves zeros or
  // NaN here, which compute_focus reports as invalid input.
  if (!(length(side) > 0) || !(fovy_degrees > 0 && fovy_degrees < 180) || !(aspect > 0)) proj.at(0, 0) = NAN;
  for (int i = 0; i < 16; ++i) cam.view[i] = view.m[i], cam.projection[i] = proj.m[i];
  return cam;
}

CameraMatrices camera_from_matrices(const float view[16], const float projection[16]) {
  CameraMatrices cam;
  for (int i = 0; i < 16; ++i) cam.view[i] = view[i], cam.projection[i] = projection[i];
  return cam;
}

}  // namespace geom
