// Tests of geom/focus.h: the focus body H, the light matrices (psm, lispsm,
// uniform) and the cube faces. Laws checked on many random and adversarial
// frames, with membership tests written here independently of the library:
//
//   (1) every point of V n S n L lies in H;
//   (2) every point of S n L on a segment from such a receiver q to the light
//       (q + t (l - q), t in [0, 1]; for a directional light q + t u, t >= 0)
//       lies in H: every possible occluder of a visible point of the scene;
//   (3) every vertex of H lies in S, in L, and in conv(V u {l}) (the ray from
//       the light through the vertex, continued, meets V n S);
//   (4) the matrix maps every vertex of H to w > 0 inside the unit cube, for
//       all three methods;
//   (5) along a light ray inside H the matrix keeps the shadow-map position
//       and orders depth by distance to the light (smaller = nearer), for
//       every light kind (inverted point lights included);
//   (6) H's faces form a closed convex polytope (V - E + F = 2).
//
// The frame used by several tests, seen from above (y up out of the page):
//
//        light (directional, travelling -y, i.e. from above)
//
//     z=-20 +-----------+           S: the box [-10,10] x [0,5] x [-20,0]
//           |    \   /  |           V: camera at (0,2,5) looking down -z
//           |     \ /   |
//     z=0   +------*----+
//                  eye (0, 2, 5)
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "focus_fixtures.h"
#include "geom/focus.h"

using namespace geom;
using namespace focustest;

namespace {

struct HalfSpace {  // n.x <= d
  P3 n;
  double d;
};

struct FrameSetup {
  double eye[3], target[3], up[3];
  double fovy = 60, aspect = 1.5, near_d = 0.1, far_d = 100;
  Light light;
  FocusBox box;
  CameraMatrices camera() const { return camera_look_at(eye, target, up, fovy, aspect, near_d, far_d); }
};

FrameSetup basic_setup() {
  FrameSetup s;
  double eye[3] = {0, 2, 5}, target[3] = {0, 1.5, -5}, up[3] = {0, 1, 0};
  for (int k = 0; k < 3; ++k) s.eye[k] = eye[k], s.target[k] = target[k], s.up[k] = up[k];
  s.light.type = LightType::Directional;
  s.light.direction[0] = 0.3, s.light.direction[1] = -1, s.light.direction[2] = 0.2;
  s.box = {{-10, 0, -20}, {10, 5, 0}};
  return s;
}

// Independent membership tests.
struct Checker {
  FrameSetup s;
  CameraMatrices cam;
  double pv[16];
  std::vector<HalfSpace> v_planes, s_planes, l_planes, h_planes;
  P3 eye, view_dir, light_pos, towards_light;
  bool directional;
  double tol;
  const FocusResult* r = nullptr;

