// focus_body.cpp: the focus body H = conv(R u {l}) n S n L of perspective
// shadow maps (Stamminger and Drettakis 2002, Sect. 4.1:
// "we use the computational geometry library CGAL to perform these geometric
// computations"). R = V n S n L is the receiver region (geom/focus.h).
//
// The only file of the focus code that includes CGAL (Exact_predicates_
// inexact_constructions kernel: exact orientation tests, so coplanar points
// and a light on a frustum plane never give a wrong hull).
//
// Per frame (focus_by_planes): conv(R u {l}) is the intersection of R's planes
// that keep the light inside and of the planes through the light and R's
// silhouette edges; the silhouette is CGAL's 2D convex hull (convex_hull_2) of
// R's vertices projected from the light. H is then the scene box clipped by
// those planes and by S's and L's: plane clips of a convex polytope of a few
// dozen vertices (polytope_clip.cpp). Measured (bench_focus), this costs a few
// microseconds where CGAL's 3D quickhull of R and the light (focus_hull, kept
// as the fallback for a silhouette of no area) costs 60-200.
// H's faces for the caller (index_polytope) are the clipped polygons when
// they close cleanly (checked: no T-junction, no sliver, V - E + F = 2), else
// CGAL's 3D hull of H's vertices, read from a Surface_mesh (CGAL 5.5's indexed-triangle-set output
// was seen to return a wrong surface for coplanar points), with coplanar
// triangles merged by union-find over shared edges so the topology stays
// closed whatever the tolerance decides.
#include "focus_body.h"

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>

namespace geom {
namespace focus {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

// The hull in an order that depends on its points alone: vertices sorted
// (x, then y, then z), each triangle starting at its least vertex (its
// orientation kept), triangles sorted. CGAL's output order follows where its
// internal structures lie in memory, so two calls on the same points could
// list them differently, and the planes and faces made from them would
// differ in order and in the last bits.
static void canonical_order(std::vector<Point>& verts, std::vector<std::array<size_t, 3>>& tris) {
  thread_local std::vector<size_t> order, rank;
  thread_local std::vector<Point> sorted;
  order.resize(verts.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Point &p = verts[a], &q = verts[b];
    return p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : p.z() < q.z();
  });
  rank.resize(verts.size());
  sorted.clear();
  for (size_t i = 0; i < order.size(); ++i) rank[order[i]] = i, sorted.push_back(verts[order[i]]);
  verts.swap(sorted);
  for (auto& t : tris) {
    for (size_t& v : t) v = rank[v];
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  }
  std::sort(tris.begin(), tris.end());
}

// CGAL's quickhull into a Surface_mesh, read back as points and triangles
// (canonical_order).
// (CGAL 5.5's indexed-triangle-set output of convex_hull_3 can return a
// triangle turned inside out where several points are coplanar; the
// Surface_mesh output is consistent.)
static bool cgal_hull(const std::vector<Point>& in, std::vector<Point>& verts,
                      std::vector<std::array<size_t, 3>>& tris) {
  verts.clear();
  tris.clear();
  if (in.size() < 4) return false;
  thread_local Mesh mesh;
  mesh.clear();
  CGAL::convex_hull_3(in.begin(), in.end(), mesh);
  if (mesh.number_of_faces() < 4) return false;
  // Compact indices: the mesh may hold removed vertices (index gaps).
  thread_local std::vector<size_t> remap;
  remap.assign(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), size_t(-1));
  for (Mesh::Vertex_index v : mesh.vertices()) {
    if (size_t(v) >= remap.size()) remap.resize(size_t(v) + 1, size_t(-1));
    remap[size_t(v)] = verts.size();
    verts.push_back(mesh.point(v));
  }
  for (Mesh::Face_index f : mesh.faces()) {
    std::array<size_t, 3> t{};
    size_t k = 0;
    for (Mesh::Halfedge_index h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) {
      if (k == 3) return false;  // quickhull gives triangles only
      t[k++] = remap[size_t(mesh.target(h))];
    }
    if (k != 3) return false;
    tris.push_back(t);
  }
  canonical_order(verts, tris);
  return true;
}

