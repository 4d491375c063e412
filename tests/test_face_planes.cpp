// Face planes (geom/face_planes.h): one stored plane per face, shared by
// coplanar neighbours, in the local frame; on tiny meshes drawn here.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geom/face_planes.h"
#include "geom/topology.h"

using namespace geom;

namespace {

FacePlanes planes_of(const std::vector<float>& p, const std::vector<uint32_t>& idx, const FacePlaneOptions& o = {}) {
  const PositionSpan span = positions_of(p.data(), p.size() / 3);
  const Topology t = build_topology(span, idx.data(), idx.size() / 3);
  return compute_face_planes(span, idx.data(), idx.size() / 3, t, o);
}

//   3-------2
//   |     / |     z = 0, counter-clockwise seen from +z: the front is +z
//   |   /   |
//   | /     |
//   0-------1
const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<uint32_t> kQuadI = {0, 1, 2, 0, 2, 3};

}  // namespace

TEST(FacePlanes, EmptyMesh) {
  const FacePlanes f = planes_of({}, {});
  EXPECT_EQ(f.plane_count(), 0u);
  EXPECT_TRUE(f.face_plane.empty());
  EXPECT_EQ(f.degenerate_faces, 0u);
}

TEST(FacePlanes, CoplanarQuadSharesOnePlaneInTheLocalFrame) {
  const FacePlanes f = planes_of(kQuad, kQuadI);
  ASSERT_EQ(f.plane_count(), 1u);
  EXPECT_EQ(f.face_plane, (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(f.shared_faces, 1u);
  EXPECT_EQ(f.origin[0], 0.5);  // the box centre
  EXPECT_EQ(f.origin[1], 0.5);
  EXPECT_EQ(f.origin[2], 0.0);
  EXPECT_NEAR(f.diagonal, std::sqrt(2.0), 1e-12);
  EXPECT_EQ(f.planes, (std::vector<float>{0, 0, 1, 0}));  // n = +z, n.p + d = 0 on the local z = 0
}

//   The quad's triangle 0-1-2 and a fin 1-0-4 hanging below edge 0-1
//   (4 = (0.5, 0, -1)): a 90 degree fold, two planes, nothing shared.
TEST(FacePlanes, FoldKeepsTwoPlanes) {
  std::vector<float> p = kQuad;
  p.insert(p.end(), {0.5f, 0, -1});
  const FacePlanes f = planes_of(p, {0, 1, 2, 1, 0, 4});
  ASSERT_EQ(f.plane_count(), 2u);
  EXPECT_EQ(f.shared_faces, 0u);
  EXPECT_NE(f.face_plane[0], f.face_plane[1]);
  const float* fin = &f.planes[4 * size_t(f.face_plane[1])];
  EXPECT_FLOAT_EQ(fin[0], 0);
  EXPECT_FLOAT_EQ(fin[1], -1);  // (1-0) x (4-0) seen from the fin's front: -y
  EXPECT_FLOAT_EQ(fin[2], 0);
}

// A collapsed triangle (two equal indices) and a zero-area one (collinear) have no plane.
TEST(FacePlanes, DegenerateFacesHaveNoPlane) {
  std::vector<float> p = kQuad;
  p.insert(p.end(), {2, 0, 0});  // 4: on the line through 0 and 1
  const FacePlanes f = planes_of(p, {0, 1, 2, 0, 0, 3, 0, 1, 4});
  EXPECT_EQ(f.degenerate_faces, 2u);
  EXPECT_EQ(f.face_plane[1], FacePlanes::kNone);
  EXPECT_EQ(f.face_plane[2], FacePlanes::kNone);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(f.normals[3 + k], 0.0);
  EXPECT_EQ(f.plane_count(), 1u);
}

// 1e5 units from the origin the stored plane is local: d stays 0, not 1e5.
TEST(FacePlanes, FarFromTheOriginStaysLocal) {
  std::vector<float> p = kQuad;
  for (size_t i = 0; i < p.size(); i += 3) p[i] += 1e5f, p[i + 2] += 1e5f;
  const FacePlanes f = planes_of(p, kQuadI);
  ASSERT_EQ(f.plane_count(), 1u);
  EXPECT_EQ(f.origin[0], 1e5 + 0.5);
  EXPECT_EQ(f.origin[2], 1e5);
  EXPECT_EQ(f.planes, (std::vector<float>{0, 0, 1, 0}));
}

// A gently bent strip: each quad turns 0.006 degrees from the last. Against
// the seed (not the last member), a 0.01 degree group takes two quads, so six
// quads make three planes; one degree takes them all. (The distance test is
// opened wide so that only the angle decides.)
//   side view:  0---1---2---3---4---5---6   (columns; the strip is 1 wide in y)
TEST(FacePlanes, GroupsCompareWithTheSeedSoCurvesDoNotDrift) {
  std::vector<float> p;
  std::vector<uint32_t> idx;
  double x = 0, z = 0;
  const double step = 0.006 * M_PI / 180;
  for (int i = 0; i <= 6; ++i) {
    p.insert(p.end(), {float(x), 0, float(z), float(x), 1, float(z)});
    x += std::cos(i * step), z += std::sin(i * step);
  }
  for (uint32_t i = 0; i < 6; ++i) {
    const uint32_t a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1;
    idx.insert(idx.end(), {a, b, c, a, c, d});
  }
  FacePlaneOptions o;
  o.coplanar_distance = 1;
  const FacePlanes f = planes_of(p, idx, o);
  EXPECT_EQ(f.plane_count(), 3u);
  EXPECT_EQ(f.face_plane[0], f.face_plane[3]);  // quads 0 and 1
  EXPECT_NE(f.face_plane[3], f.face_plane[4]);  // quad 2 starts the next group
  o.coplanar_degrees = 1;
  EXPECT_EQ(planes_of(p, idx, o).plane_count(), 1u);
}

// The shaders' front test: strictly in front, in float, for points and directions.
TEST(FacePlanes, LightInFront) {
  const float plane[4] = {0, 0, 1, 0};
  const float above[4] = {0, 0, 5, 1}, below[4] = {0, 0, -5, 1}, on[4] = {3, 2, 0, 1}, towards_z[4] = {0, 0, 1, 0};
  EXPECT_TRUE(light_in_front(plane, above));
  EXPECT_FALSE(light_in_front(plane, below));
  EXPECT_FALSE(light_in_front(plane, on));
  EXPECT_TRUE(light_in_front(plane, towards_z));
}

// The frame is the box of the referenced vertices: an unused vertex far away
// moves nothing (the index pass), and every vertex used gives the same frame
// from the vertex pass.
TEST(FacePlanes, FrameIsTheBoxOfTheReferencedVertices) {
  std::vector<float> p = kQuad;
  p.insert(p.end(), {100, 100, 100});  // vertex 4, referenced by no face
  const FacePlanes f = planes_of(p, kQuadI);
  EXPECT_EQ(f.origin[0], 0.5);
  EXPECT_EQ(f.origin[1], 0.5);
  EXPECT_EQ(f.origin[2], 0.0);
  EXPECT_NEAR(f.diagonal, std::sqrt(2.0), 1e-12);
  const FacePlanes g = planes_of(kQuad, kQuadI);  // all used
  EXPECT_EQ(g.origin[0], f.origin[0]);
  EXPECT_EQ(g.origin[1], f.origin[1]);
  EXPECT_EQ(g.diagonal, f.diagonal);
}

// An axis flat at zero with both signs of zero: the box keeps the sign of the
// first zero the faces reach (here -0, vertex 1 opening the first face), not
// the first in vertex order (+0), so the frame and every stored bit are as
// the faces read them.
TEST(FacePlanes, FlatAtZeroKeepsTheSignTheFacesReachFirst) {
  const std::vector<float> p = {0, 0, 0.0f, 1, 0, -0.0f, 1, 1, 0.0f, 0, 1, -0.0f};
  const FacePlanes f = planes_of(p, {1, 2, 3, 1, 3, 0});
  EXPECT_EQ(f.origin[2], 0.0);
  EXPECT_TRUE(std::signbit(f.origin[2]));
  const FacePlanes g = planes_of(p, {0, 1, 2, 0, 2, 3});
  EXPECT_FALSE(std::signbit(g.origin[2]));
}