  Checker(const FrameSetup& setup, const FocusResult& result) : s(setup), r(&result) {
    cam = s.camera();
    multiply(cam.projection, cam.view, pv);
    // Gribb-Hartmann planes of V: row3 +- row_i >= 0.
    for (int i = 0; i < 3; ++i)
      for (int sg = -1; sg <= 1; sg += 2) {
        P3 n{-(pv[3] + sg * pv[i]), -(pv[7] + sg * pv[4 + i]), -(pv[11] + sg * pv[8 + i])};
        double d = pv[15] + sg * pv[12 + i];
        double len = norm(n);
        if (len > 0) v_planes.push_back({n * (1 / len), d / len});
      }
    for (int k = 0; k < 3; ++k) {
      P3 e{double(k == 0), double(k == 1), double(k == 2)};
      s_planes.push_back({e, std::fmax(s.box.max[k], s.box.min[k])});
      s_planes.push_back({e * -1, -std::fmin(s.box.min[k], s.box.max[k])});
    }
    eye = {s.eye[0], s.eye[1], s.eye[2]};
    view_dir = unit(P3{s.target[0], s.target[1], s.target[2]} - eye);
    directional = s.light.type == LightType::Directional;
    light_pos = {s.light.position[0], s.light.position[1], s.light.position[2]};
    towards_light = unit(P3{s.light.direction[0], s.light.direction[1], s.light.direction[2]}) * -1;
    // Tolerance: a relative 1e-10 of the coordinates (far from the origin)
    // plus 1e-6 of the scene's size.
    double coords = 1, size = 0;
    for (int k = 0; k < 3; ++k) {
      coords = std::fmax(coords, std::fmax(std::fabs(s.box.min[k]), std::fabs(s.box.max[k])));
      coords = std::fmax(coords, std::fabs(s.eye[k]));
      size = std::fmax(size, std::fabs(s.box.max[k] - s.box.min[k]));
    }
    tol = 1e-10 * coords + 1e-6 * std::fmax(size, 1e-3);
    // A zero-size axis of S is inflated (as documented) to 1e-6 of the largest
    // extent or 1e-9 of the coordinates: that much more room then.
    if (result.fallback == FocusFallback::DegenerateScene) tol += 1e-9 * coords + 1e-6 * size;
    // L as the library documents it, for the given result.
    if (!directional) {
      P3 axis{r->light_axis[0], r->light_axis[1], r->light_axis[2]};
      l_planes.push_back({axis * -1, -(dot(axis, light_pos) + r->light_near)});
      if (s.light.range > 0)
        for (int k = 0; k < 3; ++k) {
          P3 e{double(k == 0), double(k == 1), double(k == 2)};
          double c = k == 0 ? light_pos.x : k == 1 ? light_pos.y : light_pos.z;
          l_planes.push_back({e, c + s.light.range});
          l_planes.push_back({e * -1, -(c - s.light.range)});
        }
    }
    // H's planes from its faces (outward by H's centroid).
    size_t nv = r->vertex_count();
    P3 c{0, 0, 0};
    for (size_t i = 0; i < nv; ++i) c = c + vert(i) * (1.0 / double(nv));
    size_t base = 0;
    for (uint32_t n : r->face_sizes) {
      P3 nn{0, 0, 0};
      for (uint32_t i = 0; i < n; ++i) {
        P3 a = vert(r->face_indices[base + i]), b = vert(r->face_indices[base + (i + 1) % n]);
        nn = nn + cross(a - c, b - c);
      }
      P3 a = vert(r->face_indices[base]);
      if (norm(nn) > 0) {
        nn = unit(nn);
        if (dot(nn, a - c) < 0) nn = nn * -1;
        h_planes.push_back({nn, dot(nn, a)});
      }
      base += n;
    }
  }
  P3 vert(size_t i) const { return {r->vertices[3 * i], r->vertices[3 * i + 1], r->vertices[3 * i + 2]}; }
  static bool inside(const std::vector<HalfSpace>& hs, P3 p, double tol) {
    for (const auto& h : hs)
      if (dot(h.n, p) > h.d + tol) return false;
    return true;
  }
  bool in_spot(P3 p, double slack) const {  // the spot's square pyramid contains this cone
    if (s.light.type != LightType::Spot) return true;
    P3 axis = towards_light * -1;
    P3 d = p - light_pos;
    double along = dot(d, axis);
    double side = norm(d - axis * along);
    double angle = std::fmin(s.light.outer_cone, 89.9 * M_PI / 180);
    return side <= std::tan(angle) * along * slack + tol && along >= r->light_near - tol;
  }
  bool in_v(P3 p) const { return inside(v_planes, p, tol); }
  bool in_s(P3 p) const { return inside(s_planes, p, tol); }
  bool in_l(P3 p, double slack = 1) const { return inside(l_planes, p, tol) && in_spot(p, slack); }
  bool in_h(P3 p) const { return inside(h_planes, p, 16 * tol); }

  // Does the ray o + t d, t in [t0, inf), meet V n S (within tol)?
  bool ray_meets_vs(P3 o, P3 d, double t0) const {
    double lo = t0, hi = HUGE_VAL;
    for (const auto* set : {&v_planes, &s_planes})
      for (const auto& h : *set) {
        double a = dot(h.n, d), b = h.d + tol - dot(h.n, o);  // a t <= b
        if (std::fabs(a) < 1e-300) {
          if (b < 0) return false;
        } else if (a > 0) {
          hi = std::fmin(hi, b / a);
        } else {
          lo = std::fmax(lo, b / a);
        }
      }
    return lo <= hi + 1e-9 * (1 + std::fabs(hi));
  }

