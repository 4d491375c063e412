// Tests of geom/focus.h's fitted cube faces (FocusResult::cube_faces): a
// point light among the receivers, or one whose focus body H is wider than
// FocusOptions::cube_cone_degrees, gets six 90-degree faces, each fitted to
// the part of H it looks at. Laws, on many random and adversarial frames,
// with membership written here independently of the library:
//
//   (1) every visible receiver q (a point of V n S) and every point of S on
//       the segment from q to the light, if it lies at least the floor from
//       the light along its face's axis (the floor is at most 1e-3 of the
//       farthest corner of S), falls in a face that is not empty, inside the
//       unit cube of both of that face's matrices (the 90-degree one with the
//       fitted near and far, and the method's focused one), at w > 0;
//   (2) along the segment both matrices keep the texel (the lookup of a
//       receiver finds its occluders) and the focused one orders depth
//       towards the light;
//   (3) a face that is not empty has 0 < near < far and finite matrices;
//       far lies within S's reach;
//   (4) an empty face holds no such point (implied by (1)); and a face whose
//       square pyramid misses S entirely is empty.
//
//   light at a vertex of S        light on the camera's near plane
//        L-----+                      eye |L    +-----+
//        |  S  |                     ---->|     |  S  |
//        +-----+                          |     +-----+
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include "focus_fixtures.h"
#include "geom/focus.h"

using namespace geom;
using namespace focustest;

namespace {

const P3 kAxes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const FocusMethod kMethods[3] = {FocusMethod::Psm, FocusMethod::Lispsm, FocusMethod::Uniform};

struct Frame {
  P3 eye, target, up{0, 1, 0};
  double fovy = 60, aspect = 1.5, near_d = 0.1, far_d = 1e4;
  P3 light;
  FocusBox box;
  CameraMatrices camera() const {
    double e[3] = {eye.x, eye.y, eye.z}, t[3] = {target.x, target.y, target.z}, u[3] = {up.x, up.y, up.z};
    return camera_look_at(e, t, u, fovy, aspect, near_d, far_d);
  }
  Light point() const {
    Light l;
    l.type = LightType::Point;
    l.position[0] = light.x, l.position[1] = light.y, l.position[2] = light.z;
    return l;
  }
  bool in_s(P3 p, double tol) const {
    double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k)
      if (c[k] < box.min[k] - tol || c[k] > box.max[k] + tol) return false;
    return true;
  }
  P3 corner(int i) const {
    return {i & 1 ? box.max[0] : box.min[0], i & 2 ? box.max[1] : box.min[1], i & 4 ? box.max[2] : box.min[2]};
  }
  double reach() const {  // the farthest corner of S from the light
    double r = 0;
    for (int i = 0; i < 8; ++i) r = std::fmax(r, norm(corner(i) - light));
    return r;
  }
  double scale() const {
    double s = 1;
    for (int k = 0; k < 3; ++k) s = std::fmax(s, std::fmax(std::fabs(box.min[k]), std::fabs(box.max[k])));
    return std::fmax(s, norm(eye));
  }
};

FocusResult run(const Frame& s, FocusMethod method, double cone = 0) {
  FocusOptions opt;
  opt.method = method;
  opt.cube_cone_degrees = cone;
  FocusResult r;
  EXPECT_TRUE(compute_focus(s.camera(), s.point(), s.box, opt, r)) << r.reason;
  return r;
}

bool unit_cube(const double* m, P3 p, double c[3]) {
  double h[4];
  apply(m, p, 1, h);
  if (!(h[3] > 0)) return false;
  for (int k = 0; k < 3; ++k) c[k] = h[k] / h[3];
  const double tol = 1e-6;
  return std::fabs(c[0]) <= 1 + tol && std::fabs(c[1]) <= 1 + tol && std::fabs(c[2]) <= 1 + tol;
}

// A random visible receiver: a point of V (up to the far side of S) in S.
bool sample_receiver(const Frame& s, std::mt19937& rng, P3& q) {
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  P3 view = unit(s.target - s.eye), side = unit(cross(view, s.up)), up = cross(side, view);
  double far_s = 0;
  for (int i = 0; i < 8; ++i) far_s = std::fmax(far_s, dot(s.corner(i) - s.eye, view));
  double f = std::fmin(s.far_d, far_s);
  if (!(f > s.near_d)) return false;
  double t = std::tan(s.fovy * M_PI / 360);
  for (int attempt = 0; attempt < 4000; ++attempt) {
    double depth = s.near_d + (f - s.near_d) * u01(rng);
    q = s.eye + view * depth + up * (u(rng) * t * depth) + side * (u(rng) * t * s.aspect * depth);
    if (s.in_s(q, 0)) return true;
  }
  return false;
}

