// results.cpp: geombench's result files (results.h).
#include "results.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace geombench {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string results_csv(const std::vector<Row>& rows) {
  std::ostringstream csv;
  csv << "scene,technique,shadow_map_size,time_ms,time_kind,error_visible,error_boundary,visible_pixels,"
         "boundary_pixels,frames,triangles,error_cast,error_self,cast_pixels,self_pixels,error_fraction,projection,"
         "primitives,vs_invocations,"
         "gs_invocations,fs_invocations\n";
  for (const Row& r : rows)
    csv << r.scene << "," << r.technique << "," << r.size << "," << fmt("%.4f", r.time_ms) << "," << r.time_kind << ","
        << fmt("%.6f", r.error_visible) << "," << fmt("%.6f", r.error_boundary) << "," << r.visible << "," << r.boundary
        << "," << r.frames << "," << r.triangles << "," << fmt("%.6f", r.error_cast) << "," << fmt("%.6f", r.error_self)
        << "," << r.cast << "," << r.self << "," << fmt("%.6f", r.error_fraction) << ","
        << r.projection  // render::drawn_projection: never a comma
        << "," << r.primitives << "," << r.vs_invocations << "," << r.gs_invocations << "," << r.fs_invocations << "\n";
  return csv.str();
}

// speed and memory against meshoptimizer's row of the same mesh (every third row from the second)
void bake_ratios(const std::vector<BakeRow>& bake, size_t i, double& speed, double& memory) {
  const BakeRow& r = bake[i];
  const BakeRow& mo = bake[i - i % 3 + 1];
  speed = r.triangles_per_second / std::max(1.0, mo.triangles_per_second);
  memory = mo.peak_bytes > 0 ? r.peak_bytes / mo.peak_bytes : 0.0;
}

std::string bake_csv(const std::vector<BakeRow>& bake) {
  std::ostringstream bcsv;
  bcsv << "triangles,method,seconds,triangles_per_second,peak_bytes,speed_vs_meshopt,memory_vs_meshopt\n";
  for (size_t i = 0; i < bake.size(); ++i) {
    const BakeRow& r = bake[i];
    double sp = 0, mem = 0;
    bake_ratios(bake, i, sp, mem);
    bcsv << r.triangles << "," << r.method << "," << fmt("%.6f", r.seconds) << ","
         << fmt("%.0f", r.triangles_per_second) << "," << fmt("%.0f", r.peak_bytes) << "," << fmt("%.3f", sp) << ","
         << fmt("%.3f", mem) << "\n";
  }
  return bcsv.str();
}

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

}  // namespace geombench