  // A random receiver: a point of V (depth up to the far side of S) in S and L.
  bool sample_receiver(std::mt19937& rng, P3& q) const {
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    double far_s = 0;
    for (int i = 0; i < 8; ++i) {
      P3 c{i & 1 ? s.box.max[0] : s.box.min[0], i & 2 ? s.box.max[1] : s.box.min[1],
           i & 4 ? s.box.max[2] : s.box.min[2]};
      far_s = std::fmax(far_s, dot(c - eye, view_dir));
    }
    double f = std::fmin(s.far_d, far_s);
    if (!(f > s.near_d)) return false;
    P3 side = unit(cross(view_dir, P3{s.up[0], s.up[1], s.up[2]}));
    P3 up = cross(side, view_dir);
    double t = std::tan(s.fovy * M_PI / 360);
    for (int attempt = 0; attempt < 2000; ++attempt) {
      double depth = s.near_d + (f - s.near_d) * u01(rng);
      q = eye + view_dir * depth + up * (u(rng) * t * depth) + side * (u(rng) * t * s.aspect * depth);
      // a flat S (zero extent on an axis): put the sample on its plane
      if (s.box.min[0] == s.box.max[0]) q.x = s.box.min[0];
      if (s.box.min[1] == s.box.max[1]) q.y = s.box.min[1];
      if (s.box.min[2] == s.box.max[2]) q.z = s.box.min[2];
      if (in_s(q) && in_l(q, 1 / std::sqrt(2.0)) && in_v(q)) return true;
    }
    return false;
  }
};

bool finite16(const double* m) {
  for (int i = 0; i < 16; ++i)
    if (!std::isfinite(m[i])) return false;
  return true;
}

void shadow_coords(const double* m, P3 p, double out[3], double& w) {
  double c[4];
  apply(m, p, 1, c);
  w = c[3];
  for (int k = 0; k < 3; ++k) out[k] = c[k] / c[3];
}

// Checks laws (1)-(6) on one frame and method; returns the number of samples checked.
int check_laws(const FrameSetup& s, const FocusResult& r, std::mt19937& rng, const char* what) {
  SCOPED_TRACE(what);
  EXPECT_TRUE(finite16(r.matrix));
  Checker ck(s, r);
  if (r.fallback == FocusFallback::EmptyFocus || r.fallback == FocusFallback::InvalidInput) {
    EXPECT_EQ(r.vertex_count(), 0u);
    return 0;
  }
  EXPECT_GE(r.vertex_count(), 4u);
  // (6) a closed polytope: V - E + F = 2.
  {
    size_t edges = 0;
    for (uint32_t n : r.face_sizes) edges += n;
    EXPECT_EQ(0u, edges % 2);
    long euler = long(r.vertex_count()) - long(edges / 2) + long(r.face_sizes.size());
    EXPECT_EQ(2, euler) << "V=" << r.vertex_count() << " F=" << r.face_sizes.size();
  }
  // (3) and (4) on every vertex.
  for (size_t i = 0; i < r.vertex_count(); ++i) {
    P3 v = ck.vert(i);
    EXPECT_TRUE(ck.in_s(v)) << "vertex " << i << " outside S";
    EXPECT_TRUE(ck.in_l(v, std::sqrt(2.0))) << "vertex " << i << " outside L";  // the pyramid's corners
    bool in_conv = ck.directional ? ck.ray_meets_vs(v, ck.towards_light * -1, 0)
                                  : ck.ray_meets_vs(ck.light_pos, v - ck.light_pos, 1);
    EXPECT_TRUE(in_conv) << "vertex " << i << " outside conv(V n S u {l})";
    double c[3], w;
    shadow_coords(r.matrix, v, c, w);
    EXPECT_GT(w, 0);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(c[k]), 1 + 1e-6) << "vertex " << i << " axis " << k;
  }
  // (1), (2), (5) on sampled receivers and occluders.
  int checked = 0;
  std::uniform_real_distribution<double> u01(0, 1);
  for (int i = 0; i < 40; ++i) {
    P3 q;
    if (!ck.sample_receiver(rng, q)) break;
    EXPECT_TRUE(ck.in_h(q)) << "receiver outside H";
    // occluders on the segment towards the light
    P3 step = ck.directional ? ck.towards_light * (1e3 * (1 + norm(q))) : ck.light_pos - q;
    double t1 = u01(rng), t2 = u01(rng);
    if (t1 > t2) std::swap(t1, t2);
    t1 *= t1 * t1, t2 *= t2 * t2;  // most samples near the receiver, where S n L is
    P3 a = q + step * t1, b = q + step * t2;
    bool a_ok = ck.in_s(a) && ck.in_l(a, 1 / std::sqrt(2.0)), b_ok = ck.in_s(b) && ck.in_l(b, 1 / std::sqrt(2.0));
    if (a_ok) EXPECT_TRUE(ck.in_h(a)) << "occluder outside H";
    if (b_ok) EXPECT_TRUE(ck.in_h(b)) << "occluder outside H";
    // (5) along the ray q -> light: same texel, depth ordered.
    double cq[3], ca[3], cb[3], wq, wa, wb;
    shadow_coords(r.matrix, q, cq, wq);
    EXPECT_GT(wq, 0);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(cq[k]), 1 + 1e-6);
    if (a_ok && b_ok && norm(b - a) > 1e-6 * (1 + norm(a))) {
      shadow_coords(r.matrix, a, ca, wa);
      shadow_coords(r.matrix, b, cb, wb);
      EXPECT_NEAR(ca[0], cb[0], 1e-5);
      EXPECT_NEAR(ca[1], cb[1], 1e-5);
      EXPECT_LE(cb[2], ca[2] + 1e-9) << "depth not ordered towards the light";
    }
    ++checked;
  }
  return checked;
}