bool hull_polytope(const V3* points, size_t count, Polytope& out) {
  out.clear();
  try {
    thread_local std::vector<Point> in;
    thread_local std::vector<Point> verts;
    thread_local std::vector<std::array<size_t, 3>> tris;
    in.clear();
    verts.clear();
    tris.clear();
    in.reserve(count);
    for (size_t i = 0; i < count; ++i) in.emplace_back(points[i].x, points[i].y, points[i].z);
    if (!cgal_hull(in, verts, tris)) return false;
    for (const auto& t : tris) {
      for (size_t k = 0; k < 3; ++k) {
        const Point& q = verts[t[k]];
        out.pts.emplace_back(q.x(), q.y(), q.z());
      }
      out.sizes.push_back(3);
    }
  } catch (const std::exception&) {
    out.clear();
  }
  return !out.empty();
}

// A point is a duplicate when a point already kept lies within eps of it in
// every coordinate (near_point). The kept points are also listed by x, so
// only those whose x lies near enough are compared (the window is widened by
// more than x's rounding): the answer of comparing with every kept point.
void unique_vertices(const Polytope& p, double eps, std::vector<V3>& out) {
  out.clear();
  thread_local std::vector<std::pair<double, uint32_t>> by_x;
  by_x.clear();
  for (V3 q : p.pts) {
    const double slack = 2 * eps + 1e-12 * std::fabs(q.x);
    auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(q.x - slack, uint32_t(0)));
    bool dup = false;
    for (; it != by_x.end() && it->first <= q.x + slack && !dup; ++it) dup = near_point(out[it->second], q, eps);
    if (dup) continue;
    by_x.insert(std::upper_bound(by_x.begin(), by_x.end(), std::make_pair(q.x, uint32_t(out.size()))),
                std::make_pair(q.x, uint32_t(out.size())));
    out.push_back(q);
  }
}

// The clipped polygons themselves as the faces, when they already form a
// clean closed surface: every polygon keeps at least 3 distinct corners and
// an area above the tolerance, and every directed edge has exactly one
// reverse twin (no T-junction). False otherwise (the CGAL hull decides).
static bool index_clipped(const Polytope& p, double eps, std::vector<double>& xyz, std::vector<uint32_t>& sizes,
                          std::vector<uint32_t>& indices) {
  thread_local std::vector<V3> verts;
  thread_local std::vector<std::pair<double, uint32_t>> by_x;  // verts listed by x
  thread_local std::vector<std::pair<uint32_t, uint32_t>> directed;
  verts.clear();
  by_x.clear();
  directed.clear();
  size_t base = 0;
  for (uint32_t n : p.sizes) {
    size_t start = indices.size();
    for (uint32_t i = 0; i < n; ++i) {
      V3 q = p.pts[base + i];
      // The first vertex kept within eps of q in every coordinate (the least
      // id): only those whose x lies near enough (the window widened by more
      // than x's rounding, as in unique_vertices) are compared, the answer of
      // comparing with every kept vertex in order.
      uint32_t id = uint32_t(verts.size());
      const double slack = 2 * eps + 1e-12 * std::fabs(q.x);
      auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(q.x - slack, uint32_t(0)));
      for (; it != by_x.end() && it->first <= q.x + slack; ++it)
        if (it->second < id && max_abs(verts[it->second] - q) <= eps) id = it->second;
      if (id == verts.size()) {
        by_x.insert(std::upper_bound(by_x.begin(), by_x.end(), std::make_pair(q.x, id)), std::make_pair(q.x, id));
        verts.push_back(q);
      }
      if (indices.size() > start && (indices.back() == id || indices[start] == id)) continue;
      indices.push_back(id);
    }
    base += n;
    size_t m = indices.size() - start;
    if (m < 3) return false;
    V3 area(0, 0, 0);
    double perimeter = 0;
    const V3 first = verts[indices[start]];
    for (size_t i = 0; i < m; ++i) {
      const uint32_t a = indices[start + i], b = indices[i + 1 == m ? start : start + i + 1];
      area = area + cross(verts[a] - first, verts[b] - first);
      perimeter += length(verts[b] - verts[a]);
      directed.push_back({a, b});
    }
    if (!(0.5 * length(area) > 8 * eps * perimeter)) return false;  // a sliver: no clean face
    sizes.push_back(uint32_t(m));
  }
  std::sort(directed.begin(), directed.end());
  for (size_t i = 0; i < directed.size(); ++i) {
    if (i + 1 < directed.size() && directed[i] == directed[i + 1]) return false;
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(directed[i].second, directed[i].first)))
      return false;
  }
  if (long(verts.size()) - long(directed.size() / 2) + long(sizes.size()) != 2) return false;
  for (V3 v : verts) xyz.insert(xyz.end(), {v.x, v.y, v.z});
  return true;
}

