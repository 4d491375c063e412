// geombench: speed against error of every shadow technique of the viewer, and
// baking throughput against the peer libraries (MISSION.md part 9).
//
//   geombench [--quick] [-o DIR] [--scenes a,b] [--techniques a,b] [--sizes 256,512]
//             [--size WxH] [--frames N] [--no-bake] [--no-render] [--light-radius R]
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
//    issue-18 goals are judged on error_cast. All four come from
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
// at each time budget, the goals of the issue met or missed).
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
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "bake_throughput.h"
#include "cli/args.h"
#include "geom/area_reference.h"
#include "geom/shadow_error.h"
#include "geom/shadow_reference.h"
#include "render/platform.h"
#include "render/render.h"
#include "scenes.h"
#include "size_law.h"

namespace {

struct Row {
  std::string scene, technique, time_kind;
  std::string projection;  // what was drawn (render::drawn_projection)
  int size = 0;
  double time_ms = 0, error_visible = 0, error_boundary = 0, error_cast = 0, error_self = 0, error_fraction = -1;
  size_t visible = 0, boundary = 0, cast = 0, self = 0, triangles = 0;
  int frames = 0;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

bool is_shadow_pass(const std::string& pass) {
  return pass != "depth + ambient" && pass != "lit shading" && pass != "shading" && pass != "inspection" &&
         pass.rfind("silhouette buffers", 0) != 0;
}

void score(const geom::PngImage& mask, const geom::ShadowReference& ref, Row& r) {
  const geom::ShadowError e = geom::shadow_error(mask.pixels, ref);
  r.visible = e.visible_pixels, r.boundary = e.boundary_pixels, r.cast = e.cast_pixels, r.self = e.self_pixels;
  r.error_visible = e.error_visible, r.error_boundary = e.error_boundary;
  r.error_cast = e.error_cast, r.error_self = e.error_self;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// ---- summary: the best configuration at each time budget, and the goals ----

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

const Row* find(const std::vector<Row>& rows, const std::string& scene, const std::string& t, int size) {
  for (const Row& r : rows)
    if (r.scene == scene && r.technique == t && r.size == size) return &r;
  return nullptr;
}

// Issue 16: sssm's error within 1.5x edsm's at every size on pipes, default and
// scan; edsm-soft's light-fraction error below pcf-soft's at every size on pipes
// and default, at no more than 1.2x edsm's hard-shadow time.
void soft_goals(const std::vector<Row>& rows, std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "MET" : "MISSED"); };
  int n = 0, ok = 0, nf = 0, okf = 0, nt = 0, okt = 0, ne = 0, oke = 0;
  double worst = 0, worst_t = 0;
  std::string miss, miss_f;
  for (const Row& e : rows) {
    const bool sssm_scene = e.scene == "pipes" || e.scene == "default" || e.scene == "scan";
    if (e.technique == "edsm" && sssm_scene)
      if (const Row* s = find(rows, e.scene, "sssm", e.size)) {
        const double q = s->error_cast / std::max(e.error_cast, 1e-9);
        ++n, ok += s->error_cast <= 1.5 * e.error_cast + 1e-12, worst = std::max(worst, q);
        if (s->error_cast > 1.5 * e.error_cast + 1e-12 && miss.size() < 200)
          miss += " " + e.scene + "@" + std::to_string(e.size) + " (" + fmt("%.2f", q) + "x)";
      }
    if (e.technique == "esm-soft")
      if (const Row* p = find(rows, e.scene, "pcf-soft", e.size); p && (e.scene == "pipes" || e.scene == "default"))
        ++ne, oke += e.error_fraction < p->error_fraction;
    if (e.technique != "edsm-soft") continue;
    if (const Row* p = find(rows, e.scene, "pcf-soft", e.size); p && (e.scene == "pipes" || e.scene == "default")) {
      ++nf, okf += e.error_fraction < p->error_fraction;
      if (e.error_fraction >= p->error_fraction && miss_f.size() < 200)
        miss_f += " " + e.scene + "@" + std::to_string(e.size) + " (" + fmt("%.4f", e.error_fraction) + " vs " +
                  fmt("%.4f", p->error_fraction) + ")";
    }
    if (const Row* h = find(rows, e.scene, "edsm", e.size);
        h && h->time_ms > 0 && (e.scene == "pipes" || e.scene == "default")) {
      const double q = e.time_ms / h->time_ms;
      ++nt, okt += q <= 1.2, worst_t = std::max(worst_t, q);
    }
  }
  if (n)
    out.push_back(verdict(ok == n) + ": sssm error_cast <= 1.5x edsm's on pipes, default, scan: " + std::to_string(ok) +
                  " of " + std::to_string(n) + ", worst " + fmt("%.2f", worst) + "x" +
                  (miss.empty() ? "" : "; missed:" + miss));
  if (nf)
    out.push_back(verdict(okf == nf) + ": edsm-soft light-fraction error < pcf-soft's on pipes, default: " +
                  std::to_string(okf) + " of " + std::to_string(nf) + (miss_f.empty() ? "" : "; missed:" + miss_f));
  if (ne)  // not a goal of the issue: esm-soft beside them
    out.push_back("(no goal) esm-soft light-fraction error < pcf-soft's on pipes, default: " + std::to_string(oke) +
                  " of " + std::to_string(ne));
  if (nt)
    out.push_back(verdict(okt == nt) + ": edsm-soft time <= 1.2x edsm's on pipes, default (same run): " +
                  std::to_string(okt) + " of " + std::to_string(nt) + ", worst " + fmt("%.2f", worst_t) + "x");
}

std::vector<std::string> goals(const std::vector<Row>& rows, const std::set<std::string>& hard,
                               const std::vector<geombench::BakeRow>& bake) {
  (void)hard;
  std::vector<std::string> out;
  auto verdict = [](bool ok) { return std::string(ok ? "MET" : "MISSED"); };
  {  // shadow volumes within rasterization tolerance of zero
    double worst = 0;
    std::string where;
    int n = 0;
    for (const Row& r : rows)  // depth-pass is invalid by construction on near-plane (its near plane in a shadow)
      if (r.technique.rfind("sv", 0) == 0 && !(r.technique == "sv-zpass" && r.scene == "near-plane")) {
        ++n;
        if (r.error_visible >= worst) worst = r.error_visible, where = r.scene + " " + r.technique;
      }
    if (n)
      out.push_back(verdict(worst <= 0.001) +
                    ": shadow volumes near zero error (goal <= 0.001 of visible pixels): worst " + fmt("%.5f", worst) +
                    " (" + where + ")");
  }
  // Issue 18: judged on error_cast, on the pipes, default, jenga and scan
  // scenes, N = 512..2048: edsm@N <= ssm@N / 10 and <= ssm@4N, esm@N <= ssm@N / 3.
  const std::set<std::string> goal_scenes = {"pipes", "default", "jenga", "scan"};
  struct CastGoal {
    const char* technique;
    double divisor;
    int ssm_factor;
  };
  for (const CastGoal g :
       {CastGoal{"edsm", 10, 1}, CastGoal{"edsm", 1, 4}, CastGoal{"esm", 3, 1}, CastGoal{"esm-exact", 3, 1}}) {
    int n = 0, ok = 0;
    std::string misses;
    for (const Row& e : rows) {
      if (e.technique != g.technique || !goal_scenes.count(e.scene) || e.size < 512 || e.size > 2048) continue;
      const Row* s = find(rows, e.scene, "ssm", e.size * g.ssm_factor);
      if (!s) continue;
      ++n;
      const bool met = e.error_cast <= s->error_cast / g.divisor + 1e-12;
      ok += met;
      if (!met && misses.size() < 300)
        misses += " " + e.scene + "@" + std::to_string(e.size) + " (" + fmt("%.5f", e.error_cast) + " vs " +
                  fmt("%.5f", s->error_cast) + ")";
    }
    if (n)
      out.push_back(verdict(ok == n) + ": " + g.technique + "@N error_cast <= ssm@" +
                    (g.ssm_factor == 1 ? std::string("N") : std::to_string(g.ssm_factor) + "N") +
                    (g.divisor != 1 ? " / " + fmt("%g", g.divisor) : std::string()) +
                    " (pipes, default, jenga, scan; N = 512..2048): " + std::to_string(ok) + " of " +
                    std::to_string(n) + (misses.empty() ? "" : "; missed:" + misses));
  }
  for (const char* t : {"esm", "esm-exact", "edsm"}) {  // never worse than ssm in error_visible
    int n = 0, ok = 0;
    std::string misses;
    for (const Row& e : rows) {
      if (e.technique != t) continue;
      const Row* s = find(rows, e.scene, "ssm", e.size);
      if (!s) continue;
      ++n;
      const bool met = e.error_visible <= s->error_visible + 1e-12;
      ok += met;
      if (!met && misses.size() < 300)
        misses += " " + e.scene + "@" + std::to_string(e.size) + " (" + fmt("%.5f", e.error_visible) + " vs " +
                  fmt("%.5f", s->error_visible) + ")";
    }
    if (n)
      out.push_back(verdict(ok == n) + ": " + t + "@N error_visible <= ssm@N on every scene: " + std::to_string(ok) +
                    " of " + std::to_string(n) + (misses.empty() ? "" : "; missed:" + misses));
  }
  for (const char* t : {"esm", "esm-exact", "edsm"}) {  // cost at most 1.5x ssm
    double worst = 0, sum = 0;
    int n = 0;
    std::string kind;
    for (const Row& r : rows) {
      if (r.technique != t) continue;
      const Row* s = find(rows, r.scene, "ssm", r.size);
      if (!s || s->time_ms <= 0) continue;
      const double q = r.time_ms / s->time_ms;
      worst = std::max(worst, q), sum += q, ++n, kind = r.time_kind;
    }
    if (n)
      out.push_back(verdict(worst <= 1.5) + ": " + t + " time <= 1.5x ssm (" + kind + " time" +
                    (kind == "wall" ? ", software rasterizer: the goal is about GPU figures" : "") + "): mean " +
                    fmt("%.2f", sum / n) + "x, worst " + fmt("%.2f", worst) + "x");
  }
  for (const char* t : {"psm", "lispsm"}) {  // better than uniform on the wide depth range
    int n = 0, ok = 0;
    for (const Row& r : rows) {
      if (r.technique != t || r.scene != "wide-depth") continue;
      const Row* u = find(rows, r.scene, "uniform", r.size);
      if (!u) continue;
      ++n, ok += r.error_visible < u->error_visible;
    }
    if (n)
      out.push_back(verdict(ok == n) + ": " + t + " error < uniform on wide-depth: " + std::to_string(ok) + " of " +
                    std::to_string(n) + " sizes");
  }
  for (size_t i = 0; i + 2 < bake.size() + 0 && i + 1 < bake.size(); i += 3) {
    if (bake[i].method != "bake" || bake[i + 1].method != "meshopt") continue;
    const double q = bake[i].triangles_per_second / std::max(1.0, bake[i + 1].triangles_per_second);
    out.push_back(verdict(q >= 1) + ": bake no slower than meshopt adjacency at " + std::to_string(bake[i].triangles) +
                  " triangles: " + fmt("%.2f", q) + "x its throughput (the bake also welds, classifies and emits ESM " +
                  "quads and the shadow volume)");
  }
  soft_goals(rows, out);
  std::vector<geombench::SizePoint> points;  // error falls as the map grows (size_law.h)
  for (const Row& r : rows) points.push_back({r.scene, r.technique, r.size, r.error_visible});
  for (std::string& l : geombench::size_law_lines(points)) out.push_back(std::move(l));
  return out;
}

// ---- the plot: error against time, a panel per scene ----

std::string plot_svg(const std::vector<Row>& rows, const std::vector<std::string>& scenes,
                     const std::vector<std::string>& techniques, const std::string& kind) {
  const int pw = 360, ph = 260, cols = 3, ml = 55, mb = 40, mt = 28, mr = 12;
  const int rows_n = int((scenes.size() + cols - 1) / cols);
  const int legend_h = 30, W = cols * pw, H = rows_n * ph + legend_h + 30;
  static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                  "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000"};
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"8\" y=\"18\" font-size=\"14\">geombench: error (share of visible pixels wrong) against shadow-pass "
       "time ("
    << kind << " time, log scale); a line per technique, a point per shadow-map size</text>\n";
  for (size_t si = 0; si < scenes.size(); ++si) {
    const int ox = int(si % cols) * pw, oy = 30 + int(si / cols) * ph;
    double tmin = 1e30, tmax = 0, emax = 0;
    for (const Row& r : rows)
      if (r.scene == scenes[si])
        tmin = std::min(tmin, std::max(r.time_ms, 1e-3)), tmax = std::max(tmax, r.time_ms),
        emax = std::max(emax, r.error_visible);
    if (tmax <= 0) continue;
    const double l0 = std::floor(std::log10(tmin)), l1 = std::max(l0 + 1, std::ceil(std::log10(std::max(tmax, 1e-3))));
    emax = emax > 0 ? emax * 1.1 : 0.01;
    const int x0 = ox + ml, x1 = ox + pw - mr, y0 = oy + ph - mb, y1 = oy + mt;
    auto X = [&](double t) { return x0 + (std::log10(std::max(t, 1e-3)) - l0) / (l1 - l0) * (x1 - x0); };
    auto Y = [&](double e) { return y0 - e / emax * (y0 - y1); };
    s << "<text x=\"" << ox + ml << "\" y=\"" << oy + 18 << "\" font-weight=\"bold\">" << scenes[si] << "</text>\n";
    s << "<rect x=\"" << x0 << "\" y=\"" << y1 << "\" width=\"" << x1 - x0 << "\" height=\"" << y0 - y1
      << "\" fill=\"none\" stroke=\"#888\"/>\n";
    for (double l = l0; l <= l1 + 1e-9; l += 1)
      s << "<text x=\"" << X(std::pow(10, l)) << "\" y=\"" << y0 + 14 << "\" text-anchor=\"middle\">"
        << fmt("%g", std::pow(10, l)) << "</text>\n";
    for (int k = 0; k <= 4; ++k)
      s << "<text x=\"" << x0 - 4 << "\" y=\"" << Y(emax * k / 4) + 4 << "\" text-anchor=\"end\">"
        << fmt("%.3f", emax * k / 4) << "</text>\n";
    s << "<text x=\"" << (x0 + x1) / 2 << "\" y=\"" << y0 + 30 << "\" text-anchor=\"middle\">ms</text>\n";
    for (size_t ti = 0; ti < techniques.size(); ++ti) {
      std::vector<const Row*> pts;
      for (const Row& r : rows)
        if (r.scene == scenes[si] && r.technique == techniques[ti]) pts.push_back(&r);
      std::sort(pts.begin(), pts.end(), [](const Row* a, const Row* b) { return a->size < b->size; });
      const char* c = colours[ti % 11];
      if (pts.size() > 1) {
        s << "<polyline fill=\"none\" stroke=\"" << c << "\" points=\"";
        for (const Row* p : pts) s << X(p->time_ms) << "," << Y(p->error_visible) << " ";
        s << "\"/>\n";
      }
      for (const Row* p : pts)
        s << "<circle cx=\"" << X(p->time_ms) << "\" cy=\"" << Y(p->error_visible) << "\" r=\"3\" fill=\"" << c
          << "\"><title>" << p->technique << " " << p->size << ": " << p->time_ms << " ms, " << p->error_visible
          << "</title></circle>\n";
    }
  }
  for (size_t ti = 0; ti < techniques.size(); ++ti) {
    const int x = 10 + int(ti) * 95, y = H - 18;
    s << "<rect x=\"" << x << "\" y=\"" << y - 9 << "\" width=\"12\" height=\"10\" fill=\"" << colours[ti % 11]
      << "\"/><text x=\"" << x + 16 << "\" y=\"" << y << "\">" << techniques[ti] << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  return bool(f);
}

int usage(const std::string& error) {
  if (!error.empty()) cli::error("%s", error.c_str());
  std::fprintf(error.empty() ? stdout : stderr,
               "usage: geombench [--quick] [-o DIR] [--scenes a,b] [--techniques a,b] [--sizes 256,1024]\n"
               "                 [--size WxH] [--frames N] [--no-bake] [--no-render] [--light-radius R]\n");
  return error.empty() ? cli::kExitOk : cli::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  cli::Args args(std::vector<std::string>(argv + 1, argv + argc),
                 {"--quick", "--no-bake", "--no-render", "-h", "--help"},
                 {"-o", "--scenes", "--techniques", "--sizes", "--size", "--frames", "--shaders", "--light-radius"});
  if (!args.error().empty()) return usage(args.error());
  if (args.has("-h") || args.has("--help")) return usage("");
  if (!args.positional().empty()) return usage("unexpected argument '" + args.positional()[0] + "'");
  const bool quick = args.has("--quick");
  int width = quick ? 160 : 640, height = quick ? 120 : 480, frames = quick ? 1 : 3;
  if (args.has("--size") && std::sscanf(args.get("--size").c_str(), "%dx%d", &width, &height) != 2)
    return usage("--size wants WxH");
  if (width < 8 || height < 8 || width > 4096 || height > 4096) return usage("--size out of range (8..4096)");
  if (args.has("--frames")) frames = std::atoi(args.get("--frames").c_str());
  if (frames < 1 || frames > 1000) return usage("--frames wants 1..1000");
  double light_radius = -1;  // -1: the default of each scene
  if (args.has("--light-radius")) {
    char* end = nullptr;
    light_radius = std::strtod(args.get("--light-radius").c_str(), &end);
    if (!end || *end || !(light_radius >= 0) || light_radius > 1e6) return usage("--light-radius wants R >= 0");
  }
  std::vector<int> sizes = quick ? std::vector<int>{256, 1024} : std::vector<int>{256, 512, 1024, 2048, 4096};
  if (args.has("--sizes")) {
    sizes.clear();
    for (const std::string& v : split(args.get("--sizes"))) {
      const int n = std::atoi(v.c_str());
      if (n < 16 || n > 8192) return usage("shadow-map size '" + v + "' out of range (16..8192)");
      sizes.push_back(n);
    }
  }
  std::vector<std::string> scene_list = quick ? geombench::quick_scene_names() : geombench::scene_names();
  if (args.has("--scenes")) scene_list = split(args.get("--scenes"));
  std::vector<render::Technique> techniques = render::available_techniques();
  if (args.has("--techniques")) {
    techniques.clear();
    for (const std::string& v : split(args.get("--techniques"))) {
      render::Technique t;
      if (!render::parse_technique(v, t)) return usage("unknown technique '" + v + "'");
      techniques.push_back(t);
    }
  }
  std::string shader_dir = GEOM_SHADER_DIR;
  if (const char* e = std::getenv("GEOMVIEW_SHADERS")) shader_dir = e;
  if (args.has("--shaders")) shader_dir = args.get("--shaders");
  const std::string out_dir = args.get("-o");
  if (!out_dir.empty()) {  // created before the run: minutes of work must not end unable to write
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (!std::filesystem::is_directory(out_dir)) {
      cli::error("%s: cannot create the output folder%s%s", out_dir.c_str(), ec ? ": " : "",
                 ec ? ec.message().c_str() : "");
      return cli::kExitFailure;
    }
  }

  // Bake throughput first: it forks, which is best done before a GL context exists.
  std::vector<geombench::BakeRow> bake;
  if (!args.has("--no-bake")) {
    const std::vector<int> ns = quick ? std::vector<int>{70, 158} : std::vector<int>{70, 158, 316, 633};
    bake = geombench::bake_throughput(ns, quick ? 1 : 3, quick ? 0 : 320000);
    std::printf("Bake throughput (one core; CPU time per call, median of %d; peak: extra resident memory of one run)\n",
                quick ? 1 : 3);
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
  }

  std::vector<Row> rows;
  std::set<std::string> hard;
  std::vector<std::string> scenes_done, skipped;
  std::string renderer, kind_text, kind = "wall";
  std::unique_ptr<render::Platform> platform;
  if (!args.has("--no-render")) {
    std::string note, error;
    platform = render::Platform::open(false, width, height, "geombench", note, error);
    if (!platform) {
      cli::error("no OpenGL context: %s", error.c_str());
      return cli::kExitFailure;
    }
  }
  for (const std::string& name : platform ? scene_list : std::vector<std::string>{}) {
    geombench::BenchScene b;
    std::string error;
    if (!geombench::make_scene(name, b, error)) {
      cli::warning("scene %s skipped: %s", name.c_str(), error.c_str());
      skipped.push_back(name + ": " + error);
      continue;
    }
    render::StatePtr state = render::create_state(b.scene, shader_dir, error);
    if (!state) {
      cli::error("scene %s: %s", name.c_str(), error.c_str());
      return cli::kExitFailure;
    }
    renderer = render::renderer_name(*state);
    kind_text = render::timing_kind(*state);
    kind = kind_text.find("GPU") != std::string::npos ? "gpu" : "wall";
    geom::Camera view = b.default_view ? render::default_view(*state, width, height) : b.view;
    view.width = width, view.height = height;
    const geom::ShadowReference ref =
        geom::shadow_reference(geom::positions_of(b.scene.positions.data(), b.scene.vertex_count()),
                               b.scene.indices.data(), b.scene.indices.size(), view, b.light);
    if (!ref.ok) {
      cli::error("scene %s: reference: %s", name.c_str(), ref.error.c_str());
      return cli::kExitFailure;
    }
    // The area-light reference, where a soft technique runs.
    float sb[4];
    render::scene_bounds(*state, sb);
    const bool directional = b.light.type == geom::LightType::Directional;
    const float radius = float(light_radius >= 0 ? light_radius : directional ? 0.02 : 0.04 * sb[3]);
    geom::AreaReference area;
    if (std::any_of(techniques.begin(), techniques.end(), render::technique_is_soft)) {
      area = geom::area_light_reference(geom::positions_of(b.scene.positions.data(), b.scene.vertex_count()),
                                        b.scene.indices.data(), b.scene.indices.size(), view, b.light, radius, 64);
      if (!area.ok) {
        cli::error("scene %s: area reference: %s", name.c_str(), area.error.c_str());
        return cli::kExitFailure;
      }
    }
    scenes_done.push_back(name);
    if (b.hard) hard.insert(name);
    std::printf("\n%s: %s; %zu triangles; %dx%d; %s\n", name.c_str(), b.description.c_str(), b.scene.triangle_count(),
                width, height, kind_text.c_str());
    if (area.ok) std::printf("  light radius %g (soft techniques; err frac: vs the area-light reference)\n", radius);
    std::printf("  %-10s %6s %10s %10s %10s %10s %10s %10s  %s\n", "technique", "map", "time ms", "err vis", "err bnd",
                "err cast", "err self", "err frac", "projection drawn");
    for (render::Technique t : techniques) {
      if (render::technique_needs_point_light(t) && b.light.type == geom::LightType::Directional) {
        std::printf("  %-10s (needs a point or spot light: not measured)\n", render::technique_name(t));
        continue;
      }
      bool warm = false;
      for (int size : render::technique_has_map(t) ? sizes : std::vector<int>{0}) {
        render::FrameSettings fs;
        fs.technique = t, fs.output = render::Output::Mask, fs.shadow_map_size = size ? size : 1024;
        const bool soft = render::technique_is_soft(t);
        if (soft) fs.output = render::Output::Fraction, fs.light_radius = radius;
        geom::PngImage mask;
        std::vector<render::PassTime> times;
        // Fewer frames where one is slow (4096 maps, the heavy scene), never fewer sizes.
        const int n = (size >= 4096 || b.scene.triangle_count() > 100000) ? std::min(frames, 1) : frames;
        std::vector<double> ms;
        for (int f = warm ? 0 : -1; f < n; ++f) {
          times.clear();
          if (!render::render(*state, view, b.light, fs, mask, times, error)) {
            cli::error("scene %s, %s: %s", name.c_str(), render::technique_name(t), error.c_str());
            return cli::kExitFailure;
          }
          if (f < 0) continue;
          double sum = 0;
          for (const render::PassTime& p : times)
            if (is_shadow_pass(p.pass)) sum += p.ms;
          ms.push_back(sum);
        }
        warm = true;
        std::sort(ms.begin(), ms.end());
        Row r;
        r.scene = name, r.technique = render::technique_name(t), r.size = size, r.time_kind = kind;
        r.time_ms = ms[ms.size() / 2], r.frames = n, r.triangles = b.scene.triangle_count();
        r.projection = render::drawn_projection(*state);
        if (area.ok) r.error_fraction = geom::mean_fraction_error(mask.pixels, area);
        if (soft)  // the hard state of a fraction: lit from 0.5 on
          for (uint8_t& v : mask.pixels) v = v >= 128 ? 255 : 0;
        score(mask, ref, r);
        rows.push_back(r);
        std::printf("  %-10s %6s %10.3f %10.5f %10.5f %10.5f %10.5f %10.5f  %s\n", r.technique.c_str(),
                    size ? std::to_string(size).c_str() : "-", r.time_ms, r.error_visible, r.error_boundary,
                    r.error_cast, r.error_self, r.error_fraction, r.projection.c_str());
        std::fflush(stdout);
      }
    }
  }

  const std::vector<std::string> best = budget_summary(rows);
  const std::vector<std::string> goal_lines = goals(rows, hard, bake);
  if (!rows.empty()) {
    std::printf("\nBest technique at each time budget (mean time and mean error over the scenes):\n");
    for (const std::string& l : best) std::printf("  %s\n", l.c_str());
  }
  if (!goal_lines.empty()) {
    const std::string times = rows.empty()   ? std::string("bake: CPU time per call")
                              : bake.empty() ? kind + " time"
                                             : kind + " time; bake: CPU time per call";
    std::printf("\nGoals of the full run (%s):\n", times.c_str());
    for (const std::string& l : goal_lines) std::printf("  %s\n", l.c_str());
  }

  if (!out_dir.empty()) {
    std::ostringstream csv;
    csv << "scene,technique,shadow_map_size,time_ms,time_kind,error_visible,error_boundary,visible_pixels,"
           "boundary_pixels,frames,triangles,error_cast,error_self,cast_pixels,self_pixels,error_fraction,projection\n";
    nlohmann::json results = nlohmann::json::array();
    for (const Row& r : rows) {
      csv << r.scene << "," << r.technique << "," << r.size << "," << fmt("%.4f", r.time_ms) << "," << r.time_kind
          << "," << fmt("%.6f", r.error_visible) << "," << fmt("%.6f", r.error_boundary) << "," << r.visible << ","
          << r.boundary << "," << r.frames << "," << r.triangles << "," << fmt("%.6f", r.error_cast) << ","
          << fmt("%.6f", r.error_self) << "," << r.cast << "," << r.self << "," << fmt("%.6f", r.error_fraction)
          << "," << r.projection << "\n";  // render::drawn_projection: never a comma
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
                         {"projection", r.projection}});
    }
    std::ostringstream bcsv;
    bcsv << "triangles,method,seconds,triangles_per_second,peak_bytes,speed_vs_meshopt,memory_vs_meshopt\n";
    nlohmann::json bj = nlohmann::json::array();
    for (size_t i = 0; i < bake.size(); ++i) {
      const geombench::BakeRow& r = bake[i];
      const geombench::BakeRow& mo = bake[i - i % 3 + 1];
      const double sp = r.triangles_per_second / std::max(1.0, mo.triangles_per_second);
      const double mem = mo.peak_bytes > 0 ? r.peak_bytes / mo.peak_bytes : 0.0;
      bcsv << r.triangles << "," << r.method << "," << fmt("%.6f", r.seconds) << ","
           << fmt("%.0f", r.triangles_per_second) << "," << fmt("%.0f", r.peak_bytes) << "," << fmt("%.3f", sp) << ","
           << fmt("%.3f", mem) << "\n";
      bj.push_back({{"triangles", r.triangles},
                    {"method", r.method},
                    {"seconds", r.seconds},
                    {"triangles_per_second", r.triangles_per_second},
                    {"peak_bytes", r.peak_bytes},
                    {"speed_vs_meshopt", sp},
                    {"memory_vs_meshopt", mem}});
    }
    std::vector<std::string> tech_names;
    for (render::Technique t : techniques) tech_names.push_back(render::technique_name(t));
    nlohmann::json j = {{"renderer", renderer},   {"timing", kind_text},
                        {"time_kind", kind},      {"image", {{"width", width}, {"height", height}}},
                        {"quick", quick},         {"shadow_map_sizes", sizes},
                        {"scenes", scenes_done},  {"skipped", skipped},
                        {"results", results},     {"bake", bj},
                        {"best_at_budget", best}, {"goals", goal_lines}};
    std::ostringstream md;
    md << "# geombench summary\n\nrenderer: " << renderer << "; timing: " << kind_text << "; image " << width << "x"
       << height << "\n\n## Best technique at each time budget\n\n";
    for (const std::string& l : best) md << "- " << l << "\n";
    md << "\n## Goals\n\n";
    for (const std::string& l : goal_lines) md << "- " << l << "\n";
    for (const std::string& l : skipped) md << "- skipped scene " << l << "\n";
    const bool ok = write_text(out_dir + "/results.csv", csv.str()) && write_text(out_dir + "/bake.csv", bcsv.str()) &&
                    write_text(out_dir + "/results.json", j.dump(1) + "\n") &&
                    write_text(out_dir + "/plot.svg", plot_svg(rows, scenes_done, tech_names, kind)) &&
                    write_text(out_dir + "/summary.md", md.str());
    if (!ok) {
      cli::error("%s: cannot write the results", out_dir.c_str());
      return cli::kExitFailure;
    }
    std::printf("\nwrote %s/results.csv, results.json, bake.csv, plot.svg, summary.md\n", out_dir.c_str());
  }
  return 0;
}