// The warp's own laws: min_warp_gain 0 keeps the warp on every frame.
FocusResult run(const FrameSetup& s, FocusMethod method, FocusOptions opt = {}) {
  opt.method = method;
  opt.min_warp_gain = 0;
  FocusResult r;
  compute_focus(s.camera(), s.light, s.box, opt, r);
  return r;
}

const FocusMethod kMethods[3] = {FocusMethod::Psm, FocusMethod::Lispsm, FocusMethod::Uniform};

}  // namespace

TEST(Focus, BasicFrameAllMethods) {
  FrameSetup s = basic_setup();
  std::mt19937 rng(1);
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_EQ(m, r.method) << r.reason;
    EXPECT_EQ(FocusFallback::None, r.fallback) << r.reason;
    EXPECT_EQ(LightKind::Point, r.light_kind);  // a sun from above and slightly ahead: a point on the infinity plane
    EXPECT_GT(check_laws(s, r, rng, focus_method_name(m)), 10);
  }
}

TEST(Focus, RandomFramesEveryLightAndMethod) {
  // FOCUS_ITERS / FOCUS_SEED: longer or other runs by hand (4 seeds x 3000 iterations pass).
  std::mt19937 rng(getenv("FOCUS_SEED") ? unsigned(atoi(getenv("FOCUS_SEED"))) : 12345u);
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  int frames = 0, samples = 0;
  for (int iter = 0; iter < (getenv("FOCUS_ITERS") ? atoi(getenv("FOCUS_ITERS")) : 240); ++iter) {
    FrameSetup s;
    P3 centre{u(rng) * 50, u(rng) * 50, u(rng) * 50};
    P3 half{0.5 + 20 * u01(rng), 0.5 + 20 * u01(rng), 0.5 + 20 * u01(rng)};
    s.box = {{centre.x - half.x, centre.y - half.y, centre.z - half.z},
             {centre.x + half.x, centre.y + half.y, centre.z + half.z}};
    P3 eye = centre + P3{u(rng), u(rng), u(rng)} * (norm(half) * 1.5);
    P3 target = centre + P3{u(rng) * half.x, u(rng) * half.y, u(rng) * half.z};
    s.eye[0] = eye.x, s.eye[1] = eye.y, s.eye[2] = eye.z;
    s.target[0] = target.x, s.target[1] = target.y, s.target[2] = target.z;
    s.up[0] = u(rng), s.up[1] = 1, s.up[2] = u(rng);
    s.fovy = 20 + 100 * u01(rng);
    s.aspect = 0.5 + 1.5 * u01(rng);
    s.near_d = std::pow(10.0, -3 + 3 * u01(rng));
    s.far_d = iter % 7 == 0 ? HUGE_VAL : s.near_d * std::pow(10.0, 1 + 4 * u01(rng));
    int type = iter % 3;
    s.light.type = LightType(type);
    P3 dir = unit(P3{u(rng), u(rng), u(rng)});
    s.light.direction[0] = dir.x, s.light.direction[1] = dir.y, s.light.direction[2] = dir.z;
    P3 lp = centre + P3{u(rng), u(rng), u(rng)} * (norm(half) * 3);
    s.light.position[0] = lp.x, s.light.position[1] = lp.y, s.light.position[2] = lp.z;
    if (type == 2) {  // aim most spots at the scene
      P3 aim = unit(centre - lp + P3{u(rng), u(rng), u(rng)} * norm(half) * 0.5);
      s.light.direction[0] = aim.x, s.light.direction[1] = aim.y, s.light.direction[2] = aim.z;
    }
    s.light.outer_cone = 0.1 + 1.3 * u01(rng);
    s.light.range = iter % 5 == 0 ? norm(half) * 4 : 0;
    for (FocusMethod m : kMethods) {
      FocusResult r = run(s, m);
      ASSERT_TRUE(finite16(r.matrix));
      ASSERT_NE(FocusFallback::InvalidInput, r.fallback) << r.reason;
      if (r.fallback != FocusFallback::None) EXPECT_STRNE("", r.reason);
      char what[96];
      std::snprintf(what, sizeof what, "iter %d type %d method %s", iter, type, focus_method_name(m));
      samples += check_laws(s, r, rng, what);
      ++frames;
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(samples, frames * 5);
}

// The hard cases of the issue, each for the three methods.
TEST(Focus, DirectionalParallelToView) {
  std::mt19937 rng(7);
  for (double angle : {0.0, 1e-9, 1e-6, 1e-3, 0.05}) {
    for (int sign : {1, -1}) {
      FrameSetup s = basic_setup();
      P3 v = unit(P3{s.target[0] - s.eye[0], s.target[1] - s.eye[1], s.target[2] - s.eye[2]});
      P3 side = unit(cross(v, P3{0, 1, 0}));
      P3 d = unit(v * std::cos(angle) + side * std::sin(angle)) * sign;
      s.light.direction[0] = d.x, s.light.direction[1] = d.y, s.light.direction[2] = d.z;
      for (FocusMethod m : kMethods) {
        FocusResult r = run(s, m);
        char what[96];
        std::snprintf(what, sizeof what, "angle %g sign %d %s: %s", angle, sign, focus_method_name(m), r.reason);
        check_laws(s, r, rng, what);
        // travelling along the view: from behind the viewer, an inverted point
        EXPECT_EQ(sign > 0 ? LightKind::InvertedPoint : LightKind::Point, r.light_kind) << what;
        if (m == FocusMethod::Lispsm && angle <= 1e-6) {
          EXPECT_EQ(FocusFallback::ParallelLight, r.fallback) << what;
          EXPECT_EQ(FocusMethod::Uniform, r.method);
        }
      }
    }
  }
}

TEST(Focus, PointLightBehindViewerIsInvertedAndShifts) {
  FrameSetup s = basic_setup();
  s.light.type = LightType::Point;
  s.light.position[0] = 1, s.light.position[1] = 4, s.light.position[2] = 15;  // behind the eye (z = 5)
  std::mt19937 rng(3);
  FocusResult r = run(s, FocusMethod::Psm);
  EXPECT_EQ(LightKind::InvertedPoint, r.light_kind);
  EXPECT_GT(r.camera_shift, 0) << "H reaches behind the viewer";
  EXPECT_GT(check_laws(s, r, rng, "psm"), 10);
  for (FocusMethod m : {FocusMethod::Lispsm, FocusMethod::Uniform}) check_laws(s, run(s, m), rng, "other");
}

TEST(Focus, PointLightOnCameraPlaneIsDirectional) {
  FrameSetup s = basic_setup();
  // Camera plane through the eye (0,2,5) perpendicular to the view direction.
  P3 v = unit(P3{0, -0.5, -10});
  P3 side{1, 0, 0};
  P3 up = cross(side, v);
  P3 l = P3{0, 2, 5} + side * 3 + up * 2;  // "miner's lamp"
  s.light.type = LightType::Point;
  s.light.position[0] = l.x, s.light.position[1] = l.y, s.light.position[2] = l.z;
  std::mt19937 rng(4);
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_EQ(LightKind::Directional, r.light_kind);
    check_laws(s, r, rng, focus_method_name(m));
  }
}

// A directional light parallel to the image plane stays directional after
// the perspective (Stamminger and Drettakis 2002, Sect. 3.1: the ideal case, Fig. 3).
TEST(Focus, DirectionalAcrossViewStaysDirectional) {
  FrameSetup s = basic_setup();
  P3 v = unit(P3{s.target[0] - s.eye[0], s.target[1] - s.eye[1], s.target[2] - s.eye[2]});
  P3 d = unit(cross(v, P3{1, 0, 0}));  // perpendicular to the view direction
  if (d.y > 0) d = d * -1;             // shining downwards
  s.light.direction[0] = d.x, s.light.direction[1] = d.y, s.light.direction[2] = d.z;
  std::mt19937 rng(13);
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_EQ(LightKind::Directional, r.light_kind);
    EXPECT_EQ(m, r.method) << r.reason;
    EXPECT_GT(check_laws(s, r, rng, focus_method_name(m)), 10);
  }
}

