// Laws of the GL_TRIANGLES_ADJACENCY index buffer (geom/adjacency.h):
//   * slots 0, 2, 4 are the triangle; slot 1, 3, 5 the vertex opposite each
//     edge in the neighbour chosen by the documented rule (checked by brute
//     force over all triangles), the triangle's own opposite vertex at a
//     boundary;
//   * the geometry-shader silhouette test of Kenzel 2013, Sect. 3.2.1 (signs of
//     the projected triangle and its neighbour differ) finds exactly the
//     silhouette edges of a closed mesh for random viewpoints, and every
//     boundary edge of an open one;
//   * on closed manifold meshes, the same buffer as meshoptimizer's
//     meshopt_generateAdjacencyIndexBuffer (an independent implementation).
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <array>
#include <cmath>
#include <random>
#include <set>

#include "geom/adjacency.h"
#include "silhouette_fixtures.h"

namespace {

using fixtures::Mesh;

std::vector<uint32_t> adjacency_of(const fixtures::Baked& b) {
  const size_t n = b.weld.indices.size() / 3;
  std::vector<uint32_t> adj(geom::adjacency_index_count(n), 0xdeadbeefu);
  EXPECT_TRUE(geom::build_adjacency(adj.data(), b.weld.indices.data(), n, b.weld.vertex_count()));
  return adj;
}

// The documented rule, by brute force.
uint32_t expected_neighbour(const std::vector<uint32_t>& idx, size_t t, int k) {
  const uint32_t* v = &idx[3 * t];
  const uint32_t a = v[k], b = v[(k + 1) % 3], own = v[(k + 2) % 3];
  if (a == b || b == own || own == a) return own;
  const size_t n = idx.size() / 3;
  for (int pass = 0; pass < 2; ++pass)
    for (size_t u = 0; u < n; ++u) {
      if (u == t) continue;
      const uint32_t* w = &idx[3 * u];
      if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
      for (int j = 0; j < 3; ++j) {
        const uint32_t x = w[j], y = w[(j + 1) % 3];
        if (pass == 0 ? (x == b && y == a) : (x == a && y == b)) return w[(j + 2) % 3];
      }
    }
  return own;
}

TEST(Adjacency, FollowsTheDocumentedRule) {
  for (const Mesh& m : {fixtures::box(0, 0, 0, 1, 1, 1), fixtures::torus(9, 6), fixtures::sheet(4, 0.2),
                        fixtures::book(5), fixtures::bowtie(), fixtures::flipped_box(), fixtures::degenerate_box(),
                        fixtures::stack(), fixtures::sliver_box()}) {
    const fixtures::Baked b = fixtures::bake(m);
    const std::vector<uint32_t> adj = adjacency_of(b);
    const std::vector<uint32_t>& idx = b.weld.indices;
    for (size_t t = 0; t < idx.size() / 3; ++t)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(adj[6 * t + 2 * k], idx[3 * t + k]);
        EXPECT_EQ(adj[6 * t + 2 * k + 1], expected_neighbour(idx, t, k)) << m.name << " triangle " << t;
      }
  }
}

// det of the projected triangle (homogeneous, Kenzel 2013, Sect. 3.2.1: det[p1 p2 p3]): the sign of
// the projected winding seen from the eye e.
double winding_sign(const float* p, const std::array<double, 3>& e, uint32_t a, uint32_t b, uint32_t c) {
  double m[3][3];
  const uint32_t v[3] = {a, b, c};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) m[i][k] = p[3 * v[i] + k] - e[k];
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

TEST(Adjacency, GeometryShaderTestFindsSilhouettes) {
  std::mt19937 rng(8);
  std::normal_distribution<double> g;
  for (const Mesh& m : {fixtures::sphere(16, 9), fixtures::torus(16, 9), fixtures::sheet(5, 0.3)}) {
    const fixtures::Baked b = fixtures::bake(m);
    const std::vector<uint32_t> adj = adjacency_of(b);
    const float* p = b.weld.positions.data();
    const size_t n = b.weld.indices.size() / 3;
    for (int trial = 0; trial < 20; ++trial) {
      const std::array<double, 3> eye = {3 * g(rng), 3 * g(rng), 3 * g(rng)};
      std::set<std::pair<uint32_t, uint32_t>> gs, truth;
      for (size_t t = 0; t < n; ++t) {
        const uint32_t* a = &adj[6 * t];
        const double s = winding_sign(p, eye, a[0], a[2], a[4]);
        for (int k = 0; k < 3; ++k) {
          const uint32_t v0 = a[2 * k], v1 = a[(2 * k + 2) % 6], nb = a[2 * k + 1];
          const double sn = winding_sign(p, eye, v0, nb, v1);
          if (s > 0 && sn <= 0) gs.insert({std::min(v0, v1), std::max(v0, v1)});
          if (s <= 0 && sn > 0) gs.insert({std::min(v0, v1), std::max(v0, v1)});
        }
      }
      // Truth from the edge table: the facings differ, or a boundary edge.
      for (const geom::Edge& e : b.topology.edges) {
        if (e.face_count == 1) {
          truth.insert({e.v0, e.v1});
          continue;
        }
        const uint32_t f0 = b.topology.edge_faces[e.first] >> 1, f1 = b.topology.edge_faces[e.first + 1] >> 1;
        const uint32_t* i0 = &b.weld.indices[3 * f0];
        const uint32_t* i1 = &b.weld.indices[3 * f1];
        if ((winding_sign(p, eye, i0[0], i0[1], i0[2]) > 0) != (winding_sign(p, eye, i1[0], i1[1], i1[2]) > 0))
          truth.insert({e.v0, e.v1});
      }
      EXPECT_EQ(gs, truth) << m.name;
    }
  }
}

TEST(Adjacency, MatchesMeshoptimizerOnClosedManifolds) {
  for (const Mesh& m : {fixtures::box(0, 0, 0, 1, 1, 1), fixtures::sphere(20, 10), fixtures::torus(20, 10)}) {
    const fixtures::Baked b = fixtures::bake(m);
    const std::vector<uint32_t> adj = adjacency_of(b);
    std::vector<unsigned int> ref(adj.size());
    meshopt_generateAdjacencyIndexBuffer(ref.data(), b.weld.indices.data(), b.weld.indices.size(),
                                         b.weld.positions.data(), b.weld.vertex_count(), 12);
    EXPECT_TRUE(std::equal(adj.begin(), adj.end(), ref.begin())) << m.name;
  }
}

//   0---1      two triangles (0,1,2) and (0,2,3) sharing the diagonal 0-2;
//   | / |      every other edge is a boundary: its slot repeats the
//   3---2      triangle's own opposite vertex.
//   (drawn with y down: 0 (0,0) 1 (1,0) 2 (1,1) 3 (0,1))
TEST(Adjacency, TinyQuad) {
  Mesh q;
  q.add(0, 0, 0), q.add(1, 0, 0), q.add(1, 1, 0), q.add(0, 1, 0);
  q.tri(0, 1, 2);
  q.tri(0, 2, 3);
  const fixtures::Baked b = fixtures::bake(q);
  const std::vector<uint32_t> adj = adjacency_of(b);
  const std::vector<uint32_t> want = {0, 2, 1, 0, 2, 3,   // (0,1): own 2; (1,2): own 0; (2,0): neighbour 3
                                      0, 1, 2, 0, 3, 2};  // (0,2): neighbour 1; (2,3): own 0; (3,0): own 2
  EXPECT_EQ(adj, want);
  EXPECT_TRUE(geom::build_adjacency(nullptr, nullptr, 0, 0));
}

}  // namespace
