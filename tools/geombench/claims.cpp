// claims.cpp: the published claims a full geombench run checks (claims.h).
#include "claims.h"

#include <algorithm>
#include <cmath>

#include "size_law.h"

namespace geombench {
namespace {

// Two pixels of a frame: the slack of the per-pixel comparisons (rasterization
// rules at an outline can differ by a pixel between two correct drawings).
constexpr double kSlackPixels = 2;

// The wrong pixels behind an error figure (a count over `pixels`, rounded back to it).
double wrong_pixels(double error, size_t pixels) { return std::round(error * double(pixels)); }

const Row* find(const std::vector<Row>& rows, const std::string& scene, const std::string& t, int size) {
  for (const Row& r : rows)
    if (r.scene == scene && r.technique == t && r.size == size) return &r;
  return nullptr;
}

// The soft-shadow and silhouette-map checks: sssm's error within 1.5x edsm's at every size on pipes, default and
// scan; edsm-soft's light-fraction error below pcf-soft's at every size on pipes
// and default, at no more than 1.2x edsm's hard-shadow time.
void soft_claims(const std::vector<Row>& rows, std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "holds" : "fails"); };
  int n = 0, ok = 0, nf = 0, okf = 0, nt = 0, okt = 0, ne = 0, oke = 0;
  double worst = 0, worst_t = 0;
  std::string miss, miss_f;
  for (const Row& e : rows) {
    const bool sssm_scene = e.scene == "pipes" || e.scene == "default" || e.scene == "scan";
    if (e.technique == "edsm" && sssm_scene)
      if (const Row* s = find(rows, e.scene, "sssm", e.size)) {
        const double sw = wrong_pixels(s->error_cast, s->cast), ew = wrong_pixels(e.error_cast, e.cast);
        const bool met = sw <= 1.5 * ew + kSlackPixels;
        ++n, ok += met, worst = std::max(worst, sw - 1.5 * ew);
        if (!met && miss.size() < 200)
          miss +=
              " " + e.scene + "@" + std::to_string(e.size) + " (" + fmt("%.0f", sw) + " vs " + fmt("%.0f", ew) + " px)";
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
    out.push_back(verdict(ok == n) +
                  ": Sen et al. 2003, Sect. 5 (silhouette maps as exact as the edges they store): sssm error_cast "
                  "<= 1.5x edsm's + 2 pixels on pipes, default, scan: " +
                  std::to_string(ok) + " of " + std::to_string(n) + ", worst " + fmt("%.0f", worst) +
                  " px over 1.5x edsm's" + (miss.empty() ? "" : "; missed:" + miss));
  if (nf)
    out.push_back(verdict(okf == nf) +
                  ": Kenzel 2013, Sect. 6 (soft edges from the edge distance): edsm-soft light-fraction error < "
                  "pcf-soft's on pipes, default: " +
                  std::to_string(okf) + " of " + std::to_string(nf) + (miss_f.empty() ? "" : "; missed:" + miss_f));
  if (ne)  // esm-soft is this project's own extension: measured beside, no published claim
    out.push_back("(measured, no published claim) esm-soft light-fraction error < pcf-soft's on pipes, default: " +
                  std::to_string(oke) + " of " + std::to_string(ne));
  if (nt)
    out.push_back(verdict(okt == nt) +
                  ": Kenzel 2013, Sect. 6 (soft shadows at little extra cost): edsm-soft time <= 1.2x edsm's on "
                  "pipes, default (same run): " +
                  std::to_string(okt) + " of " + std::to_string(nt) + ", worst " + fmt("%.2f", worst_t) + "x");
}

// The shadow volumes within rasterization tolerance of zero error.
void volume_claim(const std::vector<Row>& rows, std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "holds" : "fails"); };
  {  // shadow volumes within rasterization tolerance of zero
    double worst = 0;
    std::string where;
    int n = 0;
    for (const Row& r : rows)
      // depth-pass is invalid by construction on near-plane (its near plane in a shadow)
      if (r.technique.rfind("sv", 0) == 0 && !(r.technique == "sv-zpass" && r.scene == "near-plane")) {
        ++n;
        if (r.error_visible >= worst) worst = r.error_visible, where = r.scene + " " + r.technique;
      }
    if (n)
      out.push_back(verdict(worst <= 0.001) +
                    ": Everitt and Kilgard 2002 (robust shadow volumes are pixel-exact): wrong pixels <= 0.001 of "
                    "the visible ones: worst " +
                    fmt("%.5f", worst) + " (" + where + ")");
  }
}