TEST(Focus, PointLightInsideViewNeedsCubeMap) {
  FrameSetup s = basic_setup();
  s.light.type = LightType::Point;
  s.light.position[0] = 0, s.light.position[1] = 1, s.light.position[2] = -8;  // among the receivers
  std::mt19937 rng(5);
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_TRUE(r.needs_cube_map);
    EXPECT_EQ(FocusFallback::LightInsideView, r.fallback);
    check_laws(s, r, rng, focus_method_name(m));
  }
  // A spot light there is fine: its frustum is one map.
  s.light.type = LightType::Spot;
  s.light.position[1] = 4;
  s.light.outer_cone = 1.0;
  s.light.direction[0] = 0, s.light.direction[1] = -1, s.light.direction[2] = -0.3;
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_FALSE(r.needs_cube_map);
    EXPECT_GT(check_laws(s, r, rng, "spot"), 5);
  }
}

TEST(Focus, ExtremeNearAndFarPlanes) {
  std::mt19937 rng(6);
  for (double near_d : {1e-7, 1e-3}) {
    for (double far_d : {1e2, 1e9, HUGE_VAL}) {
      for (int type = 0; type < 3; ++type) {
        FrameSetup s = basic_setup();
        s.near_d = near_d, s.far_d = far_d;
        s.light.type = LightType(type);
        s.light.position[0] = 5, s.light.position[1] = 20, s.light.position[2] = -5;
        s.light.direction[0] = -0.2, s.light.direction[1] = -1, s.light.direction[2] = -0.1;
        for (FocusMethod m : kMethods) {
          FocusResult r = run(s, m);
          char what[96];
          std::snprintf(what, sizeof what, "near %g far %g type %d %s", near_d, far_d, type, focus_method_name(m));
          EXPECT_GT(check_laws(s, r, rng, what), 5) << what;
        }
      }
    }
  }
}

