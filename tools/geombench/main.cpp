// geombench: speed against error of every shadow technique of the viewer, and
// baking throughput against the peer libraries.
//
//   geombench [--quick] [-o DIR] [--scenes a,b] [--techniques a,b] [--sizes 256,512]
//             [--size WxH] [--frames N] [--no-bake] [--no-render] [--light-radius R]
//             [--time-only]
//
// For each scene (scenes.h), technique (render::available_techniques(), the
// viewer's names) and shadow-map size (256 ... 4096; one row with size 0 for
// the shadow volumes, which have no map):
//  - time_ms: the technique's shadow passes of one frame (every pass but the
//    camera's "depth + ambient", "lit shading" and "shading"; the focus CPU
//    work counts), the median over --frames frames after one warm-up frame per
//    technique; GPU timer queries on a GPU (time_kind "gpu"), wall time around
//    glFinish on a software rasterizer such as llvmpipe (time_kind "wall");
//  - error_visible: the share of visible pixels (the reference sees geometry)
//    whose shadow state differs from the reference of geom/shadow_reference.h
//    (a ray from every visible surface point to the light, Embree), leaving out
//    the reference's one-pixel `uncertain` band where a rasterizer and a ray
//    caster may legitimately differ;
//  - error_boundary: the same share among the visible pixels within 3 pixels
//    (Chebyshev) of a true shadow boundary (a lit pixel next to a shadowed one
//    in the reference), the uncertain band again left out; 0 with
//    boundary_pixels 0 where the view has no shadow boundary;
//  - error_cast, error_self: the same per class (geom/shadow_error.h): cast, a
//    receiver shadowed by another object and the lit pixels nearest to such a
//    shadow; self, a caster in its own shadow (terminators, concavities). The
//    pixel-exactness claims (Kenzel 2013, Sect. 5.2) are judged on error_cast. All four come from
//    geom::shadow_error, the viewer's figures too.
//  - error_fraction (scenes where a soft technique runs): the mean absolute
//    difference of the light fraction from the area-light reference of
//    geom/area_reference.h (a disc of radius --light-radius, default 4% of the
//    scene's bounding radius for a point light, 0.02 rad for a directional one;
//    64 stratified rays per pixel), over the pixels where it sees geometry; the
//    soft techniques (edsm-soft, pcf-soft) output their fraction, the others
//    their hard mask as 0 / 1. -1 where not measured. The soft rows take no part
//    in the budget summary (their other errors are of their fraction at 0.5).
// Output: a table on stdout; with -o DIR: DIR/results.csv, DIR/results.json,
// DIR/bake.csv, DIR/plot.svg (error against time, one panel per scene, a line
// per technique, a point per map size) and DIR/summary.md (the best technique
// at each time budget, and whether each published claim checked holds: claims.h).
// --time-only: the times and counters alone, no Embree reference (errors -1),
// no budget summary or claims: the run for a GPU machine (scripts/gpu-timing.sh).
//  - primitives, vs_invocations, gs_invocations, fs_invocations: the shadow
//    passes' pipeline statistics of one frame (render::shadow_counters; -1
//    where the context has no ARB_pipeline_statistics_query), the counts
//    Kenzel 2013, Sect. 5.1 (figs. 5.3, 5.4) sets beside the times.
// --quick (CI): 160x120 images, sizes 256 and 1024, scenes default, pipes,
// grazing, one frame, bake throughput on 10k and 50k triangles.
// cube needs a point or spot light: it has no rows for directional-light scenes.
// A scene whose data is missing (the OpenArena map, the vendored bunny) is skipped
// with a warning and listed under "skipped" in the JSON and the summary.
// Exit: 0 on success, 1 when the GL context or a render fails, 2 on bad usage.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "bake_throughput.h"
#include "claims.h"
#include "cli/args.h"
#include "cli/memory.h"
#include "cli/output.h"
#include "cli/view_check.h"
#include "geom/area_reference.h"
#include "geom/shadow_error.h"
#include "geom/shadow_reference.h"
#include "render/platform.h"
#include "render/render.h"
#include "results.h"
#include "scenes.h"