// Laws (1)-(4) on one frame; returns the number of points checked in faces.
int check_faces(const Frame& s, const FocusResult& r, std::mt19937& rng, const char* what) {
  SCOPED_TRACE(what);
  EXPECT_TRUE(r.cube);
  const double tol = 1e-9 * s.scale(), floor = 1e-3 * s.reach() * (1 + 1e-9) + tol;
  for (int f = 0; f < 6; ++f) {
    const FocusFace& face = r.cube_faces[f];
    if (face.empty) continue;
    EXPECT_GT(face.near, 0) << "face " << f;
    EXPECT_GT(face.far, face.near) << "face " << f;
    EXPECT_LE(face.far, s.reach() * (1 + 1e-9) + tol) << "face " << f;
    for (int i = 0; i < 16; ++i) EXPECT_TRUE(std::isfinite(face.matrix[i]) && std::isfinite(face.focused[i]));
  }
  for (int f = 0; f < 6; ++f) {  // (4) a pyramid that misses S: all of S strictly behind one of its planes
    bool misses = false;
    for (int b = 0; b < 3 && !misses; ++b) {
      P3 e{double(b == 0), double(b == 1), double(b == 2)};
      if (dot(e, kAxes[f]) != 0) continue;
      for (double sg : {-1.0, 1.0}) {
        P3 n = kAxes[f] + e * sg;
        bool all_out = true;
        for (int i = 0; i < 8; ++i) all_out = all_out && dot(n, s.corner(i) - s.light) < -1e-6 * s.reach();
        misses = misses || all_out;
      }
    }
    if (misses) EXPECT_TRUE(r.cube_faces[f].empty) << "face " << f << " looks away from S yet holds something";
  }
  int checked = 0;
  std::uniform_real_distribution<double> u01(0, 1);
  for (int i = 0; i < 60; ++i) {
    P3 q;
    if (!sample_receiver(s, rng, q)) break;
    double t = u01(rng);
    P3 a = q + (s.light - q) * (t * t);  // an occluder between q and the light
    P3 pts[2] = {q, a};
    double cq[3] = {0, 0, 0}, cq_fit[3] = {0, 0, 0};
    int face_q = -1;
    for (int j = 0; j < 2; ++j) {
      P3 p = pts[j], d = p - s.light;
      double dd[3] = {d.x, d.y, d.z};
      int f = focus_cube_face_of(dd);
      if (f < 0 || !s.in_s(p, tol) || dot(d, kAxes[f]) < floor) continue;
      const FocusFace& face = r.cube_faces[f];
      EXPECT_FALSE(face.empty) << "face " << f << " is empty but holds a " << (j ? "caster" : "receiver");
      if (face.empty) continue;
      double c[3], cf[3];
      EXPECT_TRUE(unit_cube(face.matrix, p, c)) << "face " << f << ": outside the 90-degree face's cube, z "
                                                << c[2] << ", near " << face.near << ", far " << face.far;
      EXPECT_TRUE(unit_cube(face.focused, p, cf)) << "face " << f << ": outside the focused matrix's cube";
      ++checked;
      if (j == 0) {
        face_q = f;
        for (int k = 0; k < 3; ++k) cq[k] = c[k], cq_fit[k] = cf[k];
      } else if (f == face_q && norm(a - q) > 1e-6 * s.reach()) {  // (2) same texel, depth towards the light
        EXPECT_NEAR(c[0], cq[0], 1e-6);
        EXPECT_NEAR(c[1], cq[1], 1e-6);
        EXPECT_NEAR(cf[0], cq_fit[0], 1e-5);
        EXPECT_NEAR(cf[1], cq_fit[1], 1e-5);
        EXPECT_LE(cf[2], cq_fit[2] + 1e-9);
      }
    }
  }
  return checked;
}

Frame basic() {
  Frame s;
  s.eye = {0, 2, 5}, s.target = {0, 1.5, -5};
  s.box = {{-10, 0, -20}, {10, 5, 0}};
  s.light = {0, 1, -8};  // among the receivers
  return s;
}

}  // namespace

TEST(FocusFaces, PointLightAmongReceiversGetsSixFittedFaces) {
  Frame s = basic();
  std::mt19937 rng(1);
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_TRUE(r.needs_cube_map);
    ASSERT_TRUE(r.cube) << "no cube faces for a light among the receivers";
    int full = 0;
    for (const FocusFace& f : r.cube_faces) full += f.empty ? 0 : 1;
    EXPECT_GE(full, 5);  // the light sees receivers on every side but (maybe) one
    EXPECT_GT(check_faces(s, r, rng, focus_method_name(m)), 60);
  }
  // A point light far outside, seen through a narrow cone: one map, no faces.
  s.light = {0, 200, -10};
  FocusResult r = run(s, FocusMethod::Uniform, 120);
  EXPECT_FALSE(r.cube);
  // The same light with a cone threshold below its cone: faces.
  r = run(s, FocusMethod::Uniform, 1);
  EXPECT_TRUE(r.cube);
  EXPECT_GT(check_faces(s, r, rng, "narrow cone"), 10);
}