// Union-find over the hull's triangles: adjacent triangles coplanar within the
// tolerance share a root, a region's plane being that of its largest triangle
// (the root), so a sliver along an edge cannot chain the two faces it touches
// into one. `edges` are the directed edges (a, b, triangle), sorted.
struct CoplanarRegions {
  const std::vector<Point>* verts_ = nullptr;
  const std::vector<std::array<size_t, 3>>* tris_ = nullptr;
  std::vector<std::array<uint32_t, 3>> edges;
  std::vector<Plane> planes;
  std::vector<double> area;
  std::vector<uint32_t> parent;

  const std::vector<std::array<size_t, 3>>& tris() const { return *tris_; }
  V3 at(size_t i) const {
    const Point& q = (*verts_)[i];
    return V3(q.x(), q.y(), q.z());
  }
  uint32_t find(uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  // The triangle of the directed edge (b, a), or -1.
  int64_t twin_of(uint32_t a, uint32_t b) const {
    auto it = std::lower_bound(edges.begin(), edges.end(), std::array<uint32_t, 3>{b, a, 0});
    return it != edges.end() && (*it)[0] == b && (*it)[1] == a ? int64_t((*it)[2]) : -1;
  }

  void merge(double eps) {
    const size_t nt = tris().size();
    planes.resize(nt);
    area.resize(nt);
    parent.resize(nt);
    for (size_t i = 0; i < nt; ++i) {
      V3 a = at(tris()[i][0]), b = at(tris()[i][1]), c = at(tris()[i][2]);
      V3 n = cross(b - a, c - a);
      area[i] = length(n);
      planes[i] = plane_through(a, normalize(n));
      parent[i] = uint32_t(i);
    }
    edges.clear();
    for (size_t i = 0; i < nt; ++i)
      for (size_t k = 0; k < 3; ++k)
        edges.push_back({uint32_t(tris()[i][k]), uint32_t(tris()[i][(k + 1) % 3]), uint32_t(i)});
    std::sort(edges.begin(), edges.end());
    for (const auto& e : edges) {
      int64_t t = twin_of(e[0], e[1]);
      if (t < 0) continue;
      uint32_t ri = find(e[2]), rj = find(uint32_t(t));
      if (ri == rj) continue;
      uint32_t big = area[ri] >= area[rj] ? ri : rj, small = big == ri ? rj : ri;
      uint32_t edge_tri = small == ri ? e[2] : uint32_t(t);
      // (No normal test: a sliver's normal is noise; the distances decide.)
      bool flat = true;
      for (size_t k = 0; k < 3 && flat; ++k)
        flat = std::fabs(planes[big].eval(at(tris()[small][k]))) <= 8 * eps &&
               std::fabs(planes[big].eval(at(tris()[edge_tri][k]))) <= 8 * eps;
      if (flat) parent[small] = big;
    }
  }

  // Each region as one face, its boundary loop (its directed edges whose twin
  // lies in another region), or its triangles where the boundary is not one
  // simple loop (the tolerance merged a ring).
  void faces(std::vector<uint32_t>& sizes, std::vector<uint32_t>& indices) {
    thread_local std::vector<std::array<uint32_t, 3>> boundary;  // (region, a, b)
    boundary.clear();
    for (const auto& e : edges) {
      int64_t t = twin_of(e[0], e[1]);
      uint32_t r = find(e[2]);
      if (t < 0 || find(uint32_t(t)) != r) boundary.push_back({r, e[0], e[1]});
    }
    std::sort(boundary.begin(), boundary.end());
    for (size_t i = 0, j = 0; i < boundary.size(); i = j) {
      while (j < boundary.size() && boundary[j][0] == boundary[i][0]) ++j;
      if (walk_loop(boundary, i, j, indices)) {
        sizes.push_back(uint32_t(j - i));
        continue;
      }
      for (size_t t = 0; t < tris().size(); ++t)
        if (find(uint32_t(t)) == boundary[i][0]) {
          for (size_t k = 0; k < 3; ++k) indices.push_back(uint32_t(tris()[t][k]));
          sizes.push_back(3);
        }
    }
  }

  // The loop of boundary edges [i, j) from the region's first edge (the next
  // edge starts where this one ends) appended to `indices`; false (nothing
  // appended) when they are not one simple loop.
  static bool walk_loop(const std::vector<std::array<uint32_t, 3>>& boundary, size_t i, size_t j,
                        std::vector<uint32_t>& indices) {
    const size_t count = j - i, start = indices.size();
    const uint32_t first = boundary[i][1];
    uint32_t v = first;
    bool ok = true;
    for (size_t step = 0; step < count && ok; ++step) {
      indices.push_back(v);
      size_t k = i;
      while (k < j && boundary[k][1] != v) ++k;
      if (k == j)
        ok = false;
      else
        v = boundary[k][2];
      if (ok && v == first && step + 1 != count) ok = false;  // several loops: not a disk
    }
    if (ok && v == first) return true;
    indices.resize(start);
    return false;
  }
};

// A vertex inside a merged face (a hair off its plane) is no corner: drops
// the vertices no face uses, so the output is exactly the faces' corners.
static void drop_unused(size_t vertex_count, std::vector<double>& xyz, std::vector<uint32_t>& indices) {
  thread_local std::vector<uint32_t> renumber;
  renumber.assign(vertex_count, UINT32_MAX);
  for (uint32_t v : indices) renumber[v] = 0;
  size_t kept = 0;
  for (size_t v = 0; v < vertex_count; ++v)
    if (renumber[v] == 0) {
      renumber[v] = uint32_t(kept);
      for (int k = 0; k < 3; ++k) xyz[3 * kept + k] = xyz[3 * v + k];
      ++kept;
    }
  xyz.resize(3 * kept);
  for (uint32_t& v : indices) v = renumber[v];
}

void index_polytope(const Polytope& p, double eps, std::vector<double>& xyz, std::vector<uint32_t>& sizes,
                    std::vector<uint32_t>& indices) {
  xyz.clear();
  sizes.clear();
  indices.clear();
  if (index_clipped(p, eps, xyz, sizes, indices)) return;
  xyz.clear();
  sizes.clear();
  indices.clear();
  // The faces come from a CGAL hull of the clipped body's distinct vertices:
  // exact predicates give a consistent closed surface even where clipping left
  // a vertex a hair off a face (a sliver face the tolerances cannot see).
  thread_local std::vector<V3> pts;
  thread_local std::vector<Point> in, verts;
  thread_local std::vector<std::array<size_t, 3>> tris;
  unique_vertices(p, eps, pts);
  in.clear();
  verts.clear();
  tris.clear();
  for (V3 q : pts) in.emplace_back(q.x, q.y, q.z);
  try {
    if (!cgal_hull(in, verts, tris)) return;  // flat: no closed surface
  } catch (const std::exception&) {
    return;
  }
  for (const Point& q : verts) xyz.insert(xyz.end(), {q.x(), q.y(), q.z()});
  // Adjacent triangles that are coplanar within the tolerance merge into one
  // face, and each face is the boundary loop of its triangles: the topology
  // stays CGAL's closed surface whatever the tolerance decides (V - E + F = 2).
  thread_local CoplanarRegions r;  // working memory, per thread
  r.verts_ = &verts, r.tris_ = &tris;
  r.merge(eps);
  r.faces(sizes, indices);
  drop_unused(verts.size(), xyz, indices);
}

bool hull_planes(PositionSpan points, std::vector<Plane>& out) {
  out.clear();
  thread_local std::vector<V3> pts;
  pts.clear();
  pts.reserve(points.size());  // exactly: a bake's hull copies every vertex
  for (size_t i = 0; i < points.size(); ++i) {
    const Float3& f = points[i];
    V3 q(f.x, f.y, f.z);
    if (!finite(q)) return false;
    pts.push_back(q);
  }
  Polytope hull;
  if (!hull_polytope(pts.data(), pts.size(), hull)) return false;
  // Each face's plane (inside is n.x + d >= 0) and area.
  thread_local std::vector<std::pair<double, Plane>> faces;
  faces.clear();
  for (size_t t = 0; t < hull.sizes.size(); ++t) {
    V3 a = hull.pts[3 * t], b = hull.pts[3 * t + 1], c = hull.pts[3 * t + 2];
    V3 n = cross(b - a, c - a);
    if (!(length(n) > 0)) continue;
    faces.push_back({length(n), plane_through(a, -normalize(n))});  // outward n: inside is -n.x + d >= 0
  }
  // The largest faces first (ties by the plane, so the order is the points'
  // alone); a face whose direction a chosen plane already has adds nothing.
  std::sort(faces.begin(), faces.end(), [](const auto& x, const auto& y) {
    if (x.first != y.first) return x.first > y.first;
    const Plane &p = x.second, &q = y.second;
    return p.n.x != q.n.x ? p.n.x < q.n.x : p.n.y != q.n.y ? p.n.y < q.n.y : p.n.z != q.n.z ? p.n.z < q.n.z : p.d < q.d;
  });
  for (const auto& f : faces) {
    if (out.size() == kMaxHullPlanes) break;
    bool known = false;
    for (const Plane& p : out) known = known || dot(p.n, f.second.n) > 1 - 1e-12;
    if (!known) out.push_back(f.second);
  }
  // Each plane moved to support the hull: every vertex inside, in the
  // arithmetic the clips use (a face's own plane moves by rounding at most).
  for (Plane& p : out) {
    double lowest = HUGE_VAL;
    for (V3 q : hull.pts) lowest = std::fmin(lowest, dot(p.n, q));
    p.d = -lowest;
  }
  return out.size() >= 4;
}

}  // namespace focus