// The pixel-exact claims on error_cast (Kenzel 2013, Sect. 5.2).
void cast_claims(const std::vector<Row>& rows, std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "holds" : "fails"); };
  // Kenzel 2013, Sect. 5.2 (pixel-exact hard shadows), judged on error_cast, on the pipes, default, jenga and scan
  // scenes, N = 512..2048: edsm@N <= ssm@N / 10 and <= ssm@4N, esm@N <= ssm@N / 3.
  const std::set<std::string> claim_scenes = {"pipes", "default", "jenga", "scan"};
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
      if (e.technique != g.technique || !claim_scenes.count(e.scene) || e.size < 512 || e.size > 2048) continue;
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
      out.push_back(verdict(ok == n) + ": Kenzel 2013, Sect. 5.2 (pixel-exact hard shadows): " + g.technique +
                    "@N error_cast <= ssm@" +
                    (g.ssm_factor == 1 ? std::string("N") : std::to_string(g.ssm_factor) + "N") +
                    (g.divisor != 1 ? " / " + fmt("%g", g.divisor) : std::string()) +
                    " (pipes, default, jenga, scan; N = 512..2048): " + std::to_string(ok) + " of " +
                    std::to_string(n) + (misses.empty() ? "" : "; missed:" + misses));
  }
}

// The silhouette maps never worse than ssm in error_visible, and their cost against ssm's.
void map_claims(const std::vector<Row>& rows, std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "holds" : "fails"); };
  for (const char* t : {"esm", "esm-exact", "edsm"}) {  // never worse than ssm in error_visible
    int n = 0, ok = 0;
    std::string misses;
    for (const Row& e : rows) {
      if (e.technique != t) continue;
      const Row* s = find(rows, e.scene, "ssm", e.size);
      if (!s) continue;
      ++n;
      const double wrong = wrong_pixels(e.error_visible, e.visible),
                   ssm_wrong = wrong_pixels(s->error_visible, s->visible);
      const bool met = wrong <= ssm_wrong + kSlackPixels;
      ok += met;
      if (!met && misses.size() < 300)
        misses += " " + e.scene + "@" + std::to_string(e.size) + " (" + fmt("%.0f", wrong) + " vs " +
                  fmt("%.0f", ssm_wrong) + " px)";
    }
    if (n)
      out.push_back(verdict(ok == n) +
                    ": Kenzel 2013, Sect. 5.1; Bujnak 2004, Sect. 3 (the edges refine the depth test): " + t +
                    "@N wrong visible pixels <= ssm@N's + 2 on every scene: " + std::to_string(ok) + " of " +
                    std::to_string(n) + (misses.empty() ? "" : "; missed:" + misses));
  }
  // Cost against ssm's shadow passes, median over the cells (this project's
  // reading of "a low additional cost": at most 2x for edsm and sssm, whose
  // edge maps are drawn in two passes, 1.5x for esm and esm-exact).
  struct CostGoal {
    const char* technique;
    double bound;
  };
  for (const CostGoal g :
       {CostGoal{"esm", 1.5}, CostGoal{"esm-exact", 1.5}, CostGoal{"edsm", 2}, CostGoal{"sssm", 2}}) {
    std::vector<double> q;
    std::string kind;
    for (const Row& r : rows) {
      if (r.technique != g.technique) continue;
      const Row* s = find(rows, r.scene, "ssm", r.size);
      if (!s || s->time_ms <= 0) continue;
      q.push_back(r.time_ms / s->time_ms), kind = r.time_kind;
    }
    if (q.empty()) continue;
    std::sort(q.begin(), q.end());
    const double median = q.size() % 2 ? q[q.size() / 2] : 0.5 * (q[q.size() / 2 - 1] + q[q.size() / 2]);
    out.push_back(verdict(median <= g.bound) +
                  ": Kenzel 2013, Sect. 5.1 (a low additional cost over shadow mapping): " + g.technique +
                  " time <= " + fmt("%g", g.bound) + "x ssm's in median (" + kind + " time" +
                  (kind == "wall" ? ", software rasterizer: the claim is about GPUs" : "") + "): median " +
                  fmt("%.2f", median) + "x, worst " + fmt("%.2f", q.back()) + "x over " + std::to_string(q.size()) +
                  " cells");
  }
}

