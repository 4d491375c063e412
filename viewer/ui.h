// ui.h: everything geomview draws with Dear ImGui (ui.cpp is the one file that
// includes ImGui): the window's panels, HUD and legend; the grid's labels;
// and, headless, labels drawn into an image through an offscreen framebuffer
// (ImGui's OpenGL 3 backend without GLFW, DisplaySize fed by hand). No ImGui
// type appears here.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "figures.h"
#include "geom/png.h"
#include "render/render.h"

namespace viewer {

// A box of text lines at (x, y) pixels from the top left; a line may have a
// colour swatch before it (the legend).
struct Label {
  int x = 0, y = 0;
  std::vector<std::string> lines;
  std::vector<std::array<float, 4>> swatches;  // per line, alpha 0: none
  int clip[4] = {0, 0, 0, 0};                  // x0 y0 x1 y1: drawn only inside (a grid panel); x1 0: no clip
};

// The legend of the inspection overlay: each colour with its count.
Label legend_label(const render::InspectionCounts& counts, int x, int y);

// Headless: draws `labels` over `image` (RGB or grey, converted to RGB).
// Needs a current GL 4.5 context.
bool draw_labels(geom::PngImage& image, const std::vector<Label>& labels, std::string& error);

// What the window's panels show and edit (window.cpp owns it).
struct WindowModel {
  std::vector<render::Technique> all;  // the techniques of this build
  size_t current = 0;
  render::FrameSettings settings;
  int light_kind = 0;  // 0 point, 1 spot, 2 directional
  float light_position[3] = {0, 0, 0};
  bool compare = false;
  std::vector<bool> compare_pick;  // per technique in `all`
  Figures figures;                 // the current frame's
  bool counts_valid = false;
  render::InspectionCounts counts;
  bool show_panels = true, show_error_overlay = true;
  std::string status;  // the last warning
  // The error overlay (RGBA, the framebuffer's size) and the grid, as textures.
  unsigned overlay_texture = 0, grid_texture = 0;
  int overlay_w = 0, overlay_h = 0, grid_w = 0, grid_h = 0;
  std::vector<Label> grid_labels;
  // Actions asked for by the panels this frame.
  bool reset_camera = false, measure = false, light_changed = false, quit = false;
};

bool ui_init_window();  // over the current GLFW window (glfwGetCurrentContext)
void ui_shutdown();
bool ui_wants_mouse();
bool ui_wants_keyboard();
void ui_window_frame(WindowModel& m, int width, int height);  // builds and draws the panels into framebuffer 0

// A texture from RGBA pixels, top row first (re-created; `texture` 0: new).
unsigned ui_upload_rgba(unsigned texture, const uint8_t* rgba, int width, int height);
void ui_delete_texture(unsigned texture);
// The current framebuffer 0 read back (RGB, top row first).
bool ui_read_window(int width, int height, geom::PngImage& image);

}  // namespace viewer