bool focus_caster_hull(PositionSpan casters, std::vector<double>& planes) {
  planes.clear();
  try {
    std::vector<focus::Plane> hull;
    if (!focus::hull_planes(casters, hull)) return false;
    for (const focus::Plane& p : hull) planes.insert(planes.end(), {p.n.x, p.n.y, p.n.z, p.d});
    return true;
  } catch (...) {  // allocation failure: never past the library boundary
    planes.clear();
    return false;
  }
}

namespace focus {

void focus_hull(const Polytope& receivers, V3 light, bool directional, double reach, const Plane* clip,
                size_t clip_count, double eps, std::vector<V3>& hull_points, Polytope& out, Polytope& scratch,
                StageTimes* times) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point t0 = times ? Clock::now() : Clock::time_point();
  out.clear();
  if (receivers.empty()) return;
  unique_vertices(receivers, eps, hull_points);
  size_t n = hull_points.size();
  if (directional) {
    // R + [0, T] u with T large enough to leave S: exact for R + [0, inf) u inside S.
    double lowest = dot(hull_points[0], light);
    for (size_t i = 1; i < n; ++i) lowest = std::fmin(lowest, dot(hull_points[i], light));
    double t = std::fmax(reach - lowest, 0.0) * 1.01 + 16 * eps;
    for (size_t i = 0; i < n; ++i) hull_points.push_back(hull_points[i] + light * t);
  } else {
    hull_points.push_back(light);
  }
  if (!hull_polytope(hull_points.data(), hull_points.size(), out)) {
    // Flat input: R has no volume and the light lies in its plane. R itself
    // (already inside S n L) is the body.
    out = receivers;
    return;
  }
  Clock::time_point t1 = times ? Clock::now() : Clock::time_point();
  clip_polytope(out, clip, clip_count, eps, scratch);
  if (times) {
    times->hull += std::chrono::duration<double>(t1 - t0).count();
    times->clip += std::chrono::duration<double>(Clock::now() - t1).count();
  }
}

}  // namespace focus
}  // namespace geom