namespace {

using geombench::fmt;
using geombench::Row;

void score(const geom::PngImage& mask, const geom::ShadowReference& ref, Row& r) {
  const geom::ShadowError e = geom::shadow_error(mask.pixels, ref);
  r.visible = e.visible_pixels, r.boundary = e.boundary_pixels, r.cast = e.cast_pixels, r.self = e.self_pixels;
  r.error_visible = e.error_visible, r.error_boundary = e.error_boundary;
  r.error_cast = e.error_cast, r.error_self = e.error_self;
}

// ---- summary: the best configuration at each time budget, and the claims ----

struct Config {
  std::string technique;
  int size = 0;
  double time = 0, error = 0;
  int scenes = 0;
};

std::vector<Config> configs(const std::vector<Row>& rows) {
  std::map<std::pair<std::string, int>, Config> m;
  for (const Row& r : rows) {
    render::Technique t;
    if (render::parse_technique(r.technique, t) && render::technique_is_soft(t)) continue;
    Config& c = m[{r.technique, r.size}];
    c.technique = r.technique, c.size = r.size;
    c.time += r.time_ms, c.error += r.error_visible, ++c.scenes;
  }
  std::vector<Config> out;
  for (auto& kv : m) {
    kv.second.time /= kv.second.scenes, kv.second.error /= kv.second.scenes;
    out.push_back(kv.second);
  }
  return out;
}

std::string config_name(const std::string& t, int size) { return size ? t + "@" + std::to_string(size) : t; }

std::vector<std::string> budget_summary(const std::vector<Row>& rows) {
  std::vector<std::string> lines;
  // Only configurations measured on every scene (cube needs a point light) compete.
  std::vector<Config> cs = configs(rows);
  int most = 0;
  for (const Config& c : cs) most = std::max(most, c.scenes);
  cs.erase(std::remove_if(cs.begin(), cs.end(), [&](const Config& c) { return c.scenes < most; }), cs.end());
  std::string last;
  for (double budget : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0}) {
    const Config* best = nullptr;
    for (const Config& c : cs)
      if (c.time <= budget && (!best || c.error < best->error || (c.error == best->error && c.time < best->time)))
        best = &c;
    if (!best) continue;
    const std::string name = config_name(best->technique, best->size);
    if (name == last) continue;
    last = name;
    lines.push_back("within " + fmt("%g", budget) + " ms: " + name + " (mean " + fmt("%.2f", best->time) +
                    " ms, mean error " + fmt("%.4f", best->error) + " over " + std::to_string(best->scenes) +
                    " scenes)");
  }
  return lines;
}

int usage(const std::string& error) {
  if (!error.empty()) cli::error("%s", error.c_str());
  std::fprintf(error.empty() ? stdout : stderr,
               "usage: geombench [--quick] [-o DIR] [--scenes a,b] [--techniques a,b] [--sizes 256,1024]\n"
               "                 [--size WxH] [--frames N] [--no-bake] [--no-render] [--light-radius R]\n"
               "                 [--time-only]\n"
               "  (technique esm: extended shadow maps, Bujnak 2004; not exponential shadow maps)\n"
               "  GEOMBENCH_DATA=DIR: read default_scene.gltf and bunny_gltf.drc from DIR (scripts/gpu-timing.sh)\n");
  return error.empty() ? cli::kExitOk : cli::kExitUsage;
}

// The whole run, from the command line, validated before anything is measured.
struct Plan {
  bool quick = false, bake = true, render = true;
  bool time_only = false;  // --time-only: no reference, no errors (-1), no budget summary or claims
  int width = 640, height = 480, frames = 3;
  double light_radius = -1;  // -1: the default of each scene
  std::vector<int> sizes;
  std::vector<std::string> scene_names;
  std::vector<render::Technique> techniques;
  std::string shader_dir = GEOM_SHADER_DIR, out_dir;
};

