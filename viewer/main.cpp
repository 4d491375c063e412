// geomview: draws a mesh or scene with every shadow technique of the project,
// headless into PNG files (EGL) or in a window (GLFW, Dear ImGui panels) with
// an orbit camera, a HUD of pass times and error, and a grid of techniques
// side by side. Usage: geomview [FILE] [options]; `geomview --help` lists them.
//
// Files: options.* (flags, input, session), headless.cpp (PNG runs),
// window.cpp (the window app), compare.* (the grid), figures.* (pass times,
// error, the HUD's lines), ui.* (everything ImGui).
#include <cstdio>

#include "app.h"

int main(int argc, char** argv) {
  viewer::Options options;
  if (const int code = viewer::parse_options(argc, argv, options); code >= 0) return code;
  viewer::Session session;
  std::string error;
  if (!viewer::open_session(options, session, error)) return viewer::fail(error);
  std::fprintf(stderr, "geomview: %s, %s (%zu triangles), shaders from %s\n", session.platform->description().c_str(),
               render::renderer_name(*session.state).c_str(), session.scene.triangle_count(), options.shaders.c_str());
  return session.platform->has_window() ? viewer::run_window(options, session) : viewer::run_headless(options, session);
}
