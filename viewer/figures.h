// figures.h: what the HUD, the grid's labels and the CLI report of one frame:
// its technique, map size, pass times and its error against the exact
// reference (geom/shadow_reference.h), scored as geombench scores it. The HUD
// and the CLI print the same lines (hud_lines).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geom/scene.h"
#include "geom/shadow_reference.h"
#include "render/render.h"

namespace viewer {

struct ErrorFigures {
  bool valid = false;
  double visible = 0, boundary = 0;  // error_visible, error_boundary
  bool has_classes = false;
  double cast = 0, self = 0;  // error_cast, error_self (per class)
  size_t visible_pixels = 0, boundary_pixels = 0;
};

struct Figures {
  render::Technique technique = render::Technique::Ssm;
  int map_size = 0;        // 0: a technique without a map
  std::string projection;  // what the frame drew (render::drawn_projection): "6 faces", "lispsm n=2.1"...
  std::vector<render::PassTime> times;
  bool gpu_timers = false;
  std::string message;  // "needs a point light" etc. instead of a frame
  ErrorFigures error;
};

// The shadow passes' time: every pass but the camera's shading, the
// inspection and the one-off bake (geombench's time_ms).
double shadow_ms(const std::vector<render::PassTime>& times);
double total_ms(const std::vector<render::PassTime>& times);
// The shadow passes' pipeline statistics (render::shadow_counters): "1200
// primitives, 3600 vs, 0 gs, 51000 fs invocations"; "" where the context has none.
std::string counter_text(const std::vector<render::PassTime>& times);

// The HUD's lines: "pcf 1024 | 6 faces" (technique, map size, the projection drawn); "shadow 1.23 ms, frame 2.50 ms
// (GPU)", or
// "(wall)" for wall time around glFinish on a software rasterizer; the
// error_lines; then each pass's time and "shadow passes: " counter_text.
std::vector<std::string> hud_lines(const Figures& f, bool passes = true);
// "error 0.520% visible, 3.10% boundary" and "per class: 0.400% cast, 0.100% self".
std::vector<std::string> error_lines(const ErrorFigures& e);

// The same figures in lines of at most about 22 characters, for small grid panels.
std::vector<std::string> compact_lines(const Figures& f);

// The exact reference of one camera and light (its objects: the connected
// components of the scene, as geombench takes them).
struct Reference {
  geom::ShadowReference ref;
};
bool make_reference(const geom::Scene& scene, const geom::Camera& camera, const geom::Light& light, Reference& out,
                    std::string& error);

// Scores a mask (255 lit, 0 shadow, 128 no geometry; reference layout) with
// geom/shadow_error.h: error_visible, error_boundary, error_cast, error_self. With
// `overlay`, an RGBA image of the wrong pixels: red where the technique
// shadows a lit pixel, blue where it lights a shadowed one, transparent
// elsewhere.
ErrorFigures score(const std::vector<uint8_t>& mask, const Reference& ref, std::vector<uint8_t>* overlay = nullptr);

// Renders the technique's mask from `camera` and scores it.
bool measure_error(render::State& state, const Reference& ref, const geom::Camera& camera, const geom::Light& light,
                   render::FrameSettings settings, ErrorFigures& out, std::vector<uint8_t>* overlay,
                   std::string& error);

}  // namespace viewer