// The flags into `plan`, each strictly (cli/args.h): an unknown scene or
// technique, an empty list, a number out of range or not whole is an error.
bool parse_plan(const cli::Args& args, Plan& plan, std::string& error) {
  plan.quick = args.has("--quick"), plan.bake = !args.has("--no-bake"), plan.render = !args.has("--no-render");
  plan.time_only = args.has("--time-only");
  if (plan.quick) plan.width = 160, plan.height = 120, plan.frames = 1;
  if (!cli::size_option(args, "--size", 8, 4096, plan.width, plan.height, error) ||
      !cli::int_option(args, "--frames", 1, 1000, plan.frames, error) ||
      !cli::real_option(args, "--light-radius", 0, 1e6, plan.light_radius, error))
    return false;
  plan.sizes = plan.quick ? std::vector<int>{256, 1024} : std::vector<int>{256, 512, 1024, 2048, 4096};
  std::vector<std::string> items;
  if (!cli::list_option(args, "--sizes", items, error)) return false;
  if (args.has("--sizes")) plan.sizes.clear();
  for (const std::string& v : args.has("--sizes") ? items : std::vector<std::string>{}) {
    long long n = 0;
    if (!cli::parse_int(v, 16, 8192, n))
      return error = "--sizes: shadow-map size '" + v + "' is not an integer within 16..8192", false;
    plan.sizes.push_back(int(n));
  }
  plan.scene_names = plan.quick ? geombench::quick_scene_names() : geombench::scene_names();
  if (!cli::list_option(args, "--scenes", plan.scene_names, error)) return false;
  const std::vector<std::string> known = geombench::scene_names();
  for (const std::string& name : plan.scene_names)
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string all;
      for (const std::string& k : known) all += " " + k;
      return error = "--scenes: unknown scene '" + name + "' (known:" + all + ")", false;
    }
  plan.techniques = render::available_techniques();
  if (!cli::list_option(args, "--techniques", items, error)) return false;
  if (args.has("--techniques")) plan.techniques.clear();
  for (const std::string& v : args.has("--techniques") ? items : std::vector<std::string>{}) {
    render::Technique t;
    if (!render::parse_technique(v, t)) return error = "--techniques: unknown technique '" + v + "'", false;
    plan.techniques.push_back(t);
  }
  if (const char* e = std::getenv("GEOMVIEW_SHADERS"); e && *e) plan.shader_dir = e;
  if (args.has("--shaders")) plan.shader_dir = args.get("--shaders");
  plan.out_dir = args.get("-o");
  if (args.has("-o") && !cli::check_output_path(plan.out_dir, true, error)) return false;
  return true;
}

// A scene of the plan with its light radius (the soft techniques').
struct Loaded {
  geombench::BenchScene b;
  float radius = 0;
};

// Every scene of the plan, built now, and checked: its light and camera
// (cli/view_check.h), the light radius against its light. A scene whose data
// is missing is skipped (listed in `skipped`); anything else wrong is an error
// before a single measurement.
bool load_scenes(const Plan& plan, std::vector<Loaded>& scenes, std::vector<std::string>& skipped, std::string& error) {
  const bool soft = std::any_of(plan.techniques.begin(), plan.techniques.end(), render::technique_is_soft);
  for (const std::string& name : plan.render ? plan.scene_names : std::vector<std::string>{}) {
    Loaded l;
    std::string problem;
    if (!geombench::make_scene(name, l.b, problem)) {
      cli::warning("scene %s skipped: %s", name.c_str(), problem.c_str());
      skipped.push_back(name + ": " + problem);
      continue;
    }
    if (!cli::check_light(l.b.light, "scene " + name + ": light", error)) return false;
    geom::Camera view = l.b.view;
    view.width = plan.width, view.height = plan.height;
    if (!l.b.default_view && !cli::check_camera(view, "scene " + name + ": camera", error)) return false;
    const bool directional = l.b.light.type == geom::LightType::Directional;
    if (soft && directional && plan.light_radius >= M_PI / 2)
      return error = "--light-radius " + fmt("%g", plan.light_radius) + ": scene " + name +
                     " has a directional light, whose radius is an angle: it must be under pi/2",
             false;
    scenes.push_back(std::move(l));
  }
  return true;
}

