// compare.cpp: the grid of techniques (compare.h).
#include "compare.h"

#include <algorithm>
#include <cmath>

namespace viewer {

int grid_columns(size_t n) { return n <= 3 ? int(n) : n == 4 ? 2 : n <= 9 ? 3 : 4; }

bool render_grid(render::State& state, const geom::Scene& scene, const std::vector<render::Technique>& techniques,
                 const geom::Camera& view, const geom::Light& light, const render::FrameSettings& settings,
                 bool with_error, Grid& g, std::string& error) {
  const size_t n = techniques.size();
  if (n == 0) return error = "no technique to compare", false;
  const int gap = 2;
  g.columns = grid_columns(n), g.rows = int((n + size_t(g.columns) - 1) / size_t(g.columns));
  g.panel_w = view.width, g.panel_h = view.height;
  const int W = g.columns * view.width + (g.columns - 1) * gap, H = g.rows * view.height + (g.rows - 1) * gap;
  g.image.width = W, g.image.height = H, g.image.channels = 3;
  g.image.pixels.assign(size_t(W) * H * 3, 12);
  g.labels.clear(), g.figures.clear();
  Reference ref;
  if (with_error && !make_reference(scene, view, light, ref, error)) return false;
  const bool gpu = render::timing_kind(state).rfind("GPU", 0) == 0;
  for (size_t i = 0; i < n; ++i) {
    const int x0 = int(i % size_t(g.columns)) * (view.width + gap),
              y0 = int(i / size_t(g.columns)) * (view.height + gap);
    Figures f;
    f.technique = techniques[i];
    f.map_size = settings.shadow_map_size;
    f.gpu_timers = gpu;
    render::FrameSettings s = settings;
    s.technique = techniques[i];
    s.output = render::Output::Color;
    geom::PngImage panel;
    if (render::technique_needs_point_light(f.technique) && light.type == geom::LightType::Directional) {
      f.message = "needs a point or spot light";
    } else {
      std::vector<render::PassTime> warm;
      if (!render::render(state, view, light, s, panel, warm, error) ||
          !render::render(state, view, light, s, panel, f.times, error))
        return error = std::string(render::technique_name(f.technique)) + ": " + error, false;
      f.projection = render::drawn_projection(state);
      if (with_error && !measure_error(state, ref, view, light, s, f.error, nullptr, error)) return false;
      for (int y = 0; y < view.height; ++y)
        std::copy_n(panel.pixels.data() + size_t(y) * view.width * 3, size_t(view.width) * 3,
                    g.image.pixels.data() + (size_t(y0 + y) * W + x0) * 3);
    }
    Label l;
    l.x = x0 + 6, l.y = y0 + 6;
    l.clip[0] = x0, l.clip[1] = y0, l.clip[2] = x0 + view.width, l.clip[3] = y0 + view.height;
    l.lines = view.width < 340 ? compact_lines(f) : hud_lines(f, false);  // readable in a small panel
    g.labels.push_back(l);
    g.figures.push_back(f);
  }
  return true;
}

}  // namespace viewer
