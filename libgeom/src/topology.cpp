// Edge table and classification (see geom/topology.h for the definitions).
//
// Half-edges are bucketed by their smaller vertex (a counting sort, O(n)),
// then each small bucket is sorted by the larger vertex and face, so edges come
// out ordered by (v0, v1) and each edge's faces in triangle order: the result
// is deterministic and independent of any hash. Nothing is dropped: an edge
// keeps every face that uses it, however many.
#include "geom/topology.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "vec3.h"
#include "work_count.h"

namespace geom {
namespace {

struct HalfEdge {
  uint32_t other;  // the larger vertex
  uint32_t face;
  uint32_t third;  // the face's vertex off the edge
  uint8_t k;       // which edge of the face: (i_k, i_{k+1})
  uint8_t reversed;
};

using vec3::Vec3;
inline Vec3 sub(const Float3& a, const Float3& b) { return vec3::of(a) - vec3::of(b); }

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

}  // namespace

Topology build_topology(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                        const TopologyOptions& options) {
  Topology t;
  TopologyStats& s = t.stats;
  const size_t vn = positions.size();
  s.triangles = triangle_count;
  t.face_flags.assign(triangle_count, 0);
  t.face_edges.assign(triangle_count * 3, Topology::kNone);
  t.face_twins.assign(triangle_count * 3, Topology::kNone);
  t.face_component.assign(triangle_count, Topology::kNone);

  // Collapsed faces, and the half-edge count per smaller vertex.
  std::vector<uint32_t> start(vn + 1, 0);
  for (size_t f = 0; f < triangle_count; ++f) {
    const uint32_t* v = indices + 3 * f;
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      t.face_flags[f] |= kFaceCollapsed;
      ++s.collapsed_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) ++start[std::min(v[k], v[(k + 1) % 3]) + 1];
  }
  for (size_t i = 0; i < vn; ++i) start[i + 1] += start[i];
  // Every entry is written below: storage without the zero fill.
  const size_t half_count = start[vn];
  std::unique_ptr<HalfEdge[]> half(new HalfEdge[half_count]);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t f = 0; f < triangle_count; ++f) {
      if (t.face_flags[f] & kFaceCollapsed) continue;
      const uint32_t* v = indices + 3 * f;
      for (int k = 0; k < 3; ++k) {
        uint32_t a = v[k], b = v[(k + 1) % 3];
        uint32_t lo = std::min(a, b), hi = std::max(a, b);
        HalfEdge& h = half[fill[lo]++];  // field by field, in place
        h.other = hi, h.face = uint32_t(f), h.third = v[(k + 2) % 3], h.k = uint8_t(k), h.reversed = uint8_t(a > b);
      }
    }
  }

  // Group each bucket into edges. Duplicate faces on the way: a face with the
  // same vertex set as an earlier one shares each of its edges with it, and
  // has the same third vertex there; so within an edge's faces (in triangle
  // order) a face whose first edge this is is a duplicate when an earlier face
  // of the edge had its third vertex (`seen_at`: the last edge that saw a
  // vertex as a third vertex). Linear however many faces share the edge.
  t.edges.reserve(half_count / 2 + 16);
  t.edge_faces.reserve(half_count);
  std::vector<uint32_t> seen_at(vn, Topology::kNone);
  for (size_t v0 = 0; v0 < vn; ++v0) {
    HalfEdge* b = half.get() + start[v0];
    HalfEdge* e = half.get() + start[v0 + 1];
    if (b == e) continue;
    uint64_t compared = 0;
    if (e - b <= 16) {
      // The bucket was filled in triangle order, so a stable sort by the
      // larger vertex alone gives the (other, face) order: insertion sort
      // (the usual bucket holds about six).
      for (HalfEdge* i = b + 1; i < e; ++i) {
        const HalfEdge x = *i;
        HalfEdge* j = i;
        for (; j > b && (++compared, j[-1].other > x.other); --j) *j = j[-1];
        *j = x;
      }
    } else {
      std::sort(b, e, [&compared](const HalfEdge& x, const HalfEdge& y) {
        ++compared;
        return x.other != y.other ? x.other < y.other : x.face < y.face;  // a face meets (v0, other) once
      });
    }
    detail::count_work(compared + uint64_t(e - b));
    for (HalfEdge* run = b; run != e;) {
      HalfEdge* end = run;
      while (end != e && end->other == run->other) ++end;
      // Written in place, field by field (a whole Edge built aside and
      // copied in stalls on its partly written bytes).
      const uint32_t id = uint32_t(t.edges.size());
      const uint32_t face_count = uint32_t(end - run);
      Edge& edge = t.edges.emplace_back();
      edge.v0 = uint32_t(v0);
      edge.v1 = run->other;
      edge.first = uint32_t(t.edge_faces.size());
      edge.face_count = face_count;
      edge.kind = face_count == 1                      ? EdgeKind::Boundary
                  : face_count >= 3                    ? EdgeKind::NonManifold
                  : run[0].reversed != run[1].reversed ? EdgeKind::Manifold
                                                       : EdgeKind::Inconsistent;
      edge.shape = EdgeShape::None;
      edge.dihedral_degrees = 0.0f;
      if (face_count == 2) {
        const uint32_t s0 = 3 * run[0].face + run[0].k, s1 = 3 * run[1].face + run[1].k;
        t.face_twins[s0] = s1;
        t.face_twins[s1] = s0;
      }
      for (HalfEdge* h = run; h != end; ++h) {
        t.edge_faces.push_back(h->face << 1 | h->reversed);
        t.face_edges[3 * size_t(h->face) + h->k] = id;
        if (face_count < 2) continue;
        const uint32_t third = h->third;
        if (h->k == 0 && seen_at[third] == id) {
          t.face_flags[h->face] |= kFaceDuplicate;
          ++s.duplicate_triangles;
        }
        seen_at[third] = id;
      }
      run = end;
    }
  }
  half.reset();

  // Face normals (double precision from the float input); zero-area faces.
  std::vector<Vec3> normal(triangle_count, Vec3{0, 0, 0});
  for (size_t f = 0; f < triangle_count; ++f) {
    if (t.face_flags[f] & kFaceCollapsed) continue;
    const uint32_t* v = indices + 3 * f;
    Vec3 n = vec3::cross(sub(positions[v[1]], positions[v[0]]), sub(positions[v[2]], positions[v[0]]));
    double len = std::sqrt(vec3::dot(n, n));
    if (!(len > 0.0)) {
      t.face_flags[f] |= kFaceZeroArea;
      ++s.zero_area_triangles;
      continue;
    }
    normal[f] = {n.x / len, n.y / len, n.z / len};
  }

  // Classify edges; dihedral angles of manifold edges.
  const double coplanar_cos = std::cos(options.coplanar_degrees * M_PI / 180.0);
  for (Edge& e : t.edges) {
    switch (e.kind) {
      case EdgeKind::Boundary:
        ++s.boundary_edges;
        break;
      case EdgeKind::Manifold:
        ++s.manifold_edges;
        break;
      case EdgeKind::Inconsistent:
        ++s.inconsistent_edges;
        break;
      case EdgeKind::NonManifold:
        ++s.non_manifold_edges;
        break;
    }
    s.max_edge_faces = std::max(s.max_edge_faces, e.face_count);
    if (e.kind != EdgeKind::Manifold) continue;
    const uint32_t f0 = t.edge_faces[e.first] >> 1, f1 = t.edge_faces[e.first + 1] >> 1;
    if ((t.face_flags[f0] | t.face_flags[f1]) & kFaceZeroArea) continue;
    const Vec3 n0 = normal[f0], n1 = normal[f1];
    const double c = std::max(-1.0, std::min(1.0, vec3::dot(n0, n1)));
    // The angle between the normals, only where asked for.
    const double theta = options.dihedral_angles ? std::acos(c) * 180.0 / M_PI : 0.0;
    if (c >= coplanar_cos) {
      e.shape = EdgeShape::Coplanar;
      e.dihedral_degrees = options.dihedral_angles ? 180.0f : 0.0f;
      ++s.coplanar_edges;
      continue;
    }
    // The far vertex of f1, against f0's plane: behind = convex.
    const uint32_t* w = indices + 3 * size_t(f1);
    uint32_t far = w[0] != e.v0 && w[0] != e.v1 ? w[0] : w[1] != e.v0 && w[1] != e.v1 ? w[1] : w[2];
    const double side = vec3::dot(n0, sub(positions[far], positions[e.v0]));
    if (side < 0.0) {
      e.shape = EdgeShape::Convex;
      e.dihedral_degrees = options.dihedral_angles ? float(180.0 - theta) : 0.0f;
      ++s.convex_edges;
    } else {
      e.shape = EdgeShape::Concave;
      e.dihedral_degrees = options.dihedral_angles ? float(180.0 + theta) : 0.0f;
      ++s.concave_edges;
    }
  }

  // Used vertices and components (union-find over shared vertices).
  std::vector<uint32_t> parent(vn);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<uint8_t> used(vn, 0);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (t.face_flags[f] & kFaceCollapsed) continue;
    const uint32_t* v = indices + 3 * f;
    used[v[0]] = used[v[1]] = used[v[2]] = 1;
    uint32_t r0 = find_root(parent, v[0]);  // a set's root is its least vertex
    for (int k = 1; k < 3; ++k) {
      const uint32_t r1 = find_root(parent, v[k]);
      if (r0 != r1) parent[std::max(r0, r1)] = std::min(r0, r1), r0 = std::min(r0, r1);
    }
  }
  for (size_t i = 0; i < vn; ++i) s.vertices += used[i];
  std::vector<uint32_t> label(vn, Topology::kNone);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (t.face_flags[f] & kFaceCollapsed) continue;
    uint32_t r = find_root(parent, indices[3 * f]);
    if (label[r] == Topology::kNone) label[r] = uint32_t(s.components++);
    t.face_component[f] = label[r];
  }
  std::vector<uint8_t> open(s.components, 0);
  for (const Edge& e : t.edges)
    if (e.kind == EdgeKind::Boundary || e.kind == EdgeKind::NonManifold)
      open[t.face_component[t.edge_faces[e.first] >> 1]] = 1;
  for (uint8_t o : open) s.closed_components += !o;

  s.edges = t.edges.size();
  s.closed = s.boundary_edges == 0 && s.non_manifold_edges == 0;
  s.euler_characteristic = int64_t(s.vertices) - int64_t(s.edges) + int64_t(triangle_count - s.collapsed_triangles);
  return t;
}

}  // namespace geom