// This machine's memory against the plan's largest image and map (before anything runs).
bool check_memory(const Plan& plan, std::string& error) {
  const int map = *std::max_element(plan.sizes.begin(), plan.sizes.end());
  const uint64_t need = uint64_t(plan.width) * uint64_t(plan.height) * cli::kBytesPerImagePixel +
                        uint64_t(map) * uint64_t(map) * cli::kBytesPerMapTexel * 6u;
  if (need > cli::memory_budget())
    return error = "the run needs about " + cli::gib(need) + " (image " + std::to_string(plan.width) + "x" +
                   std::to_string(plan.height) + ", shadow maps up to " + std::to_string(map) +
                   "), over its memory budget of " + cli::gib(cli::memory_budget()),
           false;
  return true;
}

// The GL context's limits against the plan's image and maps (the flags' ranges
// are within what every OpenGL 4.5 context must hold: 16384).
bool check_gl_limits(const Plan& plan, std::string& error) {
  const render::GlLimits gl = render::gl_limits();
  const int map = *std::max_element(plan.sizes.begin(), plan.sizes.end());
  if (plan.width > gl.max_image_width() || plan.height > gl.max_image_height() || map > gl.max_cube_map ||
      map > gl.max_texture)
    return error = "--size " + std::to_string(plan.width) + "x" + std::to_string(plan.height) + " or shadow-map size " +
                   std::to_string(map) + " is over this OpenGL's limits (image " +
                   std::to_string(gl.max_image_width()) + "x" + std::to_string(gl.max_image_height()) + ", texture " +
                   std::to_string(gl.max_texture) + ", cube-map face " + std::to_string(gl.max_cube_map) + ")",
           false;
  return true;
}

// The bake throughput table (it forks: best done before a GL context exists).
std::vector<geombench::BakeRow> run_bake(const Plan& plan) {
  const std::vector<int> ns = plan.quick ? std::vector<int>{70, 158} : std::vector<int>{70, 158, 316, 633};
  std::vector<geombench::BakeRow> bake = geombench::bake_throughput(ns, plan.quick ? 1 : 3, plan.quick ? 0 : 320000);
  std::printf("Bake throughput (one core; CPU time per call, median of %d; peak: extra resident memory of one run)\n",
              plan.quick ? 1 : 3);
  std::printf("%10s  %-9s %10s %12s %10s %9s %9s\n", "triangles", "method", "ms", "Mtris/s", "peak MiB", "speed/mo",
              "mem/mo");
  for (size_t i = 0; i < bake.size(); ++i) {
    const geombench::BakeRow& r = bake[i];
    const geombench::BakeRow& mo = bake[i - i % 3 + 1];
    std::printf("%10llu  %-9s %10.2f %12.2f %10.1f %9.2f %9.2f\n", (unsigned long long)r.triangles, r.method.c_str(),
                r.seconds * 1e3, r.triangles_per_second * 1e-6, r.peak_bytes / 1048576.0,
                r.triangles_per_second / std::max(1.0, mo.triangles_per_second),
                mo.peak_bytes > 0 ? r.peak_bytes / mo.peak_bytes : 0.0);
  }
  std::fflush(stdout);
  return bake;
}

// What the measurements of a run share: the rows and what the outputs name.
struct Measured {
  std::vector<Row> rows;
  std::set<std::string> hard;
  std::vector<std::string> scenes_done, skipped;
  std::string renderer, kind_text, kind = "wall";
};

