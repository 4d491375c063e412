// headless.cpp: geomview without a window (app.h): PNG files through EGL.
#include <cstdio>
#include <filesystem>

#include "app.h"
#include "cli/args.h"
#include "cli/output.h"
#include "compare.h"
#include "ui.h"

namespace viewer {
namespace {

void print_lines(const std::vector<std::string>& lines) {
  for (const std::string& l : lines) std::printf("hud: %s\n", l.c_str());
}

int run_compare(Options& o, Session& s) {
  Grid grid;
  std::string error;
  if (!render_grid(*s.state, s.scene, o.compare, o.view, o.light, o.settings, true, grid, error)) return fail(error);
  for (const Figures& f : grid.figures) print_lines(hud_lines(f, false));
  if (!draw_labels(grid.image, grid.labels, error)) return fail(error);
  std::string png;
  cli::OutputSet out;
  if (!geom::encode_png(grid.image, png, error)) return fail(o.out_path + ": " + error);
  out.add(o.out_path, std::move(png));
  return out.commit(error) ? 0 : fail(error);
}

}  // namespace

int run_headless(Options& o, Session& s) {
  if (!o.compare.empty()) return run_compare(o, s);
  const bool several = o.techniques.size() > 1;
  cli::OutputSet out;  // written together at the end: a failed technique leaves no file and no folder
  std::string error;
  if (o.frames > 1) std::printf("# pass times: %s\n", render::timing_kind(*s.state).c_str());
  Reference ref;
  const bool measure = o.error || o.hud;
  if (measure && !make_reference(s.scene, o.view, o.light, ref, error)) return fail(error);
  render::InspectionCounts counts;
  if (o.settings.inspect && !render::inspection_counts(*s.state, counts, error)) return fail(error);
  const bool gpu = render::timing_kind(*s.state).rfind("GPU", 0) == 0;
  render::FrameSettings settings = o.settings;
  for (render::Technique t : o.techniques) {
    settings.technique = t;
    if (render::technique_needs_point_light(t) && o.light.type == geom::LightType::Directional && several) {
      cli::warning("%s skipped: it needs a point or spot light", render::technique_name(t));
      continue;
    }
    Figures f;
    f.technique = t, f.map_size = settings.shadow_map_size, f.gpu_timers = gpu;
    geom::PngImage image;
    for (int frame = 0; frame < o.frames; ++frame) {
      std::vector<render::PassTime> times;
      if (!render::render(*s.state, o.view, o.light, settings, image, times, error))
        return fail(o.file + ": " + render::technique_name(t) + ": " + error);
      if (o.frames > 1) {
        std::printf("%s frame %d:", render::technique_name(t), frame);
        for (auto& pt : times) std::printf(" %s %.3f ms", pt.pass.c_str(), pt.ms);
        const std::string counters = counter_text(times);
        std::printf(" total %.3f ms; drew %s%s\n", total_ms(times), render::drawn_projection(*s.state).c_str(),
                    counters.empty() ? "" : ("; shadow passes: " + counters).c_str());
      }
      f.times = times;
      f.projection = render::drawn_projection(*s.state);
    }
    if (measure && !measure_error(*s.state, ref, o.view, o.light, settings, f.error, nullptr, error))
      return fail(o.file + ": " + render::technique_name(t) + ": " + error);
    if (o.error && !o.hud)
      for (const std::string& l : error_lines(f.error)) std::printf("%s %s\n", render::technique_name(t), l.c_str());
    if (o.hud) {
      const std::vector<std::string> lines = hud_lines(f);
      print_lines(lines);
      if (settings.output == render::Output::Color) {
        std::vector<Label> labels(1);
        labels[0].lines = lines;
        labels[0].x = 8, labels[0].y = 8;
        if (settings.inspect) labels.push_back(legend_label(counts, 8, image.height - 140));
        if (!draw_labels(image, labels, error)) return fail(error);
      }
    }
    if (settings.inspect && o.hud)
      for (const auto& [what, k] : {std::make_pair("report", counts.report), std::make_pair("drawn", counts.drawn)})
        std::printf("hud: inspection %s: boundary %llu non-manifold %llu inconsistent %llu degenerate %llu\n", what,
                    (unsigned long long)k.boundary_edges, (unsigned long long)k.non_manifold_edges,
                    (unsigned long long)k.inconsistent_edges, (unsigned long long)k.degenerate_faces);
    const std::string path = several ? o.out_path + "/" + render::technique_name(t) + ".png" : o.out_path;
    std::string png;
    if (!geom::encode_png(image, png, error)) return fail(path + ": " + error);
    out.add(path, std::move(png));
  }
  return out.commit(error) ? 0 : fail(error);
}

}  // namespace viewer
