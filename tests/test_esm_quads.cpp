// Laws of the extended-shadow-map quads (geom/esm_quads.h), through the CPU
// reference of shaders/esm_quad.vert (geom/extrude.h esm_corners):
//   * a quad opens exactly for silhouette edges: for every emitted manifold
//     edge, the number of open quads is 1 when the light is in front of one
//     face and behind the other (decided independently, in double, from the
//     triangles themselves) and 0 otherwise; a boundary or non-manifold edge
//     opens exactly one quad per face; skipped edges are coplanar or concave;
//   * the open quads of a closed convex mesh form closed loops;
//   * an open quad covers at least 70% of the nominal width 1.5 * len in the
//     shadow map (Bujnak 2004, Sect. 4.1, bounds the loss at 70.7%);
//   * records are 36 bytes and, with the planes they reference, at most 64
//     bytes per emitted edge on the test meshes.
// Lights within 1e-6 x the diagonal of a face's plane (or a bevel plane) are
// skipped for that edge: there the classification is decided by rounding.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <vector>

#include "geom/extrude.h"
#include "silhouette_fixtures.h"

namespace {

using fixtures::Mesh;
using V = std::array<double, 3>;
V sub(V a, V b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(V a, V b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V cross(V a, V b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double norm(V a) { return std::sqrt(dot(a, a)); }

using Key = std::array<float, 6>;
Key edge_key(const float* a, const float* b) {
  const bool swap = std::lexicographical_compare(b, b + 3, a, a + 3);
  const float* x = swap ? b : a;
  const float* y = swap ? a : b;
  return {x[0], x[1], x[2], y[0], y[1], y[2]};
}

// Light-space matrix of an orthographic projection along -d (d towards the
// light), column-major, scale k: clip = k * (x . right, x . up, ...), w = 1.
void ortho(V d, double k, float m[16]) {
  d = {d[0] / norm(d), d[1] / norm(d), d[2] / norm(d)};
  V up = std::fabs(d[1]) < 0.9 ? V{0, 1, 0} : V{1, 0, 0};
  V right = cross(up, d);
  right = {right[0] / norm(right), right[1] / norm(right), right[2] / norm(right)};
  up = cross(d, right);
  for (int i = 0; i < 16; ++i) m[i] = 0;
  for (int c = 0; c < 3; ++c) {
    m[4 * c + 0] = float(k * right[c]);
    m[4 * c + 1] = float(k * up[c]);
    m[4 * c + 2] = float(-k * d[c]);
  }
  m[15] = 1;
}

struct Light {
  V xyz;
  double w;
};

std::vector<Light> random_lights(const Mesh& m, std::mt19937& rng) {
  std::normal_distribution<double> g;
  std::vector<Light> out;
  for (int i = 0; i < 12; ++i) {
    V d = {g(rng), g(rng), g(rng)};
    out.push_back({{d[0] * 3, d[1] * 3, d[2] * 3}, 1});
    out.push_back({d, 0});
  }
  // Lights just off a face's plane (grazing) and close to a face.
  for (size_t t = 0; t < m.triangle_count() && t < 6; ++t) {
    const float* a = &m.positions[3 * m.indices[3 * t]];
    const float* b = &m.positions[3 * m.indices[3 * t + 1]];
    const float* c = &m.positions[3 * m.indices[3 * t + 2]];
    V n = cross(V{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, V{c[0] - a[0], c[1] - a[1], c[2] - a[2]});
    if (norm(n) == 0) continue;
    for (int k = 0; k < 3; ++k) n[k] /= norm(n);
    out.push_back({{a[0] + 2.0 * (b[0] - a[0]) + 1e-4 * n[0], a[1] + 2.0 * (b[1] - a[1]) + 1e-4 * n[1],
                    a[2] + 2.0 * (b[2] - a[2]) + 1e-4 * n[2]},
                   1});
    out.push_back({{(a[0] + b[0] + c[0]) / 3 + 1e-3 * n[0], (a[1] + b[1] + c[1]) / 3 + 1e-3 * n[1],
                    (a[2] + b[2] + c[2]) / 3 + 1e-3 * n[2]},
                   1});
  }
  return out;
}

TEST(EsmQuads, OpenExactlyForSilhouetteEdges) {
  std::mt19937 rng(2024);
  for (Mesh m :
       {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(14, 8), fixtures::torus(14, 8), fixtures::sheet(6, 0.3),
        fixtures::open_box(), fixtures::book(5), fixtures::bowtie(), fixtures::flipped_box(),
        fixtures::degenerate_box(), fixtures::stack(), fixtures::sheet(5, 0.0, 7, 1e-7), fixtures::sliver_box()}) {
    for (double shift : {0.0, 1e5}) {
      Mesh shifted = m;
      shifted.translate(shift, shift, -shift);
      const fixtures::Baked b = fixtures::bake(shifted);
      SCOPED_TRACE(m.name + (shift != 0 ? " at 1e5" : ""));
      const double* o = b.planes.origin;
      auto vert = [&](uint32_t v) {
        return V{double(b.weld.positions[3 * v]) - o[0], double(b.weld.positions[3 * v + 1]) - o[1],
                 double(b.weld.positions[3 * v + 2]) - o[2]};
      };
      const double eps = 1e-6 * b.planes.diagonal;
      // quads by edge
      std::map<Key, std::vector<const geom::EsmQuad*>> by_edge;
      for (const geom::EsmQuad& q : b.esm.quads) by_edge[edge_key(q.p0, q.p1)].push_back(&q);
      size_t matched = 0;
      for (const Light& l0 : random_lights(m, rng)) {
        Light l = l0;
        if (l.w != 0) l.xyz = {l.xyz[0] + shift, l.xyz[1] + shift, l.xyz[2] - shift};
        const double wl[4] = {l.xyz[0], l.xyz[1], l.xyz[2], l.w};
        float lf[4];
        geom::to_local_light(o, wl, lf);
        const V L = l.w != 0 ? V{l.xyz[0] - o[0], l.xyz[1] - o[1], l.xyz[2] - o[2]} : l.xyz;
        float mvp[16];
        ortho(l.w != 0 ? V{0.3, 1, 0.2} : l.xyz, 0.5, mvp);
        // side: signed distance of the light to a face's plane (double, from the triangle)
        auto side = [&](uint32_t f) {
          V a = vert(b.weld.indices[3 * f]), bb = vert(b.weld.indices[3 * f + 1]), c = vert(b.weld.indices[3 * f + 2]);
          V n = cross(sub(bb, a), sub(c, a));
          n = {n[0] / norm(n), n[1] / norm(n), n[2] / norm(n)};
          return l.w != 0 ? dot(n, sub(L, a)) : dot(n, L) / norm(L) * b.planes.diagonal;
        };
        for (const geom::Edge& e : b.topology.edges) {
          std::vector<uint32_t> live;
          for (uint32_t i = 0; i < e.face_count; ++i) {
            uint32_t ef = b.topology.edge_faces[e.first + i];
            if (b.planes.face_plane[ef >> 1] != geom::FacePlanes::kNone) live.push_back(ef);
          }
          if (live.empty()) continue;
          float p0[3], p1[3];
          for (int k = 0; k < 3; ++k) {
            p0[k] = float(double(b.weld.positions[3 * e.v0 + k]) - o[k]);
            p1[k] = float(double(b.weld.positions[3 * e.v1 + k]) - o[k]);
          }
          auto it = by_edge.find(edge_key(p0, p1));
          const size_t nq = it == by_edge.end() ? 0 : it->second.size();
          bool near_plane = false;
          for (uint32_t ef : live) near_plane |= std::fabs(side(ef >> 1)) < eps;
          int open = 0;
          float c[4][4];
          if (nq)
            for (const geom::EsmQuad* q : it->second) {
              const float* bp = &b.esm.planes[4 * (q->plane_b & 0x7fffffffu)];
              const float* ap = &b.esm.planes[4 * (q->plane_a & 0x7fffffffu)];
              for (const float* pl : {ap, bp}) {  // bevel planes too
                double s =
                    double(pl[0]) * lf[0] + double(pl[1]) * lf[1] + double(pl[2]) * lf[2] + double(pl[3]) * lf[3];
                near_plane |= std::fabs(s) < eps * (l.w != 0 ? 1 : 1 / b.planes.diagonal);
              }
              open += geom::esm_corners(*q, b.esm.planes.data(), lf, mvp, 0.01f, c);
            }
          if (near_plane) continue;
          ++matched;
          if (live.size() == 2) {
            const bool inconsistent = !((live[0] ^ live[1]) & 1u);
            const bool fa = side(live[0] >> 1) > 0, fb = side(live[1] >> 1) > 0;
            const bool silhouette = inconsistent ? fa == fb : fa != fb;
            if (nq == 0) {
              // skipped: coplanar (never a silhouette) or concave
              if (b.planes.face_plane[live[0] >> 1] == b.planes.face_plane[live[1] >> 1]) EXPECT_FALSE(silhouette);
              continue;
            }
            EXPECT_EQ(open, silhouette ? 1 : 0) << "edge " << e.v0 << "-" << e.v1;
          } else {
            EXPECT_EQ(nq, 2 * live.size());
            EXPECT_EQ(open, int(live.size())) << "edge " << e.v0 << "-" << e.v1;
          }
          if (::testing::Test::HasFailure()) return;
        }
      }
      EXPECT_GT(matched, b.topology.edges.size());
    }
  }
}

// Closed loops: on convex meshes (nothing concave to skip), and on a torus
// with EsmOptions::keep_concave (every non-coplanar edge kept).
TEST(EsmQuads, ClosedSilhouetteLoops) {
  std::mt19937 rng(3);
  geom::EsmOptions keep;
  keep.keep_concave = true;
  for (const Mesh& m : {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(20, 11), fixtures::torus(16, 9)}) {
    const bool torus = m.name == "torus";
    const fixtures::Baked b = fixtures::bake(m, {}, torus ? keep : geom::EsmOptions{});
    EXPECT_EQ(b.esm.stats.skipped_concave, 0u);
    if (torus) EXPECT_EQ(b.esm.stats.emitted_edges, b.esm.stats.candidate_edges - b.esm.stats.skipped_coplanar);
    for (const Light& l : random_lights(m, rng)) {
      const double wl[4] = {l.xyz[0], l.xyz[1], l.xyz[2], l.w};
      float lf[4], mvp[16], c[4][4];
      geom::to_local_light(b.planes.origin, wl, lf);
      ortho({0, 1, 0}, 1, mvp);
      std::map<std::array<float, 3>, int> degree;
      int open = 0;
      for (const geom::EsmQuad& q : b.esm.quads) {
        if (!geom::esm_corners(q, b.esm.planes.data(), lf, mvp, 0.01f, c)) continue;
        ++open;
        ++degree[{q.p0[0], q.p0[1], q.p0[2]}];
        ++degree[{q.p1[0], q.p1[1], q.p1[2]}];
      }
      for (auto& d : degree) EXPECT_EQ(d.second % 2, 0) << m.name;
      if (open == 0) continue;  // a light close to a face may see only that face
      EXPECT_GE(open, 3) << m.name;
    }
  }
}

// Width: directional light, orthographic shadow map of scale k; an open quad's
// two long sides are at least 0.7 * 1.5 * s * k apart in clip space.
TEST(EsmQuads, OpenQuadsCoverTheWidth) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  for (const Mesh& m : {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(12, 7), fixtures::torus(12, 8),
                        fixtures::sheet(5, 0.4), fixtures::book(5)}) {
    const fixtures::Baked b = fixtures::bake(m);
    int checked = 0;
    for (int i = 0; i < 60; ++i) {
      V d = {g(rng), g(rng), g(rng)};
      const double wl[4] = {d[0], d[1], d[2], 0};
      float lf[4], mvp[16], c[4][4];
      geom::to_local_light(b.planes.origin, wl, lf);
      const double k = 0.8, s = 0.02;
      ortho(d, k, mvp);
      for (const geom::EsmQuad& q : b.esm.quads) {
        if (!geom::esm_corners(q, b.esm.planes.data(), lf, mvp, float(s), c)) continue;
        double xy[4][2];
        for (int j = 0; j < 4; ++j)
          for (int r = 0; r < 2; ++r)
            xy[j][r] = mvp[r] * c[j][0] + mvp[4 + r] * c[j][1] + mvp[8 + r] * c[j][2] + mvp[12 + r];
        const double ex = xy[1][0] - xy[0][0], ey = xy[1][1] - xy[0][1], el = std::hypot(ex, ey);
        if (el < 1e-3) continue;  // the edge seen end-on: no width to speak of
        const double width = std::fabs(ex * (xy[2][1] - xy[0][1]) - ey * (xy[2][0] - xy[0][0])) / el;
        EXPECT_GE(width, 0.70 * 1.5 * s * k) << m.name;
        ++checked;
      }
    }
    EXPECT_GT(checked, 20) << m.name;
  }
}

// Tiny meshes drawn by hand.
//
//   box: 18 edges, 6 face diagonals (coplanar, skipped), 12 convex edges of
//   dihedral exactly 90 degrees: not under 90, one quad each.
//
//   wedge: a prism whose cross-section has a 30-degree ridge and 75-degree
//   base corners, all under 90: each of the three long edges gets two quads
//   against its bevel plane; the end triangles meet the sides at 90 (one quad).
//            c
//           / \ .
//          /   \ .
//         a-----b
TEST(EsmQuads, TinyMeshes) {
  fixtures::Baked b = fixtures::bake(fixtures::box(0, 0, 0, 1, 1, 1));
  EXPECT_EQ(b.esm.stats.candidate_edges, 18u);
  EXPECT_EQ(b.esm.stats.skipped_coplanar, 6u);
  EXPECT_EQ(b.esm.stats.emitted_edges, 12u);
  EXPECT_EQ(b.esm.quads.size(), 12u);
  EXPECT_EQ(b.esm.stats.bevel_edges, 0u);
  EXPECT_EQ(b.esm.planes.size(), 6u * 4);
  EXPECT_LE(double(b.esm.stats.bytes) / b.esm.stats.emitted_edges, 64.0);
  EXPECT_EQ(b.esm.stats.naive_bytes, 18u * 160);

  Mesh wedge;
  const double h = 1 / std::tan(15 * M_PI / 180);  // ridge angle 30 degrees
  uint32_t a0 = wedge.add(-1, 0, 0), b0 = wedge.add(1, 0, 0), c0 = wedge.add(0, h, 0);
  uint32_t a1 = wedge.add(-1, 0, 1), b1 = wedge.add(1, 0, 1), c1 = wedge.add(0, h, 1);
  wedge.tri(a0, c0, b0);
  wedge.tri(a1, b1, c1);
  wedge.quad(a0, b0, b1, a1);
  wedge.quad(b0, c0, c1, b1);
  wedge.quad(c0, a0, a1, c1);
  b = fixtures::bake(wedge);
  EXPECT_EQ(b.topology.stats.closed, true);
  // bevel edges: the ridge (30 degrees) and the two prism ends' edges? The end
  // triangles meet the sides at 90 degrees (no bevel); the base corners are 75.
  EXPECT_EQ(b.esm.stats.bevel_edges, 3u);
  EXPECT_EQ(b.esm.quads.size(), b.esm.stats.emitted_edges + 3);

  // Octahedral round trip.
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  for (int i = 0; i < 10000; ++i) {
    double v[3] = {g(rng), g(rng), g(rng)};
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& x : v) x /= n;
    int16_t e[2];
    float d[3];
    geom::octahedral_encode(v, e);
    geom::octahedral_decode(e, d);
    const V x = cross(V{v[0], v[1], v[2]}, V{d[0], d[1], d[2]});
    const double angle = std::atan2(norm(x), v[0] * d[0] + v[1] * d[1] + v[2] * d[2]);
    EXPECT_LT(angle, 0.01 * M_PI / 180);
  }
}

// The encoding rounds as std::lround(clamp(x / s) * 32767) does, whatever
// shortcut computes it: on the upper half (z >= 0, no fold; the fold only
// moves x and y before the same rounding), on random directions, on
// directions whose coordinates land on halves (k + 0.5) / 32767 and next to
// them, and with infinite and NaN coordinates.
TEST(EsmQuads, OctahedralEncodingRoundsAsLround) {
  auto snorm = [](double x) { return int16_t(std::lround(std::max(-1.0, std::min(1.0, x)) * 32767.0)); };
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> k(-32767, 32766);
  std::vector<std::array<double, 3>> dirs;
  for (int i = 0; i < 20000; ++i) dirs.push_back({g(rng), g(rng), std::fabs(g(rng))});
  for (int i = 0; i < 20000; ++i) {  // x / s = (k + 0.5) / 32767 and its neighbours
    const double a = (k(rng) + 0.5) / 32767.0;
    for (double t : {a, std::nextafter(a, 2.0), std::nextafter(a, -2.0)}) {
      const double rest = 1 - std::fabs(t);
      dirs.push_back({t, rest * 0.25, rest * 0.75});
      dirs.push_back({rest * 0.5, t, rest * 0.5});
    }
  }
  const double inf = HUGE_VAL, nan = std::nan("");
  for (double c : {0.0, -0.0, 1.0, -1.0, inf, -inf, nan})
    for (double d : {0.0, 1.0, inf, nan}) dirs.push_back({c, c, d}), dirs.push_back({d, c, d});
  for (const auto& d : dirs) {
    const double s = std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2]);
    int16_t got[2];
    geom::octahedral_encode(d.data(), got);
    ASSERT_EQ(got[0], snorm(s > 0 ? d[0] / s : 0)) << d[0] << " " << d[1] << " " << d[2];
    ASSERT_EQ(got[1], snorm(s > 0 ? d[1] / s : 0)) << d[0] << " " << d[1] << " " << d[2];
  }
}

TEST(EsmQuads, BytesPerEmittedEdge) {
  for (const Mesh& m : {fixtures::sphere(40, 20), fixtures::torus(40, 20), fixtures::stack()}) {
    const fixtures::Baked b = fixtures::bake(m);
    ASSERT_GT(b.esm.stats.emitted_edges, 0u);
    EXPECT_LE(double(b.esm.stats.bytes) / b.esm.stats.emitted_edges, 64.0) << m.name;
    EXPECT_EQ(b.esm.stats.bytes, b.esm.quads.size() * 36 + b.esm.planes.size() * 4);
  }
}

TEST(EsmQuads, EmptyMesh) {
  const fixtures::Baked b = fixtures::bake(Mesh{});
  EXPECT_TRUE(b.esm.quads.empty());
  EXPECT_EQ(b.esm.stats.candidate_edges, 0u);
}

}  // namespace