// One technique at one map size (0: no map) on one scene: the median time over
// the frames after a warm-up frame, and the errors against the references.
bool measure_cell(const Plan& plan, const Loaded& l, render::State& state, const geom::Camera& view,
                  const geom::ShadowReference& ref, const geom::AreaReference& area, render::Technique t, int size,
                  bool warm, Measured& m, std::string& error) {
  const geombench::BenchScene& b = l.b;
  render::FrameSettings fs;
  fs.technique = t, fs.output = render::Output::Mask, fs.shadow_map_size = size ? size : 1024;
  const bool soft = render::technique_is_soft(t);
  if (soft) fs.output = render::Output::Fraction, fs.light_radius = l.radius;
  geom::PngImage mask;
  std::vector<render::PassTime> times;
  // Fewer frames where one is slow (4096 maps, the heavy scene), never fewer sizes.
  const int n = (size >= 4096 || b.scene.triangle_count() > 100000) ? std::min(plan.frames, 1) : plan.frames;
  std::vector<double> ms;
  render::PassCounters counters;  // the last frame's: the same every frame
  for (int f = warm ? 0 : -1; f < n; ++f) {
    times.clear();
    if (!render::render(state, view, b.light, fs, mask, times, error)) return false;
    if (f < 0) continue;
    double sum = 0;
    for (const render::PassTime& p : times)
      if (render::is_shadow_pass(p.pass)) sum += p.ms;
    ms.push_back(sum);
    counters = render::shadow_counters(times);
  }
  std::sort(ms.begin(), ms.end());
  Row r;
  r.scene = b.name, r.technique = render::technique_name(t), r.size = size, r.time_kind = m.kind;
  r.time_ms = ms[ms.size() / 2], r.frames = n, r.triangles = b.scene.triangle_count();
  r.projection = render::drawn_projection(state);
  if (counters.valid) {
    r.primitives = (long long)counters.primitives, r.vs_invocations = (long long)counters.vs_invocations;
    r.gs_invocations = (long long)counters.gs_invocations, r.fs_invocations = (long long)counters.fs_invocations;
  }
  if (!plan.time_only) {
    if (area.ok) r.error_fraction = geom::mean_fraction_error(mask.pixels, area);
    if (soft)  // the hard state of a fraction: lit from 0.5 on
      for (uint8_t& v : mask.pixels) v = v >= 128 ? 255 : 0;
    score(mask, ref, r);
  } else {
    r.error_visible = r.error_boundary = r.error_cast = r.error_self = -1;
  }
  m.rows.push_back(r);
  std::printf("  %-10s %6s %10.3f %10.5f %10.5f %10.5f %10.5f %10.5f %11lld %11lld %6lld %11lld  %s\n",
              r.technique.c_str(), size ? std::to_string(size).c_str() : "-", r.time_ms, r.error_visible,
              r.error_boundary, r.error_cast, r.error_self, r.error_fraction, r.primitives, r.vs_invocations,
              r.gs_invocations, r.fs_invocations, r.projection.c_str());
  std::fflush(stdout);
  return true;
}

// Every technique and size of the plan on one scene, after its references.
bool measure_scene(const Plan& plan, Loaded& l, Measured& m, std::string& error) {
  const geombench::BenchScene& b = l.b;
  const std::string& name = b.name;
  render::StatePtr state = render::create_state(b.scene, plan.shader_dir, error);
  if (!state) return error = "scene " + name + ": " + error, false;
  if (const std::string gl = render::gl_error_text(); !gl.empty()) return error = "scene " + name + ": " + gl, false;
  m.renderer = render::renderer_name(*state);
  m.kind_text = render::timing_kind(*state);
  m.kind = m.kind_text.find("GPU") != std::string::npos ? "gpu" : "wall";
  geom::Camera view = b.default_view ? render::default_view(*state, plan.width, plan.height) : b.view;
  view.width = plan.width, view.height = plan.height;
  if (!cli::check_camera(view, "scene " + name + ": camera", error)) return false;
  const auto positions = geom::positions_of(b.scene.positions.data(), b.scene.vertex_count());
  geom::ShadowReference ref;  // --time-only: none
  if (!plan.time_only) {
    ref = geom::shadow_reference(positions, b.scene.indices.data(), b.scene.indices.size(), view, b.light);
    if (!ref.ok) return error = "scene " + name + ": reference: " + ref.error, false;
  }
  float sb[4];  // the area-light reference, where a soft technique runs
  render::scene_bounds(*state, sb);
  const bool directional = b.light.type == geom::LightType::Directional;
  l.radius = float(plan.light_radius >= 0 ? plan.light_radius : directional ? 0.02 : 0.04 * sb[3]);
  geom::AreaReference area;
  if (!plan.time_only && std::any_of(plan.techniques.begin(), plan.techniques.end(), render::technique_is_soft)) {
    area = geom::area_light_reference(positions, b.scene.indices.data(), b.scene.indices.size(), view, b.light,
                                      l.radius, 64);
    if (!area.ok) return error = "scene " + name + ": area reference: " + area.error, false;
  }
  m.scenes_done.push_back(name);
  if (b.hard) m.hard.insert(name);
  std::printf("\n%s: %s; %zu triangles; %dx%d; %s\n", name.c_str(), b.description.c_str(), b.scene.triangle_count(),
              plan.width, plan.height, m.kind_text.c_str());
  if (area.ok) std::printf("  light radius %g (soft techniques; err frac: vs the area-light reference)\n", l.radius);
  std::printf("  %-10s %6s %10s %10s %10s %10s %10s %10s %11s %11s %6s %11s  %s\n", "technique", "map", "time ms",
              "err vis", "err bnd", "err cast", "err self", "err frac", "primitives", "vs inv", "gs inv", "fs inv",
              "projection drawn");
  for (render::Technique t : plan.techniques) {
    if (render::technique_needs_point_light(t) && directional) {
      std::printf("  %-10s (needs a point or spot light: not measured)\n", render::technique_name(t));
      continue;
    }
    bool warm = false;
    for (int size : render::technique_has_map(t) ? plan.sizes : std::vector<int>{0}) {
      if (!measure_cell(plan, l, *state, view, ref, area, t, size, warm, m, error))
        return error = "scene " + name + ", " + render::technique_name(t) + ": " + error, false;
      warm = true;
    }
  }
  return true;
}

