// A program outside the project that uses an installed geom (tests/install/run.sh):
// built once through find_package(geom) and once through pkg-config. It imports
// a mesh (an archive member pulls in libzip), bakes it, reads the bytes back with
// the header-only reader, and computes a PSM matrix (CGAL's hull), printing one line.
#include <geom/bake.h>
#include <geom/baked_reader.h>
#include <geom/baked_writer.h>
#include <geom/focus.h>
#include <geom/import.h>
#include <geom/version.h>

#include <cstdio>
#include <vector>

#if !defined(GEOM_VERSION_NUMBER) || GEOM_VERSION_NUMBER < 100
#error "geom/version.h: GEOM_VERSION_NUMBER missing"
#endif

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer MESH\n");
    return 2;
  }
  const geom::ImportResult r = geom::import_file(argv[1]);
  if (!r.ok) {
    std::fprintf(stderr, "Error: %s\n", r.error.c_str());
    return 1;
  }
  const geom::BakeResult b = geom::bake_scene(r.scene, "mesh", {});
  std::vector<unsigned char> bytes;
  std::string error;
  if (!b.ok || !geom::serialize_baked(b.sections, bytes, error)) {
    std::fprintf(stderr, "Error: %s: %s\n", argv[1], b.ok ? error.c_str() : b.error.c_str());
    return 1;
  }
  geom::baked::Reader reader;
  if (!reader.open(bytes.data(), bytes.size())) {
    std::fprintf(stderr, "Error: %s: the baked bytes do not read back: %s\n", argv[1], reader.error().c_str());
    return 1;
  }
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
  std::printf("geom %s: %zu triangles, %zu sections, %zu bytes, focus %s\n", GEOM_VERSION, r.scene.triangle_count(),
              reader.sections().size(), bytes.size(), geom::focus_method_name(focus.method));
  return 0;
}
