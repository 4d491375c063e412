// Topology (geom/topology.h) and the half-edge view: tiny meshes drawn in comments, and a brute-force law on
// random soups (every count of the report equals an independent count).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "geom/halfedge.h"
#include "openmesh_halfedge.h"
#include "geom/topology.h"
#include "geom/weld.h"

using namespace geom;

namespace {

Topology topo(const std::vector<float>& p, const std::vector<uint32_t>& idx) {
  return build_topology(positions_of(p.data(), p.size() / 3), idx.data(), idx.size() / 3);
}

// A brute-force count of the report's definitions, written independently.
TopologyStats brute_force(const std::vector<float>& p, const std::vector<uint32_t>& idx) {
  TopologyStats s;
  s.triangles = idx.size() / 3;
  std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, bool>>> edges;
  std::set<uint32_t> verts;
  std::set<std::vector<uint32_t>> seen;
  for (size_t f = 0; f < idx.size() / 3; ++f) {
    uint32_t a = idx[3 * f], b = idx[3 * f + 1], c = idx[3 * f + 2];
    if (a == b || b == c || a == c) {
      ++s.collapsed_triangles;
      continue;
    }
    std::vector<uint32_t> key{a, b, c};
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) ++s.duplicate_triangles;
    verts.insert({a, b, c});
    uint32_t v[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      uint32_t x = v[k], y = v[(k + 1) % 3];
      edges[{std::min(x, y), std::max(x, y)}].push_back({uint32_t(f), x > y});
    }
  }
  s.vertices = verts.size();
  s.edges = edges.size();
  for (auto& [k, fs] : edges) {
    if (fs.size() == 1)
      ++s.boundary_edges;
    else if (fs.size() == 2)
      (fs[0].second != fs[1].second ? s.manifold_edges : s.inconsistent_edges)++;
    else
      ++s.non_manifold_edges;
  }
  // components by flood fill over shared vertices
  std::map<uint32_t, std::vector<uint32_t>> faces_of;
  for (size_t f = 0; f < idx.size() / 3; ++f) {
    uint32_t a = idx[3 * f], b = idx[3 * f + 1], c = idx[3 * f + 2];
    if (a == b || b == c || a == c) continue;
    for (uint32_t v : {a, b, c}) faces_of[v].push_back(uint32_t(f));
  }
  std::set<uint32_t> done;
  for (auto& [v, fs] : faces_of) {
    if (done.count(v)) continue;
    ++s.components;
    std::vector<uint32_t> stack{v};
    done.insert(v);
    while (!stack.empty()) {
      uint32_t u = stack.back();
      stack.pop_back();
      for (uint32_t f : faces_of[u])
        for (int k = 0; k < 3; ++k)
          if (done.insert(idx[3 * f + k]).second) stack.push_back(idx[3 * f + k]);
    }
  }
  s.closed = s.boundary_edges == 0 && s.non_manifold_edges == 0;
  s.euler_characteristic = int64_t(s.vertices) - int64_t(s.edges) + int64_t(s.triangles - s.collapsed_triangles);
  return s;
}

void expect_same(const TopologyStats& a, const TopologyStats& b) {
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.boundary_edges, b.boundary_edges);
  EXPECT_EQ(a.manifold_edges, b.manifold_edges);
  EXPECT_EQ(a.inconsistent_edges, b.inconsistent_edges);
  EXPECT_EQ(a.non_manifold_edges, b.non_manifold_edges);
  EXPECT_EQ(a.collapsed_triangles, b.collapsed_triangles);
  EXPECT_EQ(a.duplicate_triangles, b.duplicate_triangles);
  EXPECT_EQ(a.components, b.components);
  EXPECT_EQ(a.closed, b.closed);
  EXPECT_EQ(a.euler_characteristic, b.euler_characteristic);
}

// Tetrahedron, outward winding.
//        3
//       /|\       0 = (0,0,0), 1 = (1,0,0), 2 = (0,1,0), 3 = (0,0,1)
//      / | \      faces 021 (z=0, normal -z), 013, 123, 032
//     0--+--1
//      \ | /
//        2
const std::vector<float> kTetP = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const std::vector<uint32_t> kTetI = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};

}  // namespace

TEST(Topology, EmptyMesh) {
  Topology t = topo({}, {});
  EXPECT_EQ(t.stats.triangles, 0u);
  EXPECT_EQ(t.stats.edges, 0u);
  EXPECT_EQ(t.stats.components, 0u);
  EXPECT_TRUE(t.stats.closed);
  EXPECT_EQ(t.stats.euler_characteristic, 0);
}

TEST(Topology, ClosedTetrahedronIsConvexEverywhere) {
  Topology t = topo(kTetP, kTetI);
  EXPECT_EQ(t.stats.edges, 6u);
  EXPECT_EQ(t.stats.manifold_edges, 6u);
  EXPECT_EQ(t.stats.convex_edges, 6u);
  EXPECT_TRUE(t.stats.closed);
  EXPECT_EQ(t.stats.closed_components, 1u);
  EXPECT_EQ(t.stats.euler_characteristic, 2);
  for (const Edge& e : t.edges) {
    EXPECT_LT(e.v0, e.v1);
    EXPECT_GT(e.dihedral_degrees, 0.0f);
    EXPECT_LT(e.dihedral_degrees, 180.0f);
  }
  // Edge (0,1) between the z=0 face and the y=0 face: a right angle.
  auto it = std::find_if(t.edges.begin(), t.edges.end(), [](const Edge& e) { return e.v0 == 0 && e.v1 == 1; });
  ASSERT_NE(it, t.edges.end());
  EXPECT_NEAR(it->dihedral_degrees, 90.0f, 1e-4f);
}

