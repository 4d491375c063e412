// figures.cpp: pass times, the error against the reference, the HUD's lines.
#include "figures.h"

#include <algorithm>
#include <cstdio>

#include "geom/span.h"

namespace viewer {
namespace {

std::string format(const char* f, double a, double b = 0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, f, a, b);
  return buffer;
}

bool is_shadow_pass(const std::string& pass) {
  return pass != "depth + ambient" && pass != "lit shading" && pass != "shading" && pass != "inspection" &&
         pass.rfind("silhouette buffers", 0) != 0;
}

}  // namespace

double shadow_ms(const std::vector<render::PassTime>& times) {
  double ms = 0;
  for (const render::PassTime& t : times)
    if (is_shadow_pass(t.pass)) ms += t.ms;
  return ms;
}

double total_ms(const std::vector<render::PassTime>& times) {
  double ms = 0;
  for (const render::PassTime& t : times) ms += t.ms;
  return ms;
}

std::string error_line(const ErrorFigures& e) {
  if (!e.valid) return "error: press E";
  std::string s = format("error %.3f%% visible, %.2f%% boundary", 100 * e.visible, 100 * e.boundary);
  if (e.has_classes) s += format(", %.2f%% cast, %.2f%% self", 100 * e.cast, 100 * e.self);
  return s;
}

std::vector<std::string> hud_lines(const Figures& f, bool passes) {
  std::vector<std::string> lines;
  std::string head = render::technique_name(f.technique);
  if (render::technique_has_map(f.technique)) head += " " + std::to_string(f.map_size);
  lines.push_back(head);
  if (!f.message.empty()) {
    lines.push_back(f.message);
    return lines;
  }
  lines.push_back(format("shadow %.2f ms, frame %.2f ms", shadow_ms(f.times), total_ms(f.times)) +
                  (f.gpu_timers ? " (GPU)" : " (wall)"));
  lines.push_back(error_line(f.error));
  if (passes)
    for (const render::PassTime& t : f.times) lines.push_back("  " + t.pass + format(" %.2f ms", t.ms));
  return lines;
}

bool make_reference(const geom::Scene& scene, const geom::Camera& camera, const geom::Light& light, Reference& out,
                    std::string& error) {
  out.ref = geom::shadow_reference(geom::positions_of(scene.positions.data(), scene.vertex_count()),
                                   scene.indices.data(), scene.indices.size(), camera, light);
  if (!out.ref.ok) return error = "reference: " + out.ref.error, false;
  const int w = out.ref.width, h = out.ref.height, radius = 3;
  std::vector<uint8_t> edge(size_t(w) * h, 0);
  out.band.assign(size_t(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t v = out.ref.mask[size_t(y) * w + x];
      if (v == 128) continue;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, t = y + dy;
          if (u < 0 || t < 0 || u >= w || t >= h) continue;
          const uint8_t n = out.ref.mask[size_t(t) * w + u];
          if (n != 128 && n != v) edge[size_t(y) * w + x] = 1;
        }
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!edge[size_t(y) * w + x]) continue;
      for (int t = std::max(0, y - radius); t <= std::min(h - 1, y + radius); ++t)
        for (int u = std::max(0, x - radius); u <= std::min(w - 1, x + radius); ++u) out.band[size_t(t) * w + u] = 1;
    }
  return true;
}

ErrorFigures score(const std::vector<uint8_t>& mask, const Reference& r, std::vector<uint8_t>* overlay) {
  ErrorFigures e;
  const geom::ShadowReference& ref = r.ref;
  const size_t n = ref.mask.size();
  if (overlay) overlay->assign(n * 4, 0);
  size_t wrong_v = 0, wrong_b = 0;
  for (size_t i = 0; i < n; ++i) {
    if (ref.mask[i] == 128 || ref.uncertain[i]) continue;
    const uint8_t m = i < mask.size() ? mask[i] : 128;
    const bool wrong = m != ref.mask[i];
    ++e.visible_pixels, wrong_v += wrong;
    if (r.band[i]) ++e.boundary_pixels, wrong_b += wrong;
    if (wrong && overlay) {
      uint8_t* p = overlay->data() + 4 * i;
      const bool false_shadow = m == 0;
      p[0] = false_shadow ? 255 : 40, p[1] = 40, p[2] = false_shadow ? 40 : 255, p[3] = 200;
    }
  }
  e.visible = e.visible_pixels ? double(wrong_v) / double(e.visible_pixels) : 0.0;
  e.boundary = e.boundary_pixels ? double(wrong_b) / double(e.boundary_pixels) : 0.0;
  e.valid = true;
  return e;
}

bool measure_error(render::State& state, const Reference& ref, const geom::Camera& camera, const geom::Light& light,
                   render::FrameSettings settings, ErrorFigures& out, std::vector<uint8_t>* overlay,
                   std::string& error) {
  settings.output = render::Output::Mask;
  settings.inspect = false;
  geom::PngImage mask;
  std::vector<render::PassTime> times;
  if (!render::render(state, camera, light, settings, mask, times, error)) return false;
  out = score(mask.pixels, ref, overlay);
  return true;
}

}  // namespace viewer