std::string results_json(const Plan& plan, const Measured& m, const std::vector<geombench::BakeRow>& bake,
                         const std::vector<std::string>& best, const std::vector<std::string>& claim_lines) {
  nlohmann::json results = nlohmann::json::array();
  for (const Row& r : m.rows)
    results.push_back({{"scene", r.scene},
                       {"technique", r.technique},
                       {"shadow_map_size", r.size},
                       {"time_ms", r.time_ms},
                       {"time_kind", r.time_kind},
                       {"error_visible", r.error_visible},
                       {"error_boundary", r.error_boundary},
                       {"error_cast", r.error_cast},
                       {"error_self", r.error_self},
                       {"cast_pixels", r.cast},
                       {"self_pixels", r.self},
                       {"visible_pixels", r.visible},
                       {"boundary_pixels", r.boundary},
                       {"frames", r.frames},
                       {"triangles", r.triangles},
                       {"error_fraction", r.error_fraction},
                       {"projection", r.projection},
                       {"primitives", r.primitives},
                       {"vs_invocations", r.vs_invocations},
                       {"gs_invocations", r.gs_invocations},
                       {"fs_invocations", r.fs_invocations}});
  nlohmann::json bj = nlohmann::json::array();
  for (size_t i = 0; i < bake.size(); ++i) {
    const geombench::BakeRow& r = bake[i];
    double sp = 0, mem = 0;
    bake_ratios(bake, i, sp, mem);
    bj.push_back({{"triangles", r.triangles},
                  {"method", r.method},
                  {"seconds", r.seconds},
                  {"triangles_per_second", r.triangles_per_second},
                  {"peak_bytes", r.peak_bytes},
                  {"speed_vs_meshopt", sp},
                  {"memory_vs_meshopt", mem}});
  }
  const nlohmann::json j = {{"renderer", m.renderer},  {"timing", m.kind_text},
                            {"time_kind", m.kind},     {"image", {{"width", plan.width}, {"height", plan.height}}},
                            {"quick", plan.quick},     {"shadow_map_sizes", plan.sizes},
                            {"scenes", m.scenes_done}, {"skipped", m.skipped},
                            {"results", results},      {"bake", bj},
                            {"best_at_budget", best},  {"claims", claim_lines}};
  return j.dump(1) + "\n";
}

