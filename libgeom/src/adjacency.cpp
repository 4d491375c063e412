// Triangles-with-adjacency index buffer (see geom/adjacency.h), for the
// geometry-shader silhouette test of Kenzel 2013 (Edge Distance Shadow
// Mapping), Sect. 3.2.1.
//
// From the edge table (geom/topology.h): each edge lists its faces in triangle
// order with the direction each runs it, so one pass over an edge's faces
// finds the first two faces of each direction, and every face of the edge
// gets its neighbour from those four: linear however many faces share an edge
// or a vertex, deterministic, and the same table the other stages use. With
// the topology's twins (nearly every edge has two faces) one pass over the
// face slots does it: a twin gives the neighbour, a slot without one leads to
// its edge only when that has three or more faces.
//
// Without a table: directed half-edges bucketed by their start vertex (a
// counting sort), each bucket sorted by (end vertex, triangle), so "the first
// triangle traversing b -> a" is a binary search in b's bucket: O(n log n)
// whatever the valences.
#include "geom/adjacency.h"

#include <algorithm>
#include <new>
#include <vector>

#include "geom/precondition.h"
#include "work_count.h"

namespace geom {
namespace {

inline bool collapsed(const uint32_t* v) { return v[0] == v[1] || v[1] == v[2] || v[2] == v[0]; }

// The vertex of triangle `v` that is neither a nor b.
inline uint32_t third_of(const uint32_t* v, uint32_t a, uint32_t b) {
  return v[0] != a && v[0] != b ? v[0] : v[1] != a && v[1] != b ? v[1] : v[2];
}

// Every triangle's own corners, and its own opposite vertex for each edge (the
// answer for boundary edges and collapsed triangles).
void write_own(uint32_t* out, const uint32_t* indices, size_t triangle_count) {
  for (size_t t = 0; t < triangle_count; ++t) {
    const uint32_t* v = indices + 3 * t;
    uint32_t* o = out + 6 * t;
    o[0] = v[0], o[1] = v[2], o[2] = v[1], o[3] = v[0], o[4] = v[2], o[5] = v[1];
  }
}

// Where the slot of edge `id` of triangle t is in the output.
inline size_t slot_of(const Topology& topology, uint32_t t, uint32_t id) {
  const uint32_t* fe = topology.face_edges.data() + 3 * size_t(t);
  return 6 * size_t(t) + 2 * (fe[0] == id ? 0 : fe[1] == id ? 1 : 2) + 1;
}

// The neighbours across an edge of three or more faces: for each face, the
// first face the other way, else the first other one this way.
void non_manifold(uint32_t* out, const uint32_t* indices, const Topology& topology, uint32_t id) {
  const uint32_t kNone = Topology::kNone;
  const Edge& e = topology.edges[id];
  detail::count_work(2 * uint64_t(e.face_count));
  const uint32_t* faces = topology.edge_faces.data() + e.first;
  uint32_t first[2][2] = {{kNone, kNone}, {kNone, kNone}};  // [direction][0: first, 1: second]
  for (uint32_t i = 0; i < e.face_count; ++i) {
    uint32_t* slot = first[faces[i] & 1];
    if (slot[0] == kNone)
      slot[0] = faces[i] >> 1;
    else if (slot[1] == kNone)
      slot[1] = faces[i] >> 1;
  }
  for (uint32_t i = 0; i < e.face_count; ++i) {
    const uint32_t t = faces[i] >> 1, d = faces[i] & 1;
    uint32_t n = first[d ^ 1][0];
    if (n == kNone) n = first[d][0] != t ? first[d][0] : first[d][1];
    if (n == kNone) continue;
    out[slot_of(topology, t, id)] = third_of(indices + 3 * size_t(n), e.v0, e.v1);
  }
}

}  // namespace

bool build_adjacency(uint32_t* out, const uint32_t* indices, size_t triangle_count, const Topology& topology) {
  GEOM_PRECONDITION(triangle_count == 0 || out, "null output for " + std::to_string(triangle_count) + " triangles");
  GEOM_PRECONDITION(topology.face_edges.size() == 3 * triangle_count,
                    std::to_string(topology.face_edges.size()) + " face edges in the topology, expected " +
                        std::to_string(3 * triangle_count) + " (build_topology of these triangles, not released)");
  const uint32_t kNone = Topology::kNone;
  // An edge of two faces: each face's neighbour is the other, either way
  // round; its slot of the edge is the twin, the vertex off it the next but one.
  // A slot without a twin is on an edge of one face (its own vertex stays) or
  // of three or more, handled after the pass (it writes other faces' slots),
  // once, from the slot of the edge's first face: no walk over the edge
  // table, and each triangle's six indices written once.
  if (topology.face_twins.size() == 3 * triangle_count && topology.face_edges.size() == 3 * triangle_count) {
    uint64_t paired = 0;
    std::vector<uint32_t> crowded;  // edges of three or more faces
    const uint32_t* twins = topology.face_twins.data();
    for (size_t t = 0; t < triangle_count; ++t) {
      const uint32_t* v = indices + 3 * t;
      uint32_t* o = out + 6 * t;
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t tw = twins[3 * t + k];
        o[2 * k] = v[k];
        if (tw != kNone) {
          const uint32_t j = tw % 3;
          o[2 * k + 1] = indices[tw - j + (j == 0 ? 2 : j - 1)];
          ++paired;
          continue;
        }
        o[2 * k + 1] = v[k == 0 ? 2 : k - 1];  // its own opposite vertex
        const uint32_t id = topology.face_edges[3 * t + k];
        if (id == kNone) continue;
        const Edge& e = topology.edges[id];
        if (e.face_count > 2 && topology.edge_faces[e.first] >> 1 == t) crowded.push_back(id);
      }
    }
    for (uint32_t id : crowded) non_manifold(out, indices, topology, id);
    detail::count_work(2 * paired);  // 2 per face of a two-faced edge, as the walk below counts
    return true;
  }
  write_own(out, indices, triangle_count);
  uint64_t paired = 0;
  for (uint32_t id = 0; id < topology.edges.size(); ++id) {
    const Edge& e = topology.edges[id];
    if (e.face_count < 2) continue;
    if (e.face_count > 2) {
      non_manifold(out, indices, topology, id);
      continue;
    }
    paired += 4;
    // The usual edge: each face's neighbour is the other, either way round.
    const uint32_t* faces = topology.edge_faces.data() + e.first;
    const uint32_t t0 = faces[0] >> 1, t1 = faces[1] >> 1;
    out[slot_of(topology, t0, id)] = third_of(indices + 3 * size_t(t1), e.v0, e.v1);
    out[slot_of(topology, t1, id)] = third_of(indices + 3 * size_t(t0), e.v0, e.v1);
  }
  detail::count_work(paired);
  return true;
}

