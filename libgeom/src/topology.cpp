// Edge table and classification (see geom/topology.h for the definitions).
//
// Half-edges are bucketed by their smaller vertex (a counting sort, O(n)),
// then each small bucket is sorted by the larger vertex and face, so edges come
// out ordered by (v0, v1) and each edge's faces in triangle order: the result
// is deterministic and independent of any hash. Nothing is dropped: an edge
// keeps every face that uses it, however many.
//
// A half-edge is one 8-byte key, (larger vertex << 32) | slot, slot = 3 * face
// + k: sorting the keys sorts by (v1, face), and the rest (the direction, the
// face's third vertex) is read back from the face's indices. Each edge is
// classified as it is made, from the faces' cross products (computed once, in
// the first pass, not normalized): the coplanar test compares dot(n0, n1)^2
// against cos^2 |n0|^2 |n1|^2 and the side test takes the sign of the
// unnormalized dot; where either is within a margin far wider than both
// roundings, or a magnitude is out of the safe range, the normalized formulas
// decide, so every shape is the one they give. Components: a union-find over
// the edges as they are made, roots the least vertex.
#include "geom/topology.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "geom/precondition.h"
#include "vec3.h"
#include "work_count.h"

namespace geom {
namespace {

constexpr uint32_t kNone = Topology::kNone;

using vec3::Vec3;
inline Vec3 sub(const Float3& a, const Float3& b) { return vec3::of(a) - vec3::of(b); }

uint32_t find_root(uint32_t* parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

// A face's cross product (the normal before it is normalized) and its squared length.
struct FaceNormal {
  Vec3 n;
  double nn;
};

// The normalized formulas: normal / |normal|, the cosine clamped.
inline Vec3 unit(const FaceNormal& f) {
  const double len = std::sqrt(f.nn);
  return {f.n.x / len, f.n.y / len, f.n.z / len};
}

// Collapsed and zero-area faces, the cross products (`normal`, read only
// where written), and the half-edge count per smaller vertex (at lo + 2:
// after the scatter of bucket_half_edges, bucket v is [start[v], start[v + 1])).
void face_pass(PositionSpan positions, const uint32_t* indices, size_t triangle_count, Topology& t,
               std::vector<uint32_t>& start, Vec3* normal) {
  TopologyStats& s = t.stats;
  for (size_t f = 0; f < triangle_count; ++f) {
    const uint32_t* v = indices + 3 * f;
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      t.face_flags[f] = kFaceCollapsed;
      ++s.collapsed_triangles;
      continue;
    }
    ++start[std::min(v[0], v[1]) + 2];
    ++start[std::min(v[1], v[2]) + 2];
    ++start[std::min(v[2], v[0]) + 2];
    const Vec3 n = vec3::cross(sub(positions[v[1]], positions[v[0]]), sub(positions[v[2]], positions[v[0]]));
    const double nn = vec3::dot(n, n);
    normal[f] = n;
    if (!(nn > 0.0)) {  // the length sqrt(nn) is not > 0
      t.face_flags[f] = kFaceZeroArea;
      ++s.zero_area_triangles;
    }
  }
}

// The half-edges of the non-collapsed faces as 8-byte keys, (larger vertex
// << 32) | slot, bucketed by the smaller vertex (a counting sort over the
// counts of face_pass, which become the buckets' starts).
std::unique_ptr<uint64_t[]> bucket_half_edges(const uint32_t* indices, size_t triangle_count,
                                              const std::vector<uint8_t>& face_flags, std::vector<uint32_t>& start,
                                              size_t vn) {
  for (size_t i = 2; i <= vn + 1; ++i) start[i] += start[i - 1];
  const size_t half_count = start[vn + 1];
  // Every key is written below: storage without the zero fill.
  std::unique_ptr<uint64_t[]> keys(new uint64_t[half_count]);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (face_flags[f] & kFaceCollapsed) continue;
    const uint32_t* v = indices + 3 * f;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[k == 2 ? 0 : k + 1];
      const uint32_t lo = std::min(a, b), hi = std::max(a, b);
      keys[start[lo + 1]++] = uint64_t(hi) << 32 | uint32_t(3 * f + k);
    }
  }
  return keys;
}

// The shape of a manifold edge: coplanar, convex or concave, and its dihedral
// angle where asked for, counted by shape.
struct EdgeClassifier {
  EdgeClassifier(PositionSpan positions_, const Vec3* normal_, const TopologyOptions& options)
      : positions(positions_),
        normal(normal_),
        dihedral_angles(options.dihedral_angles),
        coplanar_cos(std::cos(options.coplanar_degrees * M_PI / 180.0)),
        coplanar_cos2(coplanar_cos * coplanar_cos),
        // The unnormalized tests hold where cos is well above 0 and the
        // magnitudes are far from overflow and underflow; each rounds to within
        // ~1e-15 of the exact value, as do the normalized formulas, and a margin
        // of 1e-12 sends anything closer to the threshold to the normalized formulas.
        fast_tests(!options.dihedral_angles && coplanar_cos > 1e-3) {}

