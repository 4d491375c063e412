// geomview: draws a mesh or scene with every shadow technique of the project,
// headless into PNG files (EGL) or in a window (GLFW, Dear ImGui panels) with
// an orbit camera, a HUD of pass times and error, and a grid of techniques
// side by side. Usage: geomview [FILE] [options]; `geomview --help` lists them.
//
// Files: options.* (flags, input, session), headless.cpp (PNG runs),
// window.cpp (the window app), compare.* (the grid), figures.* (pass times,
// error, the HUD's lines), ui.* (everything ImGui).
#include <cstdio>
#include <new>
#include <stdexcept>

#include "app.h"

namespace {

int run(int argc, char** argv) {
  viewer::Options options;
  if (const int code = viewer::parse_options(argc, argv, options); code >= 0) return code;
  viewer::Session session;
  std::string error;
  if (!viewer::open_session(options, session, error)) return viewer::fail(error);
  std::fprintf(stderr, "geomview: %s, %s (%zu triangles), shaders from %s\n", session.platform->description().c_str(),
               render::renderer_name(*session.state).c_str(), session.scene.triangle_count(), options.shaders.c_str());
  return session.platform->has_window() ? viewer::run_window(options, session) : viewer::run_headless(options, session);
}

}  // namespace

// A failed allocation (a size the estimate let through, a driver's own) ends
// the run with an Error: line and exit 1, as any other failure.
int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::bad_alloc&) {
    return viewer::fail("out of memory (std::bad_alloc): a smaller --size, --shadow-map-size or input");
  } catch (const std::length_error& e) {
    return viewer::fail(std::string("out of memory (") + e.what() + ")");
  }
}
