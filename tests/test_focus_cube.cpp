// Tests of geom/focus.h's cube faces (Gerasimov 2004,
// "Omnidirectional Shadow Mapping"): focus_cube_faces' six
// matrices and focus_cube_face_of, against OpenGL's cube-map face table.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "focus_fixtures.h"
#include "geom/focus.h"

using namespace geom;
using namespace focustest;

// Cube faces: every direction, seams and corners included, falls on exactly
// one face (focus_cube_face_of) and that face's matrix maps it inside; no
// other face maps it strictly inside its square.
TEST(CubeFaces, CoverEveryDirectionExactlyOnce) {
  double pos[3] = {3, -2, 7};
  double m[6][16];
  focus_cube_faces(pos, 0.05, 100, m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<P3> dirs;
  for (int i = 0; i < 20000; ++i) dirs.push_back({u(rng), u(rng), u(rng)});
  // seams and corners, exactly and one ulp away
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        if (!a && !b && !c) continue;
        dirs.push_back({double(a), double(b), double(c)});
        dirs.push_back({std::nextafter(double(a), 2.0), double(b), double(c)});
        dirs.push_back({double(a), std::nextafter(double(b), -2.0), 0.5 * c});
      }
  for (P3 d : dirs) {
    double dd[3] = {d.x, d.y, d.z};
    int face = focus_cube_face_of(dd);
    ASSERT_GE(face, 0);
    int strictly = 0;
    for (int f = 0; f < 6; ++f) {
      double c[4];
      apply(m[f], P3{pos[0], pos[1], pos[2]} + unit(d) * 10, 1, c);
      if (!(c[3] > 0)) continue;
      double x = c[0] / c[3], y = c[1] / c[3], z = c[2] / c[3];
      bool closed = std::fabs(x) <= 1 + 1e-12 && std::fabs(y) <= 1 + 1e-12;
      bool open = std::fabs(x) < 1 - 1e-12 && std::fabs(y) < 1 - 1e-12;
      if (f == face) {
        EXPECT_TRUE(closed) << "face " << f << " misses its own direction";
        EXPECT_LE(std::fabs(z), 1);
      }
      if (open) {
        ++strictly;
        EXPECT_EQ(face, f);
      }
    }
    EXPECT_LE(strictly, 1);
  }
  double zero[3] = {0, 0, 0}, bad[3] = {NAN, 1, 0};
  EXPECT_EQ(-1, focus_cube_face_of(zero));
  EXPECT_EQ(-1, focus_cube_face_of(bad));
}

// The orientation of each face is OpenGL's cube-map table: a direction's
// face coordinates (s, t) from the spec, mapped to [-1, 1], equal the matrix's
// clip x, y (sc / |ma|, tc / |ma|, spec 4.5 Table 8.19).
TEST(CubeFaces, MatchOpenGLFaceTable) {
  double pos[3] = {0, 0, 0}, m[6][16];
  focus_cube_faces(pos, 0.1, 10, m);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 2000; ++i) {
    double d[3] = {u(rng), u(rng), u(rng)};
    int f = focus_cube_face_of(d);
    double rx = d[0], ry = d[1], rz = d[2], sc, tc, ma;
    switch (f) {
      case 0:
        sc = -rz, tc = -ry, ma = rx;
        break;
      case 1:
        sc = rz, tc = -ry, ma = rx;
        break;
      case 2:
        sc = rx, tc = rz, ma = ry;
        break;
      case 3:
        sc = rx, tc = -rz, ma = ry;
        break;
      case 4:
        sc = rx, tc = -ry, ma = rz;
        break;
      default:
        sc = -rx, tc = -ry, ma = rz;
        break;
    }
    double c[4];
    apply(m[f], P3{d[0], d[1], d[2]}, 1, c);
    // Rendering flips nothing: clip x = s, clip y = -t would be D3D; GL's
    // window y and texture t both grow upwards, so clip y = t.
    EXPECT_NEAR(sc / std::fabs(ma), c[0] / c[3], 1e-12);
    EXPECT_NEAR(tc / std::fabs(ma), c[1] / c[3], 1e-12);
  }
}