  // The shape of a manifold edge (v0, v1) between faces f0 < f1, `far` f1's
  // vertex off it; None when either face is zero-area (its nn is not > 0).
  // The fast tests decide without a branch on the answer (coplanar, convex
  // and concave come in no order a predictor learns).
  void operator()(Edge& edge, uint32_t f0, uint32_t f1, uint32_t far) {
    const FaceNormal a{normal[f0], vec3::dot(normal[f0], normal[f0])};  // as the face pass computed nn
    const FaceNormal b{normal[f1], vec3::dot(normal[f1], normal[f1])};
    if (!(a.nn > 0.0) || !(b.nn > 0.0)) return;
    const Vec3 d = sub(positions[far], positions[edge.v0]);
    if (fast_tests && fast(edge, a, b, d)) return;
    const Vec3 n0 = unit(a), n1 = unit(b);
    const double c = std::max(-1.0, std::min(1.0, vec3::dot(n0, n1)));
    // The angle between the normals, only where asked for.
    const double theta = dihedral_angles ? std::acos(c) * 180.0 / M_PI : 0.0;
    if (c >= coplanar_cos) {
      edge.shape = EdgeShape::Coplanar;
      edge.dihedral_degrees = dihedral_angles ? 180.0f : 0.0f;
    } else if (vec3::dot(n0, d) < 0.0) {  // the far vertex of f1, against f0's plane: behind = convex
      edge.shape = EdgeShape::Convex;
      edge.dihedral_degrees = dihedral_angles ? float(180.0 - theta) : 0.0f;
    } else {
      edge.shape = EdgeShape::Concave;
      edge.dihedral_degrees = dihedral_angles ? float(180.0 + theta) : 0.0f;
    }
    ++shape_count[int(edge.shape)];
  }

  // The unnormalized tests: false where they cannot decide within the margin.
  bool fast(Edge& edge, const FaceNormal& a, const FaceNormal& b, const Vec3& d) {
    constexpr double kMargin = 1e-12, kTiny = 1e-280, kHuge = 1e280;
    const double p = a.nn * b.nn;
    const double dn = vec3::dot(a.n, b.n);
    const double g = dn * std::fabs(dn) - coplanar_cos2 * p;  // sign of cos - coplanar_cos
    const double side = vec3::dot(a.n, d);
    const double bound = std::fabs(a.n.x * d.x) + std::fabs(a.n.y * d.y) + std::fabs(a.n.z * d.z);
    const bool coplanar = g > kMargin * p;
    const bool decided = (p > kTiny) & (p < kHuge) &
                         (coplanar | ((g < -kMargin * p) & (bound > kTiny) & (std::fabs(side) > kMargin * bound)));
    if (!decided) return false;
    // Coplanar, else convex behind f0's plane, else concave: a table
    // lookup (the compiler turns arithmetic on the two tests into a branch).
    static constexpr uint8_t kShape[4] = {uint8_t(EdgeShape::Concave), uint8_t(EdgeShape::Coplanar),
                                          uint8_t(EdgeShape::Convex), uint8_t(EdgeShape::Coplanar)};
    const int shape = kShape[int(coplanar) | int(side < 0.0) << 1];
    edge.shape = EdgeShape(shape);
    ++shape_count[shape];
    return true;
  }

  PositionSpan positions;
  const Vec3* normal;
  bool dihedral_angles;
  double coplanar_cos, coplanar_cos2;
  bool fast_tests;
  uint64_t shape_count[4] = {0, 0, 0, 0};  // by EdgeShape
};

// Sorts one bucket of keys (unique: a face meets (v0, v1) once) and counts the work.
void sort_bucket(uint64_t* b, uint64_t* e) {
  uint64_t compared = 0;
  if (e - b <= 16) {
    // Insertion sort (the usual bucket holds about six).
    for (uint64_t* i = b + 1; i < e; ++i) {
      const uint64_t x = *i;
      uint64_t* j = i;
      for (; j > b && (++compared, j[-1] > x); --j) *j = j[-1];
      *j = x;
    }
  } else {
    std::sort(b, e, [&compared](uint64_t x, uint64_t y) {
      ++compared;
      return x < y;
    });
  }
  detail::count_work(compared + uint64_t(e - b));
}