bool build_adjacency(uint32_t* out, const uint32_t* indices, size_t triangle_count, size_t vertex_count) {
  GEOM_PRECONDITION(triangle_count == 0 || out, "null output for " + std::to_string(triangle_count) + " triangles");
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, vertex_count);
  struct Half {
    uint32_t to, third, tri;
  };
  try {
    std::vector<uint32_t> start(vertex_count + 1, 0);
    for (size_t t = 0; t < triangle_count; ++t) {
      const uint32_t* v = indices + 3 * t;
      if (collapsed(v)) continue;
      ++start[v[0] + 1];
      ++start[v[1] + 1];
      ++start[v[2] + 1];
    }
    for (size_t i = 0; i < vertex_count; ++i) start[i + 1] += start[i];
    std::vector<Half> half(start[vertex_count]);
    {
      std::vector<uint32_t> fill(start.begin(), start.end() - 1);
      for (size_t t = 0; t < triangle_count; ++t) {
        const uint32_t* v = indices + 3 * t;
        if (collapsed(v)) continue;
        half[fill[v[0]]++] = {v[1], v[2], uint32_t(t)};
        half[fill[v[1]]++] = {v[2], v[0], uint32_t(t)};
        half[fill[v[2]]++] = {v[0], v[1], uint32_t(t)};
      }
    }
    auto by_end = [](const Half& x, const Half& y) { return x.to != y.to ? x.to < y.to : x.tri < y.tri; };
    uint64_t compared = 0;
    auto counted = [&compared, &by_end](const Half& x, const Half& y) { return ++compared, by_end(x, y); };
    for (size_t i = 0; i < vertex_count; ++i)
      if (start[i + 1] - start[i] > 1) std::sort(half.begin() + start[i], half.begin() + start[i + 1], counted);
    detail::count_work(compared + half.size());
    // The first half-edge from `from` to `to` in triangle order, other than triangle `not_tri`.
    auto find = [&](uint32_t from, uint32_t to, uint32_t not_tri) -> const Half* {
      const Half* b = half.data() + start[from];
      const Half* e = half.data() + start[from + 1];
      const Half* h = std::lower_bound(b, e, Half{to, 0, 0}, by_end);
      if (h != e && h->to == to && h->tri == not_tri) ++h;
      return h != e && h->to == to ? h : nullptr;
    };
    write_own(out, indices, triangle_count);
    for (size_t t = 0; t < triangle_count; ++t) {
      const uint32_t* v = indices + 3 * t;
      if (collapsed(v)) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = v[k], b = v[(k + 1) % 3];
        const Half* h = find(b, a, uint32_t(-1));
        if (!h) h = find(a, b, uint32_t(t));
        if (h) out[6 * t + 2 * k + 1] = h->third;
      }
    }
  } catch (const std::bad_alloc&) {
    return false;
  }
  return true;
}

}  // namespace geom
