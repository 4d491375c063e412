// White-box tests of the focus body's private steps (libgeom/src/focus_body.h):
// the CGAL 3D hull path of H's faces (index_polytope) and the 3D-hull body
// (focus_hull), which compute_focus takes only on rare frames, so the public
// laws of tests/test_focus.cpp and tests/test_focus_near.cpp seldom reach them.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "focus_body.h"

using namespace geom::focus;

// The CGAL 3D hull path of H's faces (index_polytope), taken when the clipped
// polygons do not close cleanly. A unit cube whose top face comes as two
// halves: the side faces then meet a vertex in the middle of their top edge
// (a T-junction), so the hull decides:
//
//        +-----+-----+        top, split at x = 0.5
//        |     |     |
//        +-----+-----+
TEST(FocusFaces, HullPathClosesAroundTJunctions) {
  Polytope p;
  auto quad = [&](V3 a, V3 b, V3 c, V3 d) {
    for (V3 v : {a, b, c, d}) p.pts.push_back(v);
    p.sizes.push_back(4);
  };
  V3 c[8];
  for (int i = 0; i < 8; ++i) c[i] = V3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  quad(c[0], c[2], c[3], c[1]);                    // z = 0
  quad(c[4], c[5], V3(0.5, 1, 1), V3(0.5, 0, 1));  // z = 1, left half (wrong on purpose:
  quad(V3(0.5, 0, 1), V3(0.5, 1, 1), c[7], c[6]);  // two halves of one face)
  quad(c[0], c[1], c[5], c[4]);
  quad(c[2], c[6], c[7], c[3]);
  quad(c[0], c[4], c[6], c[2]);
  quad(c[1], c[3], c[7], c[5]);
  std::vector<double> xyz;
  std::vector<uint32_t> sizes, idx;
  index_polytope(p, 1e-9, xyz, sizes, idx);
  EXPECT_EQ(8u, xyz.size() / 3) << "the mid-edge points are no corners of the hull";
  EXPECT_EQ(6u, sizes.size());
  size_t edges = 0;
  for (uint32_t n : sizes) edges += n;
  EXPECT_EQ(2, long(xyz.size() / 3) - long(edges / 2) + long(sizes.size()));
}

// The same path on the clipped body that once showed CGAL 5.5's indexed
// hull output turning a triangle inside out (five coplanar points on top):
// every face must be planar and have the whole body on its inner side.
TEST(FocusFaces, HullPathOnCoplanarPoints) {
  const double v[14][3] = {{30.19296516923702, 35.784288966538632, -32.229582418873441},
                           {30.192965169237016, 36.586921566597297, -49.191882523974385},
                           {22.50026572276429, 47.10249001755151, -65.650110348388694},
                           {-10.428319400955537, 17.440086852301601, -39.135700583421297},
                           {30.192965169237013, 17.440086852301601, -33.370035928091653},
                           {-10.428319400955539, 52.801626379344555, -32.229582418873441},
                           {6.1085250742134116, 17.440086852301604, -57.692623009771275},
                           {16.748155232885125, 52.801626379344555, -32.229582418873441},
                           {-10.428319400955544, 17.440086852301601, -32.229582418873441},
                           {6.9435086054241761, 28.090301909196238, -65.650110348388694},
                           {17.997575123940152, 52.801626379344555, -65.650110348388694},
                           {30.19296516923702, 17.440086852301601, -32.229582418873441},
                           {-10.428319400955537, 52.801626379344555, -62.44564107108318},
                           {-7.5726837062666172, 52.801626379344555, -65.650110348388694}};
  Polytope p;
  for (const auto& q : v) p.pts.push_back(V3(q[0], q[1], q[2]));
  p.sizes.push_back(14);  // one "polygon" holding every point: not a closed surface, so the hull decides
  std::vector<double> xyz;
  std::vector<uint32_t> sizes, idx;
  index_polytope(p, 1e-8, xyz, sizes, idx);
  size_t nv = xyz.size() / 3, edges = 0;
  ASSERT_GE(nv, 4u);
  for (uint32_t n : sizes) edges += n;
  EXPECT_EQ(2, long(nv) - long(edges / 2) + long(sizes.size()));
  V3 centre(0, 0, 0);
  for (size_t i = 0; i < nv; ++i) centre = centre + V3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]) * (1.0 / double(nv));
  size_t base = 0;
  for (uint32_t n : sizes) {
    auto at = [&](uint32_t k) { return V3(xyz[3 * idx[k]], xyz[3 * idx[k] + 1], xyz[3 * idx[k] + 2]); };
    V3 nn(0, 0, 0);
    for (uint32_t i = 0; i < n; ++i) nn = nn + cross(at(base + i) - centre, at(base + (i + 1) % n) - centre);
    nn = normalize(nn);
    double d = dot(nn, at(base));
    for (uint32_t i = 0; i < n; ++i) EXPECT_NEAR(d, dot(nn, at(base + i)), 1e-6) << "face not planar";
    for (size_t i = 0; i < nv; ++i)
      EXPECT_LE(dot(nn, V3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2])), d + 1e-6) << "vertex outside a face";
    base += n;
  }
}

// The 3D-hull body (focus_hull), the fallback when the silhouette has no
// area: the box [0,1]^3 with a point light at (0.5, 0.5, 3) gives the
// pyramid-topped box, clipped by S = [-1,2] x [-1,2] x [0,2].
TEST(FocusFaces, HullBodyFallback) {
  V3 c[8] = {V3(0, 0, 1), V3(1, 0, 1), V3(1, 1, 1), V3(0, 1, 1), V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0), V3(0, 1, 0)};
  Polytope r, body, scratch;
  frustum_polytope(c, r);
  std::vector<Plane> clip = {{V3(0, 0, -1), 2}};  // z <= 2
  std::vector<V3> work;
  focus_hull(r, V3(0.5, 0.5, 3), false, 0, clip.data(), clip.size(), 1e-9, work, body, scratch);
  std::vector<V3> verts;
  unique_vertices(body, 1e-9, verts);
  EXPECT_EQ(12u, verts.size());  // 8 box corners + 4 where the pyramid meets z = 2
  for (V3 v : verts) {
    EXPECT_LE(v.z, 2 + 1e-9);
    if (v.z > 1 + 1e-9) EXPECT_NEAR(0.25, std::fabs(v.x - 0.5), 1e-9);  // (2-1)/(3-1) of the way to the apex
  }
}