// What grouping the half-edges into edges works on. Duplicate faces on the
// way: a face with the same vertex set as an earlier one shares each of its
// edges with it, and has the same third vertex there; so within an edge's
// faces (in triangle order) a face whose first edge this is is a duplicate
// when an earlier face of the edge had its third vertex (`seen_at`: the last
// edge that saw a vertex as a third vertex). Linear however many faces share
// the edge. Components on the way: parent[v] is kNone until v is on an edge,
// then at most v (a root is its set's least vertex).
struct EdgeGrouping {
  EdgeGrouping(Topology& t_, const uint32_t* indices_, const uint64_t* keys_, size_t vn, EdgeClassifier& classify_)
      : t(t_),
        indices(indices_),
        keys(keys_),
        edge_faces(t_.edge_faces.data()),
        classify(classify_),
        seen_at(vn, kNone),
        parent(vn, kNone),
        open(vn, 0) {}
  Topology& t;
  const uint32_t* indices;
  const uint64_t* keys;
  uint32_t* edge_faces;  // in key order: a half-edge's entry sits where its key does
  EdgeClassifier& classify;
  std::vector<uint32_t> seen_at;
  std::vector<uint32_t> parent;
  std::vector<uint8_t> open;  // v0 of a boundary or non-manifold edge
};

// Joins v1's component with v0's, whose root is r0 (kept the smaller root).
inline void join(std::vector<uint32_t>& parent, uint32_t& r0, uint32_t v1) {
  if (parent[v1] == kNone) {
    parent[v1] = r0;
  } else {
    const uint32_t r1 = find_root(parent.data(), v1);
    if (r1 < r0)
      parent[r0] = r1, r0 = r1;
    else if (r1 > r0)
      parent[r1] = r0;
  }
}

// One edge (v0, v1) from its run of keys [run, end): its faces, kind and shape.
void add_edge(EdgeGrouping& g, uint32_t v0, uint32_t& r0, const uint64_t* run, const uint64_t* end) {
  Topology& t = g.t;
  TopologyStats& s = t.stats;
  const uint32_t* indices = g.indices;
  const uint32_t v1 = uint32_t(*run >> 32);
  // Written in place, field by field (a whole Edge built aside and copied in
  // stalls on its partly written bytes).
  const uint32_t id = uint32_t(t.edges.size());
  const uint32_t face_count = uint32_t(end - run);
  Edge& edge = t.edges.emplace_back();
  edge.v0 = v0;
  edge.v1 = v1;
  edge.first = uint32_t(run - g.keys);
  edge.face_count = face_count;
  edge.shape = EdgeShape::None;
  edge.dihedral_degrees = 0.0f;
  join(g.parent, r0, v1);
  if (face_count == 1) {
    const uint32_t sl = uint32_t(*run);
    edge.kind = EdgeKind::Boundary;
    ++s.boundary_edges;
    g.open[v0] = 1;
    g.edge_faces[edge.first] = (sl / 3) << 1 | uint32_t(indices[sl] != v0);
    t.face_edges[sl] = id;
    return;
  }
  if (face_count >= 3) {
    edge.kind = EdgeKind::NonManifold;
    ++s.non_manifold_edges;
    g.open[v0] = 1;
    s.max_edge_faces = std::max(s.max_edge_faces, face_count);
  }
  for (const uint64_t* h = run; h != end; ++h) {
    const uint32_t sl = uint32_t(*h), f = sl / 3, k = sl - 3 * f;
    g.edge_faces[h - g.keys] = f << 1 | uint32_t(indices[sl] != v0);
    t.face_edges[sl] = id;
    const uint32_t third = indices[sl + 2 - 3 * uint32_t(k != 0)];  // the face's corner k + 2
    // Without a branch on k (a third of the half-edges, in no order).
    const uint32_t duplicate = uint32_t(g.seen_at[third] == id) & uint32_t(k == 0);
    t.face_flags[f] |= uint8_t(duplicate * kFaceDuplicate);
    s.duplicate_triangles += duplicate;
    g.seen_at[third] = id;
  }
  if (face_count != 2) return;
  const uint32_t s0 = uint32_t(run[0]), s1 = uint32_t(run[1]);
  t.face_twins[s0] = s1;
  t.face_twins[s1] = s0;
  const uint32_t* pair = g.edge_faces + edge.first;
  if ((pair[0] ^ pair[1]) & 1) {
    edge.kind = EdgeKind::Manifold;
    ++s.manifold_edges;
    const uint32_t f1 = pair[1] >> 1;
    g.classify(edge, pair[0] >> 1, f1, indices[s1 + 2 - 3 * uint32_t(s1 != 3 * f1)]);
  } else {
    edge.kind = EdgeKind::Inconsistent;
    ++s.inconsistent_edges;
  }
}