TEST(Focus, SceneFarFromOrigin) {
  std::mt19937 rng(8);
  for (double offset : {1e4, 1e6}) {
    for (int type = 0; type < 3; ++type) {
      FrameSetup s = basic_setup();
      for (double* p : {s.eye, s.target, s.light.position}) p[0] += offset, p[2] -= offset;
      s.box.min[0] += offset, s.box.max[0] += offset, s.box.min[2] -= offset, s.box.max[2] -= offset;
      s.light.type = LightType(type);
      s.light.position[1] += 25;
      s.light.direction[0] = 0.1, s.light.direction[1] = -1, s.light.direction[2] = -0.4;
      for (FocusMethod m : kMethods) {
        FocusResult r = run(s, m);
        EXPECT_GT(check_laws(s, r, rng, focus_method_name(m)), 5) << "offset " << offset << " type " << type;
      }
    }
  }
}

TEST(Focus, EmptyIntersectionIsStated) {
  FrameSetup s = basic_setup();
  s.box = {{-10, 0, 20}, {10, 5, 40}};  // entirely behind the camera
  for (int type = 0; type < 3; ++type) {
    s.light.type = LightType(type);
    s.light.position[1] = 30;
    for (FocusMethod m : kMethods) {
      FocusResult r = run(s, m);
      EXPECT_EQ(FocusFallback::EmptyFocus, r.fallback);
      EXPECT_TRUE(finite16(r.matrix));
      EXPECT_EQ(0u, r.vertex_count());
    }
  }
}

TEST(Focus, ZeroSizeAndFlatScenes) {
  std::mt19937 rng(9);
  FrameSetup s = basic_setup();
  s.box = {{1, 1, -5}, {1, 1, -5}};  // a point, in view
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_EQ(FocusFallback::DegenerateScene, r.fallback) << r.reason;
    EXPECT_TRUE(finite16(r.matrix));
    check_laws(s, r, rng, "point scene");
  }
  s.box = {{-10, 0, -20}, {10, 0, 0}};  // a flat ground
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_EQ(FocusFallback::DegenerateScene, r.fallback);
    EXPECT_GT(check_laws(s, r, rng, "flat scene"), 5);
  }
}

TEST(Focus, CameraInsideSceneLimitsPsmWarp) {
  FrameSetup s = basic_setup();
  s.box = {{-50, -1, -50}, {50, 10, 50}};  // contains the eye
  std::mt19937 rng(10);
  FocusResult r = run(s, FocusMethod::Psm);
  EXPECT_EQ(FocusMethod::Psm, r.method);
  EXPECT_EQ(FocusFallback::NearLimited, r.fallback);
  EXPECT_GT(r.psm_near, s.near_d);
  check_laws(s, r, rng, "psm");
}