// This project's goals beside the papers' claims: the warped maps never worse
// than the uniform map they warp (1.1x its wrong pixels + 2, every scene and
// size), and no map technique shadowing its own lit faces (error_self at most
// 0.2% at 1024 texels and above).
void goal_claims(const std::vector<Row>& rows, std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "holds" : "fails"); };
  for (const char* t : {"psm", "lispsm"}) {
    int n = 0, ok = 0;
    std::string misses;
    for (const Row& r : rows) {
      const Row* u = r.technique == t ? find(rows, r.scene, "uniform", r.size) : nullptr;
      if (!u) continue;
      const double w = wrong_pixels(r.error_visible, r.visible), uw = wrong_pixels(u->error_visible, u->visible);
      const bool met = w <= 1.1 * uw + kSlackPixels;
      ++n, ok += met;
      if (!met && misses.size() < 300)
        misses +=
            " " + r.scene + "@" + std::to_string(r.size) + " (" + fmt("%.0f", w) + " vs " + fmt("%.0f", uw) + " px)";
    }
    if (n)
      out.push_back(verdict(ok == n) + ": (this project's goal) " + t +
                    " wrong visible pixels <= 1.1x uniform's + 2 on every scene and size: " + std::to_string(ok) +
                    " of " + std::to_string(n) + (misses.empty() ? "" : "; missed:" + misses));
  }
  int n = 0, ok = 0;
  std::string misses;
  for (const Row& r : rows) {
    if (r.size < 1024 || r.error_self < 0) continue;
    const bool met = r.error_self <= 0.002;
    ++n, ok += met;
    if (!met && misses.size() < 400)
      misses += " " + r.technique + " " + r.scene + "@" + std::to_string(r.size) + " (" +
                fmt("%.3f", 100 * r.error_self) + "%)";
  }
  if (n)
    out.push_back(verdict(ok == n) +
                  ": (this project's goal) every map technique error_self <= 0.2% at 1024 and above: " +
                  std::to_string(ok) + " of " + std::to_string(n) + (misses.empty() ? "" : "; missed:" + misses));
}

// The warped maps against uniform on wide-depth, and the bake against meshoptimizer.
void warp_bake_claims(const std::vector<Row>& rows, const std::vector<geombench::BakeRow>& bake,
                      std::vector<std::string>& out) {
  auto verdict = [](bool ok) { return std::string(ok ? "holds" : "fails"); };
  for (const char* t : {"psm", "lispsm"}) {  // better than uniform on the wide depth range
    int n = 0, ok = 0;
    for (const Row& r : rows) {
      if (r.technique != t || r.scene != "wide-depth") continue;
      const Row* u = find(rows, r.scene, "uniform", r.size);
      if (!u) continue;
      ++n, ok += r.error_visible < u->error_visible;
    }
    if (n)
      out.push_back(verdict(ok == n) + ": Stamminger and Drettakis 2002, Sect. 1; Wimmer et al. 2004, Sect. 1 (the " +
                    "warp resolves a wide depth range better): " + t +
                    " error < uniform on wide-depth: " + std::to_string(ok) + " of " + std::to_string(n) + " sizes");
  }
  for (size_t i = 0; i + 2 < bake.size() + 0 && i + 1 < bake.size(); i += 3) {
    if (bake[i].method != "bake" || bake[i + 1].method != "meshopt") continue;
    const double q = bake[i].triangles_per_second / std::max(1.0, bake[i + 1].triangles_per_second);
    out.push_back(verdict(q >= 1) + ": (this project's figure) bake no slower than meshopt adjacency at " +
                  std::to_string(bake[i].triangles) + " triangles: " + fmt("%.2f", q) +
                  "x its throughput (the bake also welds, classifies and emits ESM " + "quads and the shadow volume)");
  }
}

}  // namespace

std::vector<std::string> claims(const std::vector<Row>& rows, const std::set<std::string>& hard,
                                const std::vector<geombench::BakeRow>& bake) {
  (void)hard;
  std::vector<std::string> out;
  volume_claim(rows, out);
  cast_claims(rows, out);
  map_claims(rows, out);
  warp_bake_claims(rows, bake, out);
  goal_claims(rows, out);
  soft_claims(rows, out);
  std::vector<geombench::SizePoint> points;  // error falls as the map grows (size_law.h)
  for (const Row& r : rows) {
    const bool soft = r.technique.size() > 5 && r.technique.compare(r.technique.size() - 5, 5, "-soft") == 0;
    points.push_back({r.scene, r.technique, r.size, soft ? r.error_fraction : r.error_visible, soft});
  }
  for (std::string& l : geombench::size_law_lines(points)) out.push_back(std::move(l));
  return out;
}

}  // namespace geombench