namespace geom {
namespace focus {

bool focus_by_planes(const std::vector<V3>& r_verts, V3 light, bool directional, V3 axis, const Plane* r_planes,
                     size_t r_count, const Plane* k_planes, size_t k_count, const V3 box[8], double eps,
                     std::vector<Plane>& planes, Polytope& out, Polytope& scratch, StageTimes* times,
                     const Polytope* start) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point t0 = times ? Clock::now() : Clock::time_point();
  out.clear();
  if (r_verts.size() < 3) return false;
  // R's vertices seen from the light: a 2D frame across the axis.
  V3 e1 = any_perpendicular(axis), e2 = cross(axis, e1);
  thread_local std::vector<Kernel::Point_2> flat;
  thread_local std::vector<size_t> order, ring;
  flat.clear();
  order.clear();
  ring.clear();
  V3 centre(0, 0, 0);
  for (size_t i = 0; i < r_verts.size(); ++i) {
    V3 d = directional ? r_verts[i] : r_verts[i] - light;
    double depth = directional ? 1.0 : dot(d, axis);
    if (!(depth > 0)) return false;
    flat.emplace_back(dot(d, e1) / depth, dot(d, e2) / depth);
    order.push_back(i);
    centre = centre + r_verts[i] * (1.0 / double(r_verts.size()));
  }
  using Traits = CGAL::Convex_hull_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Kernel::Point_2>::type>;
  try {
    CGAL::convex_hull_2(order.begin(), order.end(), std::back_inserter(ring), Traits(CGAL::make_property_map(flat)));
  } catch (const std::exception&) {
    return false;
  }
  if (ring.size() < 3) return false;
  planes.clear();
  // Planes of R that hold the light (or the whole ray towards it) inside.
  for (size_t i = 0; i < r_count; ++i) {
    const Plane& p = r_planes[i];
    bool keeps = directional ? dot(p.n, axis) >= -1e-12 * length(p.n) : p.eval(light) >= -eps * length(p.n);
    if (keeps) planes.push_back(p);
  }
  // Silhouette planes, oriented towards R's centre. An edge seen end-on from
  // the light (its two ends project to one point) bounds nothing and has no
  // well-defined plane: skipped (its neighbours' planes close the cone).
  double extent = 0;
  for (size_t k = 0; k < ring.size(); ++k)
    extent = std::fmax(extent, std::sqrt(CGAL::to_double(CGAL::squared_distance(flat[ring[k]], flat[ring[0]]))));
  for (size_t k = 0; k < ring.size(); ++k) {
    size_t i = ring[k], j = ring[(k + 1) % ring.size()];
    if (std::sqrt(CGAL::to_double(CGAL::squared_distance(flat[i], flat[j]))) <= 1e-7 * extent) continue;
    V3 a = r_verts[i], b = r_verts[j];
    V3 n = directional ? cross(b - a, axis) : cross(a - light, b - a);
    double len = length(n);
    if (!(len > 0)) continue;
    Plane p = plane_through(a, n * (1.0 / len));
    if (p.eval(centre) < 0) p = {-p.n, -p.d};
    planes.push_back(p);
  }
  planes.insert(planes.end(), k_planes, k_planes + k_count);
  if (start)
    out = *start;
  else
    frustum_polytope(box, out);
  Clock::time_point t1 = times ? Clock::now() : Clock::time_point();
  clip_polytope(out, planes.data(), planes.size(), eps, scratch);
  if (times) {
    times->hull += std::chrono::duration<double>(t1 - t0).count();
    times->clip += std::chrono::duration<double>(Clock::now() - t1).count();
  }
  return true;
}

}  // namespace focus
}  // namespace geom
