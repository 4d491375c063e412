// compare.h: techniques side by side. One camera and light, one panel per
// technique (2 to 20), each labelled with its technique, map size, shadow
// pass time and error against the exact reference (computed once for the
// grid); headless into one PNG (--compare), and as the window's grid (C).
#pragma once
#include <string>
#include <vector>

#include "figures.h"
#include "geom/png.h"
#include "ui.h"

namespace viewer {

struct Grid {
  int columns = 0, rows = 0, panel_w = 0, panel_h = 0;
  geom::PngImage image;  // RGB, the panels without labels
  std::vector<Label> labels;
  std::vector<Figures> figures;  // per panel, in order
};

// Columns for n panels: 1-3 in a row, 4 as 2x2, 5-9 in rows of 3, 10-16 in rows of 4.
int grid_columns(size_t n);

// Renders every technique at panel_view's size (a warm-up frame, then the
// measured one); with `measure_error`, scores each against one reference.
bool render_grid(render::State& state, const geom::Scene& scene, const std::vector<render::Technique>& techniques,
                 const geom::Camera& panel_view, const geom::Light& light, const render::FrameSettings& settings,
                 bool measure_error, Grid& out, std::string& error);

}  // namespace viewer