TEST(FocusFaces, RandomFrames) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  int frames = 0, points = 0;
  for (int i = 0; i < 300; ++i) {
    Frame s;
    double size = std::pow(10.0, 3 * u(rng));
    P3 c{u(rng) * size * 3, u(rng) * size * 3, u(rng) * size * 3};
    P3 half{size * (0.2 + u01(rng)), size * (0.2 + u01(rng)), size * (0.2 + u01(rng))};
    s.box = {{c.x - half.x, c.y - half.y, c.z - half.z}, {c.x + half.x, c.y + half.y, c.z + half.z}};
    s.eye = c + P3{u(rng), u(rng), u(rng)} * (size * 3);
    s.target = c + P3{u(rng), u(rng), u(rng)} * size;
    if (norm(s.target - s.eye) < 1e-3 * size) continue;
    s.up = P3{u(rng), u(rng), u(rng)};
    if (norm(cross(s.up, s.target - s.eye)) < 1e-3 * norm(s.up) * norm(s.target - s.eye)) continue;
    s.fovy = 20 + 100 * u01(rng);
    s.near_d = size * std::pow(10.0, -3 + 2 * u01(rng));
    s.far_d = size * 100;
    s.light = c + P3{u(rng) * half.x, u(rng) * half.y, u(rng) * half.z} * 1.2;  // mostly inside S
    FocusMethod m = kMethods[i % 3];
    FocusResult r = run(s, m, 90);
    if (!r.cube) continue;
    ++frames;
    points += check_faces(s, r, rng, focus_method_name(m));
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "frame " << i;
      break;
    }
  }
  EXPECT_GT(frames, 150);
  EXPECT_GT(points, 3000);
}

// The hard cases: the light at a vertex of S (and so of H), on the camera's
// near plane, behind the camera, exactly at the eye, on a face of S.
TEST(FocusFaces, HardLightPlaces) {
  std::mt19937 rng(3);
  Frame base = basic();
  P3 view = unit(base.target - base.eye);
  const P3 places[] = {
      {-10, 0, -20},                       // a vertex of S
      {10, 5, 0},                          // the vertex nearest the eye
      base.eye + view * base.near_d,       // on the camera's near plane
      base.eye - view * 2.0,               // behind the camera, outside S
      base.eye,                            // at the eye
      {0, 0, -10},                         // on S's floor
      {0, 2.5, -20},                       // on S's back face
  };
  for (P3 l : places) {
    Frame s = base;
    s.light = l;
    for (FocusMethod m : kMethods) {
      FocusResult r = run(s, m, 1);  // faces for any cone wider than 1 degree
      if (!r.cube) {
        ADD_FAILURE() << "no faces for the light at " << l.x << "," << l.y << "," << l.z;
        continue;
      }
      EXPECT_GT(check_faces(s, r, rng, focus_method_name(m)), 20) << l.x << "," << l.y << "," << l.z;
    }
  }
}

// geombake focus prints the six faces for a point light among the receivers.
TEST(FocusFaces, CommandPrintsSixFaces) {
  std::string dir = std::string(GEOM_BINARY_DIR) + "/tests";
  std::string geombake = std::string(GEOM_BINARY_DIR) + "/tools/geombake";
  std::string frame = dir + "/focus_faces_frame.json", out = dir + "/focus_faces_out.txt";
  std::ofstream(frame) << R"({"camera": {"eye": [0,2,5], "target": [0,1.5,-5], "up": [0,1,0],
    "fovy_degrees": 60, "aspect": 1.5, "near": 0.1, "far": 100},
    "light": {"type": "point", "position": [0,1,-8]},
    "scene_bounds": {"min": [-10,0,-20], "max": [10,5,0]}, "method": "uniform"})";
  ASSERT_EQ(0, std::system((geombake + " focus " + frame + " > " + out + " 2>&1").c_str()));
  std::ifstream in(out);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t at = text.find("\"faces\": [");
  ASSERT_NE(std::string::npos, at) << text;
  int entries = 0;
  for (size_t p = text.find("{\"matrix\": [", at); p != std::string::npos; p = text.find("{\"matrix\": [", p + 1)) {
    ++entries;
    size_t end = text.find('}', p);
    std::string entry = text.substr(p, end - p);
    for (const char* key : {"\"near\": ", "\"far\": ", "\"empty\": "})
      EXPECT_NE(std::string::npos, entry.find(key)) << key << " in " << entry;
  }
  EXPECT_EQ(6, entries) << text;
  // A spot light: one map, no faces.
  std::ofstream(frame) << R"({"camera": {"eye": [0,2,5], "target": [0,1.5,-5], "up": [0,1,0],
    "fovy_degrees": 60, "aspect": 1.5, "near": 0.1, "far": 100},
    "light": {"type": "spot", "position": [0,10,-5], "direction": [0,-1,0], "spot_angle_degrees": 40},
    "scene_bounds": {"min": [-10,0,-20], "max": [10,5,0]}})";
  ASSERT_EQ(0, std::system((geombake + " focus " + frame + " > " + out + " 2>&1").c_str()));
  std::ifstream in2(out);
  std::string spot((std::istreambuf_iterator<char>(in2)), std::istreambuf_iterator<char>());
  EXPECT_NE(std::string::npos, spot.find("\"faces\": []")) << spot;
}