// Every bucket sorted and grouped into edges, in (v0, v1) order.
void group_edges(EdgeGrouping& g, uint64_t* keys, const std::vector<uint32_t>& start, size_t vn) {
  for (size_t v0 = 0; v0 < vn; ++v0) {
    uint64_t* b = keys + start[v0];
    uint64_t* e = keys + start[v0 + 1];
    if (b == e) continue;
    sort_bucket(b, e);
    if (g.parent[v0] == kNone) g.parent[v0] = uint32_t(v0);
    uint32_t r0 = find_root(g.parent.data(), uint32_t(v0));
    for (const uint64_t* run = b; run != e;) {
      const uint32_t v1 = uint32_t(*run >> 32);
      const uint64_t* end = run + 1;
      while (end != e && uint32_t(*end >> 32) == v1) ++end;
      add_edge(g, uint32_t(v0), r0, run, end);
      run = end;
    }
  }
}

// Components: parent[v] <= v, so one pass in vertex order takes each used
// vertex to its root; labels in the order of the first face of each. A
// component is open when an edge of it is boundary or non-manifold (its v0
// is marked). `label` is working memory of vn entries.
void label_components(Topology& t, const uint32_t* indices, size_t triangle_count, std::vector<uint32_t>& parent,
                      const std::vector<uint8_t>& open, std::vector<uint32_t>& label) {
  TopologyStats& s = t.stats;
  const size_t vn = parent.size();
  for (size_t v = 0; v < vn; ++v)
    if (parent[v] != kNone) parent[v] = parent[parent[v]], ++s.vertices;
  std::fill(label.begin(), label.end(), kNone);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (t.face_flags[f] & kFaceCollapsed) {
      t.face_component[f] = kNone;
      continue;
    }
    const uint32_t r = parent[indices[3 * f]];
    if (label[r] == kNone) label[r] = uint32_t(s.components++);
    t.face_component[f] = label[r];
  }
  std::vector<uint8_t> open_component(s.components, 0);
  for (size_t v = 0; v < vn; ++v)
    if (open[v]) open_component[label[parent[v]]] = 1;
  for (uint8_t o : open_component) s.closed_components += !o;
}

}  // namespace

Topology build_topology(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                        const TopologyOptions& options) {
  GEOM_PRECONDITION(triangle_count <= (size_t(0xffffffffu) - 1) / 3,
                    std::to_string(triangle_count) + " triangles, expected at most " +
                        std::to_string((size_t(0xffffffffu) - 1) / 3) + " (32-bit face slots)");
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  Topology t;
  TopologyStats& s = t.stats;
  const size_t vn = positions.size();
  s.triangles = triangle_count;
  t.face_flags.assign(triangle_count, 0);
  t.face_edges.assign(triangle_count * 3, kNone);
  t.face_twins.assign(triangle_count * 3, kNone);
  t.face_component.resize(triangle_count);

  std::vector<uint32_t> start(vn + 2, 0);
  // The cross product alone (24 bytes a face, not normalized): its squared
  // length is recomputed where read rather than stored beside it.
  std::unique_ptr<Vec3[]> normal(new Vec3[triangle_count]);
  face_pass(positions, indices, triangle_count, t, start, normal.get());
  std::unique_ptr<uint64_t[]> keys = bucket_half_edges(indices, triangle_count, t.face_flags, start, vn);
  const size_t half_count = start[vn + 1];

  EdgeClassifier classify(positions, normal.get(), options);
  t.edges.reserve(half_count / 2 + 16);
  t.edge_faces.resize(half_count);
  EdgeGrouping g(t, indices, keys.get(), vn, classify);
  group_edges(g, keys.get(), start, vn);
  keys.reset();
  normal.reset();
  s.coplanar_edges = classify.shape_count[int(EdgeShape::Coplanar)];
  s.convex_edges = classify.shape_count[int(EdgeShape::Convex)];
  s.concave_edges = classify.shape_count[int(EdgeShape::Concave)];
  if (s.manifold_edges + s.inconsistent_edges) s.max_edge_faces = std::max(s.max_edge_faces, 2u);
  if (s.boundary_edges) s.max_edge_faces = std::max(s.max_edge_faces, 1u);

  label_components(t, indices, triangle_count, g.parent, g.open, g.seen_at);
  s.edges = t.edges.size();
  s.closed = s.boundary_edges == 0 && s.non_manifold_edges == 0;
  s.euler_characteristic = int64_t(s.vertices) - int64_t(s.edges) + int64_t(triangle_count - s.collapsed_triangles);
  return t;
}

}  // namespace geom