// Two triangles folded up: a valley (concave) and a flat pair (coplanar).
//   3-----2
//   | \   |     0 (0,0,0) 1 (1,0,0) 2 (1,1,h) 3 (0,1,0); faces 013, 123, normal +z
//   |   \ |
//   0-----1
TEST(Topology, ConcaveAndCoplanar) {
  std::vector<uint32_t> idx = {0, 1, 3, 1, 2, 3};
  Topology flat = topo({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, idx);
  EXPECT_EQ(flat.stats.coplanar_edges, 1u);
  EXPECT_EQ(flat.stats.boundary_edges, 4u);
  Topology valley = topo({0, 0, 0, 1, 0, 0, 1, 1, 1, 0, 1, 0}, idx);  // 2 lifted: a concave crease at 1-3
  EXPECT_EQ(valley.stats.concave_edges, 1u);
  Topology ridge = topo({0, 0, 0, 1, 0, 0, 1, 1, -1, 0, 1, 0}, idx);
  EXPECT_EQ(ridge.stats.convex_edges, 1u);
  for (const Edge& e : valley.edges)
    if (e.kind == EdgeKind::Manifold) EXPECT_GT(e.dihedral_degrees, 180.0f);
}

// Three triangles on one edge (a fin), one inconsistent pair, one collapsed,
// one zero-area and one duplicate face.
TEST(Topology, NonManifoldAndDegenerateFaces) {
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 2, 0, 0};
  //  edge 0-1 shared by 012, 103 (opposite), 014 -> non-manifold with 3 faces
  std::vector<uint32_t> idx = {0, 1, 2, 1, 0, 3, 0, 1, 4, 2, 2, 3, 0, 1, 5, 0, 1, 2};
  Topology t = topo(p, idx);
  EXPECT_EQ(t.stats.collapsed_triangles, 1u);
  EXPECT_EQ(t.stats.zero_area_triangles, 1u);  // 0,1,5 are collinear
  EXPECT_EQ(t.stats.duplicate_triangles, 1u);
  EXPECT_EQ(t.stats.non_manifold_edges, 1u);
  EXPECT_EQ(t.stats.max_edge_faces, 5u);
  EXPECT_FALSE(t.stats.closed);
  EXPECT_EQ(t.face_edges[9], Topology::kNone);
  expect_same(t.stats, brute_force(p, idx));
  // Inconsistent: two faces traversing 0->1.
  Topology inc = topo(p, {0, 1, 2, 0, 1, 3});
  EXPECT_EQ(inc.stats.inconsistent_edges, 1u);
}

TEST(Topology, RandomSoupsMatchBruteForce) {
  std::mt19937 rng(12345);
  for (int iter = 0; iter < 300; ++iter) {
    int nv = 3 + int(rng() % 30), nt = int(rng() % 60);
    std::vector<float> p(3 * nv);
    for (float& x : p) x = float(rng() % 5);  // few distinct values: collinear and duplicate points happen
    std::vector<uint32_t> idx(3 * nt);
    for (uint32_t& i : idx) i = rng() % nv;
    WeldResult w = weld(positions_of(p.data(), nv), idx.data(), idx.size());
    Topology t = build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(), nt);
    expect_same(t.stats, brute_force(w.positions, w.indices));
    // Every non-collapsed face has three edges, each listing the face.
    for (int f = 0; f < nt; ++f) {
      if (t.face_flags[f] & kFaceCollapsed) continue;
      for (int k = 0; k < 3; ++k) {
        const Edge& e = t.edges[t.face_edges[3 * f + k]];
        bool found = false;
        for (uint32_t i = 0; i < e.face_count; ++i) found |= (t.edge_faces[e.first + i] >> 1) == uint32_t(f);
        EXPECT_TRUE(found);
      }
    }
  }
}

// OpenMesh's half-edge view accounts for every face and finds the holes.
//   3---2---5
//   | / | / |    2x1 quads strip: one boundary loop; closing it into a
//   0---1---4    tetrahedron: none; a fin on edge 0-1: one face refused.
TEST(Halfedge, AccountsForEveryFace) {
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0, 0, 0, 1};
  std::vector<uint32_t> strip = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
  HalfedgeSummary s = summarize_halfedges(positions_of(p.data(), 7), strip.data(), 4);
  EXPECT_EQ(s.added_faces, 4u);
  EXPECT_EQ(s.boundary_loops, 1u);
  HalfedgeSummary tet = summarize_halfedges(positions_of(kTetP.data(), 4), kTetI.data(), 4);
  EXPECT_EQ(tet.boundary_loops, 0u);
  EXPECT_EQ(tet.added_faces, 4u);
  std::vector<uint32_t> fin = {0, 1, 2, 1, 0, 3, 0, 1, 6, 3, 3, 1};
  HalfedgeSummary f = summarize_halfedges(positions_of(p.data(), 7), fin.data(), 4);
  EXPECT_EQ(f.added_faces + f.refused_faces + f.skipped_faces, 4u);
  EXPECT_EQ(f.refused_faces, 1u);
  EXPECT_EQ(f.skipped_faces, 1u);
}
