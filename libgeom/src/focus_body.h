// focus_body.h (private): the convex-polytope steps of the focus body H
// (Stamminger and Drettakis 2002, Sect. 4.1), used by compute_focus.cpp.
//
// A Polytope is a convex body as a list of convex polygons (flat vertex
// coordinates + a vertex count per polygon), counter-clockwise seen from
// outside. Tolerances are absolute distances (`eps`).
#pragma once
#include <cstdint>
#include <vector>

#include "focus_math.h"
#include "geom/focus.h"
#include "geom/span.h"

namespace geom {
namespace focus {

using StageTimes = FocusStageTimes;  // geom/focus.h

struct Polytope {
  std::vector<V3> pts;
  std::vector<uint32_t> sizes;
  void clear() {
    pts.clear();
    sizes.clear();
  }
  bool empty() const { return sizes.empty(); }
};

// The frustum with these eight corners: 0-3 near (x-,y-), (x+,y-), (x+,y+),
// (x-,y+); 4-7 the same on the far side.
void frustum_polytope(const V3 corners[8], Polytope& out);

// p n {h.eval >= 0}, in place (scratch is working memory). A point within eps
// of the plane counts as inside. The cut is closed with a cap polygon.
void clip_polytope(Polytope& p, const Plane& h, double eps, Polytope& scratch);
void clip_polytope(Polytope& p, const Plane* planes, size_t count, double eps, Polytope& scratch);

// Convex hull of points with CGAL (Exact_predicates_inexact_constructions_kernel),
// as triangles. False (out empty) when the points span no volume and no polygon.
bool hull_polytope(const V3* points, size_t count, Polytope& out);

// The distinct vertices of p (merged within eps).
void unique_vertices(const Polytope& p, double eps, std::vector<V3>& out);

// The indexed form of p: merged vertices, and one convex polygon per plane
// (coplanar polygons merged), counter-clockwise seen from outside.
void index_polytope(const Polytope& p, double eps, std::vector<double>& xyz, std::vector<uint32_t>& sizes,
                    std::vector<uint32_t>& indices);

// The half-spaces of the convex hull of `points` (outward faces become
// inside-positive planes): the planes of its kMaxHullPlanes largest faces (of
// distinct directions), each moved to support the hull, so their
// intersection holds every point and is the hull itself when it has no more
// faces. Bounded so that clipping a frame's bodies by them stays cheap. In an
// order that depends on the points alone. False when they span no volume.
constexpr size_t kMaxHullPlanes = 16;
bool hull_planes(PositionSpan points, std::vector<Plane>& out);

// H = conv(R u {l}) n S n L, with R the receiver region (already clipped by S,
// L and the receiver bounds). For a directional light (`directional` true)
// `light` is the unit vector towards the light and conv(R u {l}) is R extruded
// along it up to where dot(x, light) >= reach (reach: the largest dot(s, light)
// over S, so the extrusion leaves S). `clip` holds the half-spaces of S and L.
// `hull_points` is working memory. Empty out when H is empty.
void focus_hull(const Polytope& receivers, V3 light, bool directional, double reach, const Plane* clip,
                size_t clip_count, double eps, std::vector<V3>& hull_points, Polytope& out, Polytope& scratch,
                StageTimes* times = nullptr);

// H = conv(R u {l}) n K by half-spaces alone (K = S n L, given by `k_planes`,
// inside the box with corners `box`): conv(R u {l}) is the intersection of
// the planes of R (`r_planes`, all of them R's supporting planes or
// redundant) that keep the light on their inner side, and of the planes
// through the light (or along its direction) and R's silhouette edges. The
// silhouette is the 2D convex hull, by CGAL (convex_hull_2), of R's vertices
// projected from the light along `axis` (point: every vertex lies at least a
// positive distance along it; directional: axis is the light direction).
// False when the silhouette has no area (the caller falls back to focus_hull).
// `start` (may be null): a convex body inside the box holding K's part that
// `k_planes` then need not repeat (S cut by the casters' hull, made once per
// frame), clipped in the box's place.
bool focus_by_planes(const std::vector<V3>& r_verts, V3 light, bool directional, V3 axis, const Plane* r_planes,
                     size_t r_count, const Plane* k_planes, size_t k_count, const V3 box[8], double eps,
                     std::vector<Plane>& planes, Polytope& out, Polytope& scratch, StageTimes* times = nullptr,
                     const Polytope* start = nullptr);

}  // namespace focus
}  // namespace geom