TEST(Focus, InvalidInputGivesIdentity) {
  FrameSetup s = basic_setup();
  s.eye[0] = NAN;
  for (FocusMethod m : kMethods) {
    FocusResult r = run(s, m);
    EXPECT_EQ(FocusFallback::InvalidInput, r.fallback);
    EXPECT_STRNE("", r.reason);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(i % 5 == 0 ? 1.0 : 0.0, r.matrix[i]);
  }
  FrameSetup t = basic_setup();
  t.near_d = 0;  // near must be positive
  EXPECT_EQ(FocusFallback::InvalidInput, run(t, FocusMethod::Psm).fallback);
  FrameSetup d = basic_setup();
  d.light.direction[0] = d.light.direction[1] = d.light.direction[2] = 0;
  EXPECT_EQ(FocusFallback::InvalidInput, run(d, FocusMethod::Uniform).fallback);
}

// LiSPSM's warp fades smoothly to the uniform matrix as the light turns
// towards the view direction: no hard switch.
TEST(Focus, LispsmWarpFadesSmoothly) {
  FrameSetup s = basic_setup();
  P3 v = unit(P3{s.target[0] - s.eye[0], s.target[1] - s.eye[1], s.target[2] - s.eye[2]});
  P3 side = unit(cross(v, P3{0, 1, 0}));
  double prev_gap = HUGE_VAL, prev_n = 0;
  for (double deg = 60; deg > 1e-5; deg *= 0.7) {
    double a = deg * M_PI / 180;
    P3 d = unit(v * std::cos(a) + side * std::sin(a));
    s.light.direction[0] = d.x, s.light.direction[1] = d.y, s.light.direction[2] = d.z;
    FocusResult l = run(s, FocusMethod::Lispsm), u = run(s, FocusMethod::Uniform);
    double gap = 0;
    for (size_t i = 0; i < l.vertex_count(); ++i) {
      double cl[3], cu[3], w;
      P3 p{l.vertices[3 * i], l.vertices[3 * i + 1], l.vertices[3 * i + 2]};
      shadow_coords(l.matrix, p, cl, w);
      shadow_coords(u.matrix, p, cu, w);
      for (int k = 0; k < 2; ++k) gap = std::fmax(gap, std::fabs(cl[k] - cu[k]));
    }
    if (l.method == FocusMethod::Lispsm) {
      EXPECT_GT(l.lispsm_n, prev_n) << "warp distance must grow as the angle shrinks, at " << deg;
      prev_n = l.lispsm_n;
    } else {
      EXPECT_LT(gap, 1e-3) << "the switch to uniform must be invisible, at " << deg;
    }
    EXPECT_LE(gap, prev_gap * 1.05 + 1e-9) << "the warp must weaken monotonically, at " << deg << " degrees";
    prev_gap = gap;
  }
  EXPECT_LT(prev_gap, 1e-3);
}

// Casters and receiver bounds tighten H (and H stays inside them).
TEST(Focus, CastersAndReceiversTighten) {
  FrameSetup s = basic_setup();
  std::vector<float> casters = {-2, 0, -8, 2, 0, -8, -2, 3, -8, 2, 3, -8, -2, 0, -12, 2, 0, -12, -2, 3, -12, 2, 3, -12};
  FocusBox receivers{{-5, 0, -15}, {5, 1, -3}};
  FocusOptions plain, tight;
  tight.casters = positions_of(casters.data(), 8);
  tight.receivers = &receivers;
  for (FocusMethod m : kMethods) {
    FocusResult a = run(s, m, plain), b = run(s, m, tight);
    // No fallback but, at times, the unwarped map where the warp would not help.
    ASSERT_TRUE(b.fallback == FocusFallback::None || b.fallback == FocusFallback::WarpNoGain) << b.reason;
    for (size_t i = 0; i < b.vertex_count(); ++i) {
      P3 p{b.vertices[3 * i], b.vertices[3 * i + 1], b.vertices[3 * i + 2]};
      EXPECT_GE(p.x, -2 - 1e-6);
      EXPECT_LE(p.x, 2 + 1e-6);
      EXPECT_LE(p.y, 3 + 1e-6);
      EXPECT_LE(p.z, -3 + 1e-6);
    }
    EXPECT_GT(a.vertex_count(), 0u);
    EXPECT_GT(b.vertex_count(), 0u);
  }
}

// Without faces (an engine's per-frame call) the matrix is the same map.
TEST(Focus, MatrixOnlyMatchesWithFaces) {
  FrameSetup s = basic_setup();
  for (int type = 0; type < 3; ++type) {
    s.light.type = LightType(type);
    s.light.position[1] = 12;
    for (FocusMethod m : kMethods) {
      FocusOptions with, without;
      without.faces = false;
      FocusResult a = run(s, m, with), b = run(s, m, without);
      EXPECT_EQ(a.method, b.method);
      EXPECT_TRUE(b.face_sizes.empty());
      EXPECT_GE(b.vertex_count(), a.vertex_count());
      for (size_t i = 0; i < a.vertex_count(); ++i) {
        P3 p{a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]};
        double ca[3], cb[3], w;
        shadow_coords(a.matrix, p, ca, w);
        shadow_coords(b.matrix, p, cb, w);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(ca[k], cb[k], 1e-6);
      }
    }
  }
}

