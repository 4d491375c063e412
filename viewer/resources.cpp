// resources.cpp: what a run will need, checked against the open context's
// limits and this machine's memory before any work (options.h).
#include <algorithm>
#include <string>

#include "cli/memory.h"
#include "compare.h"
#include "options.h"

namespace viewer {

bool check_resources(const Options& o, std::string& error) {
  const render::GlLimits gl = render::gl_limits();
  int width = o.view.width, height = o.view.height;
  uint64_t pixels = uint64_t(width) * uint64_t(height);
  std::string what = "the image";
  if (!o.compare.empty()) {  // the grid as compare.cpp lays it out: 2-pixel gaps
    const int cols = grid_columns(o.compare.size()), rows = int((o.compare.size() + size_t(cols) - 1) / size_t(cols));
    const uint64_t gw = uint64_t(cols) * uint64_t(width) + 2u * uint64_t(cols - 1),
                   gh = uint64_t(rows) * uint64_t(height) + 2u * uint64_t(rows - 1);
    pixels += gw * gh;
    what = "the compare grid";
    width = int(std::min<uint64_t>(gw, INT32_MAX)), height = int(std::min<uint64_t>(gh, INT32_MAX));
  }
  if (width > gl.max_image_width() || height > gl.max_image_height())
    return error = what + " is " + std::to_string(width) + "x" + std::to_string(height) +
                   " pixels, over the largest image this OpenGL can draw, " + std::to_string(gl.max_image_width()) +
                   "x" + std::to_string(gl.max_image_height()) +
                   " (GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS): a smaller --size",
           false;
  bool cube = false;
  for (const auto& list : {o.techniques, o.compare})
    for (render::Technique t : list) cube = cube || t == render::Technique::Cube;
  const int map = o.settings.shadow_map_size;
  if (map > gl.max_texture || (cube && map > gl.max_cube_map))
    return error = "--shadow-map-size " + std::to_string(map) + " is over this OpenGL's largest " +
                   (cube && map > gl.max_cube_map ? "cube-map face, " + std::to_string(gl.max_cube_map)
                                                  : "texture, " + std::to_string(gl.max_texture)),
           false;
  const uint64_t need =
      pixels * cli::kBytesPerImagePixel + uint64_t(map) * uint64_t(map) * cli::kBytesPerMapTexel * (cube ? 6u : 1u);
  const uint64_t budget = cli::memory_budget();
  if (need > budget)
    return error = what + " (" + std::to_string(o.view.width) + "x" + std::to_string(o.view.height) +
                   (o.compare.empty() ? "" : " per panel") + ") and a " + std::to_string(map) +
                   " shadow map need about " + cli::gib(need) + ", over this run's memory budget of " +
                   cli::gib(budget) + " (half of the machine's memory or of ulimit -v): a smaller --size or map",
           false;
  return true;
}

}  // namespace viewer
