// viewer/renderer.h: the renderer of geomview, one state struct and the
// functions that drive it (init, render). Everything GL lives in renderer.cpp;
// the platform (EGL / GLFW) in platform.cpp; the passes' shaders in shaders/.
//
// A frame = the technique's light passes (shadow map, cube map, extended map,
// stencil volumes...) then one shared shading pass: the technique decides lit
// or shadowed per fragment (shaders/lookup_*.frag), shaders/shade.frag shades.
// Conventions are those of geom/shadow_reference.h (camera, light, mask).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "geom/png.h"
#include "geom/scene.h"

namespace viewer {

enum class Technique { Ssm, Pcf, Esm, Edsm, Sv, SvZPass, SvZFail, Cube, Psm, Lispsm, Uniform };

// The names of --technique, in order; only techniques this build renders.
std::vector<Technique> available_techniques();
const char* technique_name(Technique t);
bool parse_technique(const std::string& name, Technique& out);  // false: unknown or unavailable

struct View {
  glm::vec3 eye{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
  float fovy_deg = 60, near_plane = 0.1f, far_plane = 1000;
  int width = 320, height = 240;
};

struct LightSetup {
  glm::vec4 position{0, 10, 0, 1};  // w = 1 point light, w = 0 direction towards a light at infinity
  bool spot = false;
  glm::vec3 spot_direction{0, -1, 0};  // where the spot shines
  float spot_angle_deg = 45;           // axis to cone edge
};

enum class Output { Color, Mask };

struct PassTime {
  std::string pass;
  double ms = 0;
};

struct FrameSettings {
  Technique technique = Technique::Ssm;
  Output output = Output::Color;
  int shadow_map_size = 1024;
  bool inspect = false;  // overlay: silhouette quads, topology problems, focus body (colour output only)
};

struct State;  // the one state struct (GL objects, buffers, cached programs)

struct StateDeleter {
  void operator()(State* s) const;
};
using StatePtr = std::unique_ptr<State, StateDeleter>;

// Uploads the scene's triangles (the current GL context must stay current for
// the life of the state). `shader_dir` holds the shaders/ files.
StatePtr create_state(const geom::Scene& scene, const std::string& shader_dir, std::string& error);

// Reads a baked container (geom/baked_reader.h, written by `geombake bake`) and
// draws its buffers: the welded triangles (`positions`, `indices`) as the scene,
// its ESM quads, shadow volume and adjacency buffer as one caster, as they lie.
// `scene` receives the triangles and the baked static lights (for a default
// light and the reference). Every index in the file is checked before upload.
StatePtr create_state_baked(const void* bytes, size_t size, const std::string& shader_dir, geom::Scene& scene,
                            std::string& error);

// Renders one frame into an offscreen framebuffer of view.width x view.height and
// reads it back into `image` (Output::Mask: 1 channel, 255 lit / 0 shadow / 128
// background; Output::Color: 3 channels), top row first. `times` receives the time
// of each pass (GPU timer queries, or CPU wall time around glFinish on a software
// rasterizer: see timing_kind()).
bool render(State& state, const View& view, const LightSetup& light, const FrameSettings& settings,
            geom::PngImage& image, std::vector<PassTime>& times, std::string& error);

// Draws the frame into the default framebuffer (window mode), no read back.
bool render_to_window(State& state, const View& view, const LightSetup& light, const FrameSettings& settings,
                      int width, int height, std::vector<PassTime>& times, std::string& error);

std::string renderer_name(State& state);  // GL_RENDERER
std::string timing_kind(State& state);    // "GPU timer queries" or "wall time around glFinish (software)"

// Bounding sphere of the scene (centre xyz, radius), for default cameras and light frusta.
glm::vec4 scene_bounds(const State& state);

// The default camera: the scene's bounding sphere seen from above, front and right.
View default_view(const State& state, int width, int height);

}  // namespace viewer
