// options.h: geomview's command line (flags, techniques, camera, light, the
// shaders folder) and its input (a baked container or a file imported and
// baked in process) with the GL context and the render state.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "geom/scene.h"
#include "render/platform.h"
#include "render/render.h"

namespace viewer {

// The flags' ranges; what the GL context can hold is checked again once it is
// open (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS).
constexpr int kMinMapSize = 16, kMaxMapSize = 16384, kMaxImageSize = 16384;

struct Options {
  std::string file;                           // the input (the bundled default scene when absent)
  std::vector<render::Technique> techniques;  // --technique (pcf when absent)
  std::vector<render::Technique> compare;     // --compare: the grid's panels (empty: no grid)
  render::FrameSettings settings;
  geom::Camera view;  // after resolve_camera: the default framing, then --eye ... --far
  geom::Light light;  // after resolve_light: the file's first light, then --light, --spot
  int up_axis = -1;   // --up-axis x|y|z (0 1 2); -1: from the format (Quake 3's BSP and MD3: z)
  bool size_given = false;
  int frames = 1;
  bool window = false;
  bool hud = false;    // headless: the HUD drawn into the PNG, its lines on stdout
  bool error = false;  // measure the error against the ray-cast reference (HUD, CLI, grid)
  std::string out_path, shaders;
  std::string script;      // --script KEYS: keys fed to the window, one per frame (tests, screenshots)
  std::string screenshot;  // --screenshot FILE.png: the window's last frame, then quit
  std::vector<std::string> camera_flags[6];  // --eye --target --up --fovy --near --far, applied after framing
  std::string light_flag, spot_flag;
};

// Parses argv into `o`. Returns -1 to go on, else the exit code (help printed,
// or an Error: line written).
int parse_options(int argc, char** argv, Options& o);

// The shaders folder: --shaders, $GEOMVIEW_SHADERS, ../share/geom/shaders beside
// the binary (an installed bin/), the source tree's shaders/, the configured
// install folder; the first that holds shade.frag (--shaders and the variable
// are taken as given).
std::string find_shaders(const std::string& flag);

// The up axis of a file: 2 for Quake 3's formats (.bsp, .md3), 1 otherwise.
int format_up_axis(const std::string& path);

// The input, its GL context and render state.
struct Session {
  std::unique_ptr<render::Platform> platform;
  geom::Scene scene;  // the triangles (for the reference) and lights
  render::StatePtr state;
  int up_axis = 1;
};

// Loads the input, opens the context (a window when o.window), creates the
// state, frames the camera and resolves the light. Error: message, false.
bool open_session(Options& o, Session& s, std::string& error);

// Checks, once the context is open, the image (or grid) and shadow-map sizes
// against its limits and the memory the run needs against this machine's
// (cli/memory.h). Error: message, false.
bool check_resources(const Options& o, std::string& error);

// The default framing of the current scene (the reset key).
geom::Camera framed_view(const Session& s, int width, int height);

int fail(const std::string& message);  // Error: line, exit code 1

}  // namespace viewer
