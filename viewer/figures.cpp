// figures.cpp: pass times, the error against the reference, the HUD's lines.
#include "figures.h"

#include <algorithm>
#include <cstdio>

#include "geom/shadow_error.h"
#include "geom/span.h"

namespace viewer {
namespace {

std::string format(const char* f, double a, double b = 0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, f, a, b);
  return buffer;
}

}  // namespace

double shadow_ms(const std::vector<render::PassTime>& times) {
  double ms = 0;
  for (const render::PassTime& t : times)
    if (render::is_shadow_pass(t.pass)) ms += t.ms;
  return ms;
}

std::string counter_text(const std::vector<render::PassTime>& times) {
  const render::PassCounters c = render::shadow_counters(times);
  if (!c.valid) return "";
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "%llu primitives, %llu vs, %llu gs, %llu fs invocations",
                (unsigned long long)c.primitives, (unsigned long long)c.vs_invocations,
                (unsigned long long)c.gs_invocations, (unsigned long long)c.fs_invocations);
  return buffer;
}

double total_ms(const std::vector<render::PassTime>& times) {
  double ms = 0;
  for (const render::PassTime& t : times) ms += t.ms;
  return ms;
}

std::vector<std::string> error_lines(const ErrorFigures& e) {
  if (!e.valid) return {"error: press E"};
  std::vector<std::string> lines = {format("error %.3f%% visible, %.2f%% boundary", 100 * e.visible, 100 * e.boundary)};
  if (e.has_classes) lines.push_back(format("per class: %.3f%% cast, %.3f%% self", 100 * e.cast, 100 * e.self));
  return lines;
}

std::vector<std::string> hud_lines(const Figures& f, bool passes) {
  std::vector<std::string> lines;
  std::string head = render::technique_name(f.technique);
  if (render::technique_has_map(f.technique)) head += " " + std::to_string(f.map_size);
  if (!f.projection.empty()) head += " | " + f.projection;
  lines.push_back(head);
  if (!f.message.empty()) {
    lines.push_back(f.message);
    return lines;
  }
  lines.push_back(format("shadow %.2f ms, frame %.2f ms", shadow_ms(f.times), total_ms(f.times)) +
                  (f.gpu_timers ? " (GPU)" : " (wall)"));
  for (const std::string& l : error_lines(f.error)) lines.push_back(l);
  if (passes) {  // each pass once, in order; repeated ones (a cube map's six faces) summed as "name x6"
    std::vector<std::pair<std::string, std::pair<double, int>>> merged;
    for (const render::PassTime& t : f.times) {
      auto it = std::find_if(merged.begin(), merged.end(), [&](const auto& m) { return m.first == t.pass; });
      if (it == merged.end())
        merged.push_back({t.pass, {t.ms, 1}});
      else
        it->second.first += t.ms, ++it->second.second;
    }
    for (const auto& [name, v] : merged)
      lines.push_back("  " + name + (v.second > 1 ? " x" + std::to_string(v.second) : "") +
                      format(" %.2f ms", v.first));
    if (const std::string c = counter_text(f.times); !c.empty()) lines.push_back("shadow passes: " + c);
  }
  return lines;
}

std::vector<std::string> compact_lines(const Figures& f) {
  std::vector<std::string> lines = hud_lines(f, false);
  if (lines.size() < 3 || !f.message.empty()) return lines;
  lines[1] = format("%.2f ms", shadow_ms(f.times)) + (f.gpu_timers ? " (GPU)" : " (wall)");
  if (!f.error.valid) return lines;
  lines.resize(2);
  lines.push_back(format("err %.3f%%, bnd %.2f%%", 100 * f.error.visible, 100 * f.error.boundary));
  if (f.error.has_classes) lines.push_back(format("cast %.2f%%, self %.2f%%", 100 * f.error.cast, 100 * f.error.self));
  return lines;
}

bool make_reference(const geom::Scene& scene, const geom::Camera& camera, const geom::Light& light, Reference& out,
                    std::string& error) {
  out.ref = geom::shadow_reference(geom::positions_of(scene.positions.data(), scene.vertex_count()),
                                   scene.indices.data(), scene.indices.size(), camera, light);
  if (!out.ref.ok) return error = "reference: " + out.ref.error, false;
  return true;
}

// geom/shadow_error.h scores (geombench's figures); the overlay colours its wrong pixels.
ErrorFigures score(const std::vector<uint8_t>& mask, const Reference& r, std::vector<uint8_t>* overlay) {
  geom::ShadowErrorOptions options;
  options.wrong_mask = overlay != nullptr;
  const geom::ShadowError s = geom::shadow_error(mask, r.ref, options);
  ErrorFigures e;
  e.valid = true;
  e.visible = s.error_visible, e.boundary = s.error_boundary;
  e.has_classes = true;
  e.cast = s.error_cast, e.self = s.error_self;
  e.visible_pixels = s.visible_pixels, e.boundary_pixels = s.boundary_pixels;
  if (overlay) {
    const size_t n = r.ref.mask.size();
    overlay->assign(n * 4, 0);
    for (size_t i = 0; i < n && i < s.wrong.size(); ++i) {
      const auto w = geom::WrongPixel(s.wrong[i]);
      if (w == geom::WrongPixel::Right || w == geom::WrongPixel::Uncertain) continue;
      uint8_t* p = overlay->data() + 4 * i;
      const bool false_shadow = i < mask.size() && mask[i] == 0;
      p[0] = false_shadow ? 255 : 40, p[1] = 40, p[2] = false_shadow ? 40 : 255, p[3] = 200;
    }
  }
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