// The tables on stdout; with -o, the five files, all or none (cli/output.h).
bool report(const Plan& plan, const Measured& m, const std::vector<geombench::BakeRow>& bake, std::string& error) {
  const std::vector<std::string> best = plan.time_only ? std::vector<std::string>{} : budget_summary(m.rows);
  const std::vector<std::string> claim_lines =
      plan.time_only ? std::vector<std::string>{} : geombench::claims(m.rows, m.hard, bake);
  if (!best.empty()) {
    std::printf("\nBest technique at each time budget (mean time and mean error over the scenes):\n");
    for (const std::string& l : best) std::printf("  %s\n", l.c_str());
  }
  if (!claim_lines.empty()) {
    const std::string times = m.rows.empty() ? std::string("bake: CPU time per call")
                              : bake.empty() ? m.kind + " time"
                                             : m.kind + " time; bake: CPU time per call";
    std::printf("\nClaims checked on this run, each with its source (%s):\n", times.c_str());
    for (const std::string& l : claim_lines) std::printf("  %s\n", l.c_str());
  }
  if (plan.out_dir.empty()) return true;
  const std::string& dir = plan.out_dir;
  cli::OutputSet out;
  out.add(dir + "/results.csv", results_csv(m.rows));
  out.add(dir + "/bake.csv", bake_csv(bake));
  out.add(dir + "/results.json", results_json(plan, m, bake, best, claim_lines));
  std::vector<std::string> tech_names;
  for (render::Technique t : plan.techniques) tech_names.push_back(render::technique_name(t));
  out.add(dir + "/plot.svg", plot_svg(m.rows, m.scenes_done, tech_names, m.kind));
  std::ostringstream md;
  md << "# geombench summary\n\nrenderer: " << m.renderer << "; timing: " << m.kind_text << "; image " << plan.width
     << "x" << plan.height << "\n\n## Best technique at each time budget\n\n";
  for (const std::string& l : best) md << "- " << l << "\n";
  md << "\n## Claims checked\n\n";
  for (const std::string& l : claim_lines) md << "- " << l << "\n";
  for (const std::string& l : m.skipped) md << "- skipped scene " << l << "\n";
  out.add(dir + "/summary.md", md.str());
  if (!out.commit(error)) return false;
  std::printf("\nwrote %s/results.csv, results.json, bake.csv, plot.svg, summary.md\n", dir.c_str());
  return true;
}

int run(int argc, char** argv) {
  cli::Args args(std::vector<std::string>(argv + 1, argv + argc),
                 {"--quick", "--no-bake", "--no-render", "--time-only", "-h", "--help"},
                 {"-o", "--scenes", "--techniques", "--sizes", "--size", "--frames", "--shaders", "--light-radius"});
  if (!args.error().empty()) return usage(args.error());
  if (args.has("-h") || args.has("--help")) return usage("");
  if (!args.positional().empty()) return usage("unexpected argument '" + args.positional()[0] + "'");
  Plan plan;
  std::string error;
  if (!parse_plan(args, plan, error)) return usage(error);
  Measured m;
  std::vector<Loaded> scenes;
  if (!load_scenes(plan, scenes, m.skipped, error)) return usage(error);
  if (!check_memory(plan, error)) return cli::error("%s", error.c_str()), cli::kExitFailure;
  std::vector<geombench::BakeRow> bake;
  if (plan.bake) bake = run_bake(plan);
  if (plan.render && !scenes.empty()) {
    std::string note;
    std::unique_ptr<render::Platform> platform =
        render::Platform::open(false, plan.width, plan.height, "geombench", note, error);
    if (!platform) return cli::error("no OpenGL context: %s", error.c_str()), cli::kExitFailure;
    if (!check_gl_limits(plan, error)) return cli::error("%s", error.c_str()), cli::kExitFailure;
    for (Loaded& l : scenes)
      if (!measure_scene(plan, l, m, error)) return cli::error("%s", error.c_str()), cli::kExitFailure;
  }
  if (!report(plan, m, bake, error)) return cli::error("%s", error.c_str()), cli::kExitFailure;
  return cli::kExitOk;
}

}  // namespace

// A failed allocation ends the run with an Error: line and exit 1, nothing written.
int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::bad_alloc&) {
    cli::error("out of memory (std::bad_alloc): a smaller --size, fewer --sizes or scenes");
    return cli::kExitFailure;
  }
}
