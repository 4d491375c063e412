// Weld (geom/weld.h): exact and tolerant merges on tiny meshes drawn in
// comments, strided input, far coordinates and NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geom/topology.h"
#include "geom/weld.h"

using namespace geom;

namespace {

Topology topo(const std::vector<float>& p, const std::vector<uint32_t>& idx) {
  return build_topology(positions_of(p.data(), p.size() / 3), idx.data(), idx.size() / 3);
}

}  // namespace

TEST(Weld, ExactMergesSignedZerosAndKeepsTheMap) {
  //  two triangles of a quad split by a seam: 6 corners, 4 positions, one with -0
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 1, 1, 0, -0.0f, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5};
  WeldResult w = weld(positions_of(p.data(), 6), idx.data(), idx.size());
  EXPECT_EQ(w.vertex_count(), 4u);
  EXPECT_EQ(w.remap[3], w.remap[0]);
  EXPECT_EQ(w.remap[4], w.remap[2]);
  EXPECT_EQ(w.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  Topology t = topo(w.positions, w.indices);
  EXPECT_EQ(t.stats.manifold_edges, 1u);
}

TEST(Weld, ToleranceAndStride) {
  // Interleaved vertices (position + 2 floats of UV), stride 20 bytes.
  struct V {
    float x, y, z, u, v;
  };
  std::vector<V> verts = {
      {0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {0.0004f, 0, 0, 5, 5}, {1, 1e-5f, 0, 0, 1}, {3, 0, 0, 0, 0}};
  std::vector<uint32_t> idx = {0, 1, 4, 2, 3, 4};
  PositionSpan span(&verts[0].x, verts.size(), sizeof(V));
  WeldResult exact = weld(span, idx.data(), idx.size());
  EXPECT_EQ(exact.vertex_count(), 5u);
  WeldResult loose = weld(span, idx.data(), idx.size(), 1e-3f);
  EXPECT_EQ(loose.vertex_count(), 3u);
  EXPECT_EQ(loose.remap[2], 0u);
  EXPECT_EQ(loose.remap[3], 1u);
  EXPECT_EQ(loose.positions[3], 1.0f);  // the representative keeps its own position
  WeldResult tight = weld(span, idx.data(), idx.size(), 1e-6f);
  EXPECT_EQ(tight.vertex_count(), 5u);
}

TEST(Weld, FarFromOriginAndNaN) {
  std::vector<float> p = {1e5f, 1e5f, 1e5f, 1e5f, 1e5f, 1e5f, NAN, 0, 0, NAN, 0, 0};
  std::vector<uint32_t> idx = {0, 1, 2, 3, 0, 1};
  WeldResult w = weld(positions_of(p.data(), 4), idx.data(), idx.size());
  EXPECT_EQ(w.vertex_count(), 3u);  // NaN vertices never merge
  WeldResult t = weld(positions_of(p.data(), 4), idx.data(), idx.size(), 0.5f);
  EXPECT_EQ(t.vertex_count(), 3u);
}
