// polytope_clip.cpp: convex polytopes as lists of convex polygons (focus_body.h):
// a frustum's, and the cut of one by planes, each polygon clipped
// Sutherland-Hodgman style and the cut closed by a cap polygon. The focus
// body H of perspective shadow maps (Stamminger and Drettakis 2002, Sect. 4.1)
// is such clips of the scene box; no CGAL here.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "focus_body.h"

namespace geom {
namespace focus {

void frustum_polytope(const V3 c[8], Polytope& out) {
  // Counter-clockwise seen from outside for a right-handed camera (near face
  // seen from the eye: x right, y up); reversed below for a mirrored one.
  static const int faces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 3, 7, 4}, {1, 5, 6, 2}, {0, 4, 5, 1}, {3, 2, 6, 7}};
  V3 centre(0, 0, 0);
  for (int i = 0; i < 8; ++i) centre = centre + c[i] * 0.125;
  V3 far_normal = cross(c[7] - c[4], c[6] - c[7]);
  bool mirrored = dot(far_normal, c[4] - centre) < 0;
  out.clear();
  for (const auto& f : faces) {
    for (int k = 0; k < 4; ++k) out.pts.push_back(c[f[mirrored ? 3 - k : k]]);
    out.sizes.push_back(4);
  }
}

// Sorts `pts[first..]` counter-clockwise around `normal` (seen from where it
// points), by each point's angle around their centroid, computed once.
static void sort_around(std::vector<V3>& pts, size_t first, V3 normal) {
  size_t n = pts.size() - first;
  V3 c(0, 0, 0);
  for (size_t i = first; i < pts.size(); ++i) c = c + pts[i];
  c = c * (1.0 / double(n));
  V3 u = any_perpendicular(normalize(normal));
  V3 v = cross(normalize(normal), u);
  thread_local std::vector<std::pair<double, V3>> keyed;
  keyed.clear();
  for (size_t i = first; i < pts.size(); ++i)
    keyed.push_back({std::atan2(dot(pts[i] - c, v), dot(pts[i] - c, u)), pts[i]});
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < n; ++i) pts[first + i] = keyed[i].second;
}

// clip_polytope of one plane; false when nothing was cut (p unchanged).
static bool clip_one(Polytope& p, const Plane& h, double eps, Polytope& scratch) {
  bool any_out = false, any_in = false;
  thread_local std::vector<double> dist;  // each point's signed distance, computed once
  dist.resize(p.pts.size());
  for (size_t i = 0; i < p.pts.size(); ++i) {
    const double d = dist[i] = h.eval(p.pts[i]);
    if (d < -eps) any_out = true;
    if (d > eps) any_in = true;
  }
  if (!any_out) return false;  // nothing to cut
  if (!any_in) {               // everything outside or on the plane: no volume left
    p.clear();
    return true;
  }
  scratch.clear();
  thread_local std::vector<V3> cap;
  cap.clear();
  size_t base = 0;
  for (uint32_t n : p.sizes) {
    size_t start = scratch.pts.size();
    for (uint32_t i = 0; i < n; ++i) {
      const size_t ia = base + i, ib = i + 1 == n ? base : ia + 1;  // the next corner, round the polygon
      V3 a = p.pts[ia], b = p.pts[ib];
      double da = dist[ia], db = dist[ib];
      if (da >= -eps) scratch.pts.push_back(a);
      if (std::fabs(da) <= eps) cap.push_back(a);
      if ((da < -eps && db > eps) || (da > eps && db < -eps)) {
        V3 x = a + (b - a) * (da / (da - db));
        scratch.pts.push_back(x);
        cap.push_back(x);
      }
    }
    size_t added = scratch.pts.size() - start;
    if (added >= 3)
      scratch.sizes.push_back(uint32_t(added));
    else
      scratch.pts.resize(start);
    base += n;
  }
  // The cap: the distinct points on the plane, counter-clockwise around -n.
  size_t start = scratch.pts.size();
  for (V3 q : cap) {
    bool dup = false;
    for (size_t i = start; i < scratch.pts.size() && !dup; ++i) dup = near_point(scratch.pts[i], q, eps);
    if (!dup) scratch.pts.push_back(q);
  }
  if (scratch.pts.size() - start >= 3) {
    sort_around(scratch.pts, start, -h.n);
    scratch.sizes.push_back(uint32_t(scratch.pts.size() - start));
  } else {
    scratch.pts.resize(start);
  }
  std::swap(p.pts, scratch.pts);
  std::swap(p.sizes, scratch.sizes);
  return true;
}

void clip_polytope(Polytope& p, const Plane& h, double eps, Polytope& scratch) { clip_one(p, h, eps, scratch); }

// The planes in turn; a plane that holds the polytope's bounding box inside,
// by more than eps plus the rounding of its distances, cannot cut (every
// point's distance is above -eps): it is passed over without visiting the
// points, the result the same as clip_one's.
void clip_polytope(Polytope& p, const Plane* planes, size_t count, double eps, Polytope& scratch) {
  V3 lo, hi;
  double size = 0;
  bool boxed = false;
  for (size_t i = 0; i < count && !p.empty(); ++i) {
    const Plane& h = planes[i];
    if (!boxed) {
      lo = hi = p.pts[0];
      for (V3 q : p.pts) {  // finite points: plain comparisons (no library call)
        lo.x = q.x < lo.x ? q.x : lo.x, lo.y = q.y < lo.y ? q.y : lo.y, lo.z = q.z < lo.z ? q.z : lo.z;
        hi.x = q.x > hi.x ? q.x : hi.x, hi.y = q.y > hi.y ? q.y : hi.y, hi.z = q.z > hi.z ? q.z : hi.z;
      }
      size = max_of(max_abs(lo), max_abs(hi));
      boxed = true;
    }
    const double low = h.d + (h.n.x >= 0 ? h.n.x * lo.x : h.n.x * hi.x) + (h.n.y >= 0 ? h.n.y * lo.y : h.n.y * hi.y) +
                       (h.n.z >= 0 ? h.n.z * lo.z : h.n.z * hi.z);
    const double rounding = 1e-9 * (std::fabs(h.d) + (std::fabs(h.n.x) + std::fabs(h.n.y) + std::fabs(h.n.z)) * size);
    if (low - rounding > eps) continue;
    if (clip_one(p, h, eps, scratch)) boxed = false;
  }
}

}  // namespace focus
}  // namespace geom