TEST(Focus, MatricesFromEngineFloatsMatchLookAt) {
  FrameSetup s = basic_setup();
  CameraMatrices c = s.camera();
  float view[16], proj[16];
  for (int i = 0; i < 16; ++i) view[i] = float(c.view[i]), proj[i] = float(c.projection[i]);
  CameraMatrices f = camera_from_matrices(view, proj);
  FocusResult a, b;
  FocusOptions opt;
  compute_focus(c, s.light, s.box, opt, a);
  compute_focus(f, s.light, s.box, opt, b);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.fallback, b.fallback) << a.reason << " / " << b.reason;
  EXPECT_NEAR(a.psm_near, b.psm_near, 1e-4 * a.psm_near);
  EXPECT_NEAR(a.camera_shift, b.camera_shift, 1e-4 * (1 + a.camera_shift));
  // The same shadow map: H's vertices land on the same texels (the entries
  // themselves may differ more: a far post-perspective light conditions them badly).
  for (size_t i = 0; i < a.vertex_count(); ++i) {
    P3 p{a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]};
    double ca[3], cb[3], w;
    shadow_coords(a.matrix, p, ca, w);
    shadow_coords(b.matrix, p, cb, w);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ca[k], cb[k], 1e-4);
  }
  Light gl;
  gl.type = LightType::Spot;
  gl.position[1] = 7;
  gl.outer_cone = 0.5f;
  // An imported light (geom/scene.h) is compute_focus's input as it is: no conversion.
  const Light& fl = gl;
  EXPECT_EQ(LightType::Spot, fl.type);
  EXPECT_DOUBLE_EQ(7, fl.position[1]);
  EXPECT_NEAR(0.5, fl.outer_cone, 1e-7);
  FocusResult spot;
  EXPECT_TRUE(compute_focus(c, fl, s.box, opt, spot)) << spot.reason;
}

// geombake focus: a frame in, JSON out; bad input: Error: FILE: ..., exit 1.
TEST(FocusCommand, PrintsJsonAndRejectsBadInput) {
  std::string dir = std::string(GEOM_BINARY_DIR) + "/tests";
  std::string geombake = std::string(GEOM_BINARY_DIR) + "/tools/geombake";
  ASSERT_TRUE(std::ifstream(geombake).good()) << geombake << " is not built";
  std::string good = dir + "/focus_frame.json", bad = dir + "/focus_bad.json", out = dir + "/focus_out.txt";
  std::ofstream(good) << R"({"camera": {"eye": [0,2,5], "target": [0,1.5,-5], "up": [0,1,0],
    "fovy_degrees": 60, "aspect": 1.5, "near": 0.1, "far": 100},
    "light": {"type": "spot", "position": [0,10,-5], "direction": [0,-1,0], "spot_angle_degrees": 40},
    "scene_bounds": {"min": [-10,0,-20], "max": [10,5,0]}, "method": "lispsm", "min_warp_gain": 0})";
  ASSERT_EQ(0, std::system((geombake + " focus " + good + " > " + out + " 2>&1").c_str()));
  std::ifstream in(out);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : {"\"method\": \"lispsm\"", "\"fallback\": null", "\"light_kind\": \"point\"",
                          "\"camera_shift\"", "\"focus_vertices\"", "\"matrix\""})
    EXPECT_NE(std::string::npos, text.find(key)) << key << " in " << text;
  std::ofstream(bad) << R"({"camera": {"eye": [0,2,5]}, "light": {"type": "point"}})";
  int rc = std::system((geombake + " focus " + bad + " > " + out + " 2>&1").c_str());
  EXPECT_EQ(1, WEXITSTATUS(rc));
  std::ifstream in2(out);
  std::string err((std::istreambuf_iterator<char>(in2)), std::istreambuf_iterator<char>());
  EXPECT_NE(std::string::npos, err.find("Error: " + bad + ": ")) << err;
  std::ofstream(bad) << "{ not json";
  rc = std::system((geombake + " focus " + bad + " > " + out + " 2>&1").c_str());
  EXPECT_EQ(1, WEXITSTATUS(rc));
}
