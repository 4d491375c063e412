// geom::focus's consumer (tests/install/run.sh): a focused light matrix for a
// camera and a directional light (CGAL's hull inside).
#include <geom/focus.h>

#include <cstdio>

int main() {
  const double eye[3] = {0, 2, 5}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
  const geom::CameraMatrices camera = geom::camera_look_at(eye, target, up, 60, 1.5, 0.1, 100);
  geom::Light light;
  light.type = geom::LightType::Directional;
  light.direction[0] = 0.3, light.direction[1] = -1, light.direction[2] = 0.2;
  const geom::FocusBox box = {{-2, -2, -2}, {2, 2, 2}};
  geom::FocusResult focus;
  if (!geom::compute_focus(camera, light, box, {}, focus)) {
    std::fprintf(stderr, "Error: compute_focus failed: %s\n", focus.reason);
    return 1;
  }
  std::printf("focus: %s\n", geom::focus_method_name(focus.method));
  return 0;
}