// The quads streamed (EsmOptions::quads_out) are the kept ones, in order, in
// pieces of whole edges (at most 4096 + an edge's), with the same planes and
// stats; none is kept. Every fixture, concave edges kept or not, and a sphere
// of more than 4096 quads so the pieces split.
TEST(EsmQuads, StreamedQuadsAreTheKeptOnes) {
  std::vector<Mesh> meshes = {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(14, 8), fixtures::torus(14, 8),
                              fixtures::sheet(6, 0.3), fixtures::open_box(), fixtures::book(5), fixtures::bowtie(),
                              fixtures::flipped_box(), fixtures::degenerate_box(), fixtures::stack(),
                              fixtures::sheet(5, 0.0, 7, 1e-7), fixtures::sliver_box(), fixtures::sphere(90, 45)};
  for (const Mesh& m : meshes)
    for (bool concave : {false, true}) {
      geom::EsmOptions kept;
      kept.keep_concave = concave;
      const fixtures::Baked b = fixtures::bake(m, {}, kept);
      std::vector<geom::EsmQuad> quads;
      size_t most = 0, calls = 0;
      geom::EsmOptions streamed = kept;
      streamed.quads_out = [&](const geom::EsmQuad* p, size_t n) {
        quads.insert(quads.end(), p, p + n), most = std::max(most, n), ++calls;
      };
      const geom::EsmQuads e =
          geom::build_esm_quads(geom::positions_of(b.weld.positions.data(), b.weld.vertex_count()),
                                b.weld.indices.data(), b.weld.indices.size() / 3, b.topology, b.planes, streamed);
      const std::string what = m.name + (concave ? " concave kept" : "");
      ASSERT_EQ(quads.size(), b.esm.quads.size()) << what;
      EXPECT_EQ(std::memcmp(quads.data(), b.esm.quads.data(), quads.size() * sizeof(geom::EsmQuad)), 0) << what;
      EXPECT_LE(most, 4096u + 2 * 3) << what;
      EXPECT_TRUE(e.quads.empty()) << what;
      EXPECT_EQ(e.planes, b.esm.planes) << what;
      EXPECT_EQ(e.stats.quads, b.esm.stats.quads) << what;
      EXPECT_EQ(e.stats.bytes, b.esm.stats.bytes) << what;
      EXPECT_EQ(e.stats.emitted_edges, b.esm.stats.emitted_edges) << what;
      if (b.esm.quads.size() > 3 * 4096) EXPECT_GE(calls, 3u) << what;
    }
}
