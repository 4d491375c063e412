// Laws of the static shadow volumes (geom/shadow_volume.h) through the CPU
// reference of the GPU extrusion (geom/extrude.h):
//   * for any light, what one light rasterizes is a closed oriented surface
//     (every directed edge matched by its reverse, exactly, corners compared
//     bit for bit) and nothing is NaN;
//   * for any point P, the signed crossing count of a ray from P to infinity
//     (z-fail's count) equals the number of faces the segment P-L crosses
//     (brute force in double), so it is non-zero exactly when P is blocked,
//     checked against an independent ray cast with Embree;
//   * the one-sided variant does the same for lights outside closed meshes;
//   * a per-light volume rasterizes exactly what the generic one does, with
//     fewer records; the finite `geombake volume` mesh is closed and has the
//     same count inside the scene's bounds.
// Closed, open, non-manifold, inconsistent, degenerate and T-junction meshes,
// point and directional lights, lights on a face's plane, grazing, near a
// vertex and very close to a face, and everything again 1e5 from the origin.
//
// Excluded points (stated epsilon): P within 1e-4 x the scene's diagonal of
// the boundary of some face's shadow frustum (the face, or one of its three
// side quads), or of the light. There the answer depends on rounding. Lights
// are kept 5e-6 x the diagonal off the surface (the closest at 1e-5, on either
// side of a face): on the surface itself a face's frustum is decided by
// rounding (geom/shadow_volume.h, "Limits").
#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

#include "geom/extrude.h"
#include "geom/import.h"
#include "geom/pipeline.h"
#include "silhouette_fixtures.h"

namespace {

using fixtures::Mesh;
using V = std::array<double, 3>;
V sub(V a, V b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V add(V a, V b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V mul(V a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(V a, V b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V cross(V a, V b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double norm(V a) { return std::sqrt(dot(a, a)); }

// 4x4 determinant of rows.
double det4(const double* r0, const double* r1, const double* r2, const double* r3) {
  const double* m[4] = {r0, r1, r2, r3};
  auto d3 = [&](int a, int b, int c, int i, int j, int k) {
    return m[a][i] * (m[b][j] * m[c][k] - m[b][k] * m[c][j]) - m[a][j] * (m[b][i] * m[c][k] - m[b][k] * m[c][i]) +
           m[a][k] * (m[b][i] * m[c][j] - m[b][j] * m[c][i]);
  };
  return m[0][0] * d3(1, 2, 3, 1, 2, 3) - m[0][1] * d3(1, 2, 3, 0, 2, 3) + m[0][2] * d3(1, 2, 3, 0, 1, 3) -
         m[0][3] * d3(1, 2, 3, 0, 1, 2);
}
int sgn(double x) { return (x > 0) - (x < 0); }
double det3(const double* a, const double* b, const double* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// Signed crossing count of the ray P + t r (t > 0) with homogeneous triangles
// (w >= 0): the five vectors A, B, C, O = (P, 1), R = (r, 0) are linearly
// dependent; the cones {aA + bB + cC} and {oO + rR} (all weights > 0) meet
// exactly when the dependency's coefficients split as (A, B, C) vs (O, R).
// +1 when the ray leaves through the front (exits), -1 when it enters. Far
// caps (all corners at infinity) are crossed at the ray's own end at infinity.
int winding(const std::vector<float>& tris, V p, V r) {
  const double O[4] = {p[0], p[1], p[2], 1}, R[4] = {r[0], r[1], r[2], 0};
  static const double ca[4] = {0, 0, 0, 1}, cb[4] = {1, 0, 0, 1}, cc[4] = {0, 1, 0, 1}, cr[4] = {0, 0, 1, 0};
  static const int exit_sign = sgn(det4(ca, cb, cc, cr));  // a +z ray leaves a CCW xy triangle
  int count = 0;
  for (size_t t = 0; t + 12 <= tris.size(); t += 12) {
    double A[4], B[4], C[4];
    for (int k = 0; k < 4; ++k) A[k] = tris[t + k], B[k] = tris[t + 4 + k], C[k] = tris[t + 8 + k];
    if (A[3] == 0 && B[3] == 0 && C[3] == 0) {
      // A far cap lies on the plane at infinity: the ray reaches it at (r, 0)
      // when r is inside the cone of A, B, C (Cramer), leaving through it when
      // det(A, B, C) > 0 (the cap's normal (B - A) x (C - A) points along r).
      const int s = sgn(det3(A, B, C));
      if (s != 0 && sgn(det3(R, B, C)) == s && sgn(det3(A, R, C)) == s && sgn(det3(A, B, R)) == s) count += s;
      continue;
    }
    const int sa = sgn(det4(B, C, O, R)), sb = -sgn(det4(A, C, O, R)), sc = sgn(det4(A, B, O, R));
    const int so = -sgn(det4(A, B, C, R)), sr = sgn(det4(A, B, C, O));
    if (sa == 0 || sa != sb || sa != sc || so != -sa || sr != -sa) continue;
    count += sgn(det4(A, B, C, R)) * exit_sign;
  }
  return count;
}

// Point-triangle distance (Ericson, Real-Time Collision Detection 5.1.5).
double point_triangle(V p, V a, V b, V c) {
  V ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(ap);
  V bp = sub(p, b);
  double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(bp);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return norm(sub(p, add(a, mul(ab, d1 / (d1 - d3)))));
  V cp = sub(p, c);
  double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(cp);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return norm(sub(p, add(a, mul(ac, d2 / (d2 - d6)))));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return norm(sub(p, add(b, mul(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))))));
  double denom = 1 / (va + vb + vc);
  return norm(sub(p, add(a, add(mul(ab, vb * denom), mul(ac, vc * denom)))));
}

// Segment [p, q] crosses triangle abc (Moller-Trumbore, double, open segment).
bool segment_crosses(V p, V q, V a, V b, V c) {
  V d = sub(q, p), e1 = sub(b, a), e2 = sub(c, a), h = cross(d, e2);
  double det = dot(e1, h);
  if (std::fabs(det) < 1e-300) return false;
  double inv = 1 / det;
  V s = sub(p, a);
  double u = dot(s, h) * inv;
  if (u < 0 || u > 1) return false;
  V qq = cross(s, e1);
  double v = dot(d, qq) * inv;
  if (v < 0 || u + v > 1) return false;
  double t = dot(e2, qq) * inv;
  return t > 0 && t < 1 - 1e-12;  // a face through a light on the surface: not crossed at the light
}

struct Embree {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = nullptr;
  Embree(const std::vector<V>& verts, const std::vector<uint32_t>& idx) {
    scene = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float* vb =
        static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, verts.size()));
    for (size_t i = 0; i < verts.size(); ++i)
      for (int k = 0; k < 3; ++k) vb[3 * i + k] = float(verts[i][k]);
    unsigned* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, idx.size() / 3));
    std::copy(idx.begin(), idx.end(), ib);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~Embree() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  // Is the segment from p towards the light (point: up to it; directional: to infinity) blocked?
  // short_by: stop that far before a point light (one lying on the surface).
  bool blocked(V p, V l, double w, double short_by = 0) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray{};
    V d = w != 0 ? sub(l, p) : l;
    ray.org_x = float(p[0]), ray.org_y = float(p[1]), ray.org_z = float(p[2]);
    ray.dir_x = float(d[0]), ray.dir_y = float(d[1]), ray.dir_z = float(d[2]);
    ray.tnear = 0;
    ray.tfar = w != 0 ? float(1 - short_by / norm(d)) : INFINITY;
    ray.mask = 0xffffffffu;
    rtcOccluded1(scene, &ctx, &ray);
    return ray.tfar < 0;
  }
};

struct Light {
  V xyz;
  double w;
  std::string what;
};

std::string fmt17(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

struct LawStats {
  int checked = 0, excluded = 0, shadowed = 0;
};

// Checks every law for one mesh, one light, one variant; returns the counts.
// `volume`: the generic volume of `b` when null, else a per-light volume (its
// count then lies between 1 and the number of crossed faces when blocked).
void check_laws(const Mesh& mesh, const fixtures::Baked& b, const Light& light, bool one_sided, std::mt19937& rng,
                LawStats& stats, int points = 250, const geom::ShadowVolume* volume = nullptr,
                const Light* reference = nullptr) {
  SCOPED_TRACE(mesh.name + ", light " + light.what + (one_sided ? ", one-sided" : "") + " at " + fmt17(light.xyz[0]) +
               " " + fmt17(light.xyz[1]) + " " + fmt17(light.xyz[2]) + " " + fmt17(light.w));
  const double* o = b.planes.origin;
  // Mesh in the local frame, double (for the brute force and Embree).
  std::vector<V> verts(b.weld.vertex_count());
  for (size_t i = 0; i < verts.size(); ++i)
    for (int k = 0; k < 3; ++k) verts[i][k] = double(b.weld.positions[3 * i + k]) - o[k];
  const std::vector<uint32_t>& idx = b.weld.indices;
  const Light& ref = reference ? *reference : light;  // the light the brute force and Embree see
  const V L = ref.w != 0 ? sub(ref.xyz, V{o[0], o[1], o[2]}) : ref.xyz;
  const double wl[4] = {light.xyz[0], light.xyz[1], light.xyz[2], light.w};
  float lf[4];
  geom::to_local_light(o, wl, lf);

  const std::vector<float> tris = geom::extrude_volume(volume ? *volume : b.volume, lf, true);
  for (float f : tris) ASSERT_TRUE(std::isfinite(f));
  // Closed: directed corner edges cancel exactly.
  {
    std::map<std::array<float, 8>, int> edges;
    for (size_t t = 0; t < tris.size(); t += 12)
      for (int k = 0; k < 3; ++k) {
        const float* a = &tris[t + 4 * k];
        const float* c = &tris[t + 4 * ((k + 1) % 3)];
        std::array<float, 8> key, rev;
        for (int j = 0; j < 4; ++j) key[j] = a[j], key[4 + j] = c[j], rev[j] = c[j], rev[4 + j] = a[j];
        auto it = edges.find(rev);
        if (it != edges.end() && it->second > 0) {
          if (--it->second == 0) edges.erase(it);
        } else {
          ++edges[key];
        }
      }
    ASSERT_EQ(edges.size(), 0u) << "the volume is not closed";
  }

  // Scene box: the mesh bounds, enlarged, and the light if it is a point.
  V lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const V& v : verts)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  const double diag = norm(sub(hi, lo));
  const double eps = 1e-4 * diag;
  for (int k = 0; k < 3; ++k) {
    double c = 0.5 * (lo[k] + hi[k]), h = 0.75 * (hi[k] - lo[k]) + 0.05 * diag;
    lo[k] = c - h, hi[k] = c + h;
  }
  // Faces with a plane, and their frustum boundaries (for the exclusion).
  std::vector<size_t> live;
  for (size_t f = 0; f < mesh.triangle_count(); ++f)
    if (b.planes.face_plane[f] != geom::FacePlanes::kNone) live.push_back(f);
  const double far = 100 * (diag + (light.w != 0 ? norm(L) : 0));
  auto extrude = [&](V v) {
    V d = light.w != 0 ? sub(v, L) : mul(L, -1.0);
    double n = norm(d);
    return n > 0 ? add(v, mul(d, far / n)) : v;
  };
  auto near_boundary = [&](V p) {
    if (light.w != 0 && norm(sub(p, L)) < eps) return true;
    for (size_t f : live) {
      V a = verts[idx[3 * f]], bb = verts[idx[3 * f + 1]], c = verts[idx[3 * f + 2]];
      if (point_triangle(p, a, bb, c) < eps) return true;
      const V q[3] = {a, bb, c};
      for (int k = 0; k < 3; ++k) {
        V u = q[k], v = q[(k + 1) % 3], u2 = extrude(u), v2 = extrude(v);
        if (point_triangle(p, u, v, v2) < eps || point_triangle(p, u, v2, u2) < eps) return true;
      }
    }
    return false;
  };
  auto front_face = [&](size_t f) {
    V a = verts[idx[3 * f]], bb = verts[idx[3 * f + 1]], c = verts[idx[3 * f + 2]];
    V n = cross(sub(bb, a), sub(c, a));
    return light.w != 0 ? dot(n, sub(L, a)) > 0 : dot(n, L) > 0;
  };

  // A light on the surface: Embree's float ray must not graze the faces at
  // the light, so it stops eps short (points within eps of it are excluded).
  double short_by = 0;
  for (size_t f : live)
    if (ref.w != 0 && point_triangle(L, verts[idx[3 * f]], verts[idx[3 * f + 1]], verts[idx[3 * f + 2]]) < 1e-9 * diag)
      short_by = eps;
  Embree embree(verts, idx);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < points; ++i) {
    V p;
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * u01(rng);
    if (i % 4 == 3 && !live.empty()) {  // just above or below a random face
      size_t f = live[rng() % live.size()];
      V a = verts[idx[3 * f]], bb = verts[idx[3 * f + 1]], c = verts[idx[3 * f + 2]];
      double s = u01(rng), t = u01(rng) * (1 - s);
      V n = cross(sub(bb, a), sub(c, a));
      p = add(add(a, add(mul(sub(bb, a), s), mul(sub(c, a), t))), mul(n, (u01(rng) - 0.5) * 0.05 * diag / norm(n)));
    }
    if (near_boundary(p)) {
      ++stats.excluded;
      continue;
    }
    ++stats.checked;
    const V q = light.w != 0 ? L : add(p, mul(L, 1e3 * (diag + norm(p)) / norm(L)));
    int crossed = 0;
    for (size_t f : live)
      if ((!one_sided || front_face(f)) &&
          segment_crosses(p, q, verts[idx[3 * f]], verts[idx[3 * f + 1]], verts[idx[3 * f + 2]]))
        ++crossed;
    // The winding number of a closed surface does not depend on the ray; a ray
    // that grazes an edge (in double) can miscount, so take the median of three.
    int w3[3];
    for (int& w : w3) w = winding(tris, p, {gauss(rng), gauss(rng), gauss(rng)});
    std::sort(w3, w3 + 3);
    const int count = w3[1];
    const bool blocked = embree.blocked(p, light.w != 0 ? L : light.xyz, light.w, short_by);
    stats.shadowed += blocked;
    if (volume) {
      EXPECT_GE(count, 0);
      EXPECT_LE(count, crossed);
    } else {
      EXPECT_EQ(count, crossed) << "P = " << p[0] << " " << p[1] << " " << p[2];
    }
    EXPECT_EQ(count != 0, blocked) << "P = " << p[0] << " " << p[1] << " " << p[2] << " count " << count;
    if (::testing::Test::HasFailure()) return;
  }
}

// Random and adversarial lights for a mesh (input coordinates).
std::vector<Light> lights_for(const Mesh& m, std::mt19937& rng, bool outside_only) {
  std::vector<Light> out;
  V lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t i = 0; i < m.vertex_count(); ++i)
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], double(m.positions[3 * i + k])), hi[k] = std::max(hi[k], double(m.positions[3 * i + k]));
  const V c = mul(add(lo, hi), 0.5);
  const double diag = norm(sub(hi, lo));
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> u01(0, 1);
  auto unit = [&]() {
    V d = {gauss(rng), gauss(rng), gauss(rng)};
    return mul(d, 1 / norm(d));
  };
  for (int i = 0; i < 4; ++i) out.push_back({add(c, mul(unit(), diag * (0.8 + u01(rng)))), 1, "random point"});
  for (int i = 0; i < 3; ++i) out.push_back({unit(), 0, "random direction"});
  auto vert = [&](uint32_t v) { return V{m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; };
  auto face = [&](size_t f, V& a, V& b, V& cc, V& n) {
    a = vert(m.indices[3 * f]), b = vert(m.indices[3 * f + 1]), cc = vert(m.indices[3 * f + 2]);
    n = cross(sub(b, a), sub(cc, a));
    double l = norm(n);
    if (l > 0) n = mul(n, 1 / l);
    return l > 0;
  };
  for (int tries = 0, made = 0; tries < 50 && made < 2; ++tries) {
    size_t f = rng() % m.triangle_count();
    V a, b, cc, n;
    if (!face(f, a, b, cc, n)) continue;
    ++made;
    V centroid = mul(add(a, add(b, cc)), 1.0 / 3);
    V along = sub(b, a);
    // On the face's plane, outside the face.
    if (!outside_only) out.push_back({add(centroid, mul(along, 1.7)), 1, "on a face's plane"});
    // Grazing: just off the plane, far along it.
    out.push_back({add(add(centroid, mul(along, 2.5)), mul(n, 1e-6 * diag)), 1, "grazing"});
    // Very close to the face, in front of it.
    if (!outside_only) out.push_back({add(centroid, mul(n, 1e-3 * diag)), 1, "very close"});
    if (!outside_only) out.push_back({add(centroid, mul(n, (made == 1 ? 1e-5 : -1e-5) * diag)), 1, "touching"});
    // Near a vertex.
    if (!outside_only) out.push_back({add(a, mul(unit(), 1e-3 * diag)), 1, "near a vertex"});
    // A directional light parallel to the face.
    out.push_back({mul(along, 1 / norm(along)), 0, "directional along a face"});
  }
  {  // a light lying on the surface itself is the limit of two different lights
     // (one per side): keep only lights at least 5e-6 x diagonal off the mesh
    std::vector<Light> kept;
    for (const Light& l : out) {
      double d = HUGE_VAL;
      for (size_t f = 0; l.w != 0 && f < m.triangle_count(); ++f)
        d = std::min(
            d, point_triangle(l.xyz, vert(m.indices[3 * f]), vert(m.indices[3 * f + 1]), vert(m.indices[3 * f + 2])));
      if (d >= 5e-6 * diag) kept.push_back(l);
    }
    out.swap(kept);
  }
  if (outside_only) {  // keep only lights outside the bounding box
    std::vector<Light> kept;
    for (const Light& l : out) {
      bool inside = l.w != 0;
      for (int k = 0; k < 3 && inside; ++k) inside = l.xyz[k] > lo[k] - 1e-3 * diag && l.xyz[k] < hi[k] + 1e-3 * diag;
      if (!inside) kept.push_back(l);
    }
    out.swap(kept);
  }
  return out;
}

std::vector<Mesh> all_meshes() {
  return {fixtures::box(-1, -1, -1, 1, 1, 1),
          fixtures::sphere(12, 7),
          fixtures::torus(12, 8),
          fixtures::sheet(6, 0.3),
          fixtures::open_box(),
          fixtures::book(4),
          fixtures::bowtie(),
          fixtures::flipped_box(),
          fixtures::degenerate_box(),
          fixtures::stack(),
          fixtures::sheet(5, 0.0, 7, 1e-7),
          fixtures::sliver_box()};
}

Light shifted(Light l, double s) {
  if (l.w != 0) l.xyz = add(l.xyz, V{s, -s, s});
  return l;
}

TEST(ShadowVolume, CountEqualsCrossingsAndBlocking) {
  std::mt19937 rng(12345);
  for (double shift : {0.0, 1e5}) {
    for (Mesh m : all_meshes()) {
      const Mesh original = m;
      m.translate(shift, -shift, shift);
      if (shift != 0) m.name += " at 1e5";
      const fixtures::Baked b = fixtures::bake(m);
      LawStats stats;
      for (const Light& l : lights_for(original, rng, false)) {
        check_laws(m, b, shifted(l, shift), false, rng, stats);
        if (::testing::Test::HasFailure()) return;
      }
      EXPECT_GT(stats.shadowed, stats.checked / 20) << m.name;  // the test sees shadow
      EXPECT_LT(stats.excluded, stats.checked / 2) << m.name;   // and excludes little
    }
  }
}

TEST(ShadowVolume, OneSidedClosedMeshesLightsOutside) {
  std::mt19937 rng(777);
  geom::ShadowVolumeOptions one;
  one.one_sided_closed = true;
  for (Mesh m : {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(10, 6), fixtures::torus(10, 7)}) {
    const fixtures::Baked b = fixtures::bake(m, one);
    EXPECT_EQ(b.volume.stats.double_sided_faces, 0u) << m.name;
    LawStats stats;
    for (const Light& l : lights_for(m, rng, true)) {
      check_laws(m, b, l, true, rng, stats);
      if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(stats.checked, 0);
  }
}

// Silhouette loops: the open side quads of a closed mesh, as directed edges
// a -> b (corner 0 -> 1), have in-degree == out-degree at every vertex.
TEST(ShadowVolume, SilhouetteFormsClosedLoops) {
  std::mt19937 rng(99);
  for (Mesh m : {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(16, 9), fixtures::torus(16, 9)}) {
    for (bool one_sided : {false, true}) {
      geom::ShadowVolumeOptions o;
      o.one_sided_closed = one_sided;
      const fixtures::Baked b = fixtures::bake(m, o);
      for (const Light& l : lights_for(m, rng, false)) {
        const double wl[4] = {l.xyz[0], l.xyz[1], l.xyz[2], l.w};
        float lf[4];
        geom::to_local_light(b.planes.origin, wl, lf);
        std::map<std::array<float, 3>, int> degree;
        int open = 0;
        float q[4][4];
        for (const geom::SvSide& s : b.volume.sides) {
          if (!geom::side_corners(s, b.volume.planes.data(), lf, q)) continue;
          ++open;
          ++degree[{q[0][0], q[0][1], q[0][2]}];
          --degree[{q[1][0], q[1][1], q[1][2]}];
        }
        if (l.what.rfind("random", 0) == 0) EXPECT_GT(open, 0) << m.name << " " << l.what;
        for (auto& d : degree) EXPECT_EQ(d.second, 0) << m.name << " " << l.what;
      }
    }
  }
}

// Per-light volumes: fewer records, the same laws (closed surface, count
// non-zero exactly when blocked), one-sided closed components where the light
// is known to be outside (or inside) them.
TEST(ShadowVolume, PerLightVolumes) {
  std::mt19937 rng(5);
  uint64_t one_sided = 0;
  for (const Mesh& m : all_meshes()) {
    const fixtures::Baked b = fixtures::bake(m);
    LawStats stats;
    std::vector<Light> lights = lights_for(m, rng, false);
    lights.push_back({{0.01, 0.02, 0.03}, 1, "at the centre"});  // inside closed meshes
    for (const Light& l : lights) {
      const double wl[4] = {l.xyz[0], l.xyz[1], l.xyz[2], l.w};
      float lf[4];
      geom::to_local_light(b.planes.origin, wl, lf);
      const geom::ShadowVolume lv = geom::build_light_volume(b.volume, lf);
      ASSERT_TRUE(lv.per_light);
      EXPECT_LE(lv.sides.size(), b.volume.sides.size());
      EXPECT_LE(lv.caps.size(), b.volume.caps.size());
      one_sided += lv.stats.light_one_sided;
      check_laws(m, b, l, false, rng, stats, 120, &lv);
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(one_sided, 20u);
  const fixtures::Baked b = fixtures::bake(fixtures::box(0, 0, 0, 1, 1, 1));
  const float zero[4] = {0, 0, 0, 0};
  EXPECT_FALSE(geom::build_light_volume(b.volume, zero).per_light);
  // A light outside a closed box: one-sided, every pair once, 2 front caps.
  const float above[4] = {0.0f, 0.0f, 5.0f, 1.0f};
  const geom::ShadowVolume lv = geom::build_light_volume(b.volume, above);
  EXPECT_EQ(lv.stats.light_one_sided, 1u);
  EXPECT_EQ(lv.sides.size(), 4u);
  EXPECT_EQ(lv.caps.size(), 2u);
  // Inside it: the 10 back-facing triangles, no side open.
  const float inside[4] = {0.1f, 0.2f, 0.3f, 1.0f};
  const geom::ShadowVolume in = geom::build_light_volume(b.volume, inside);
  EXPECT_EQ(in.sides.size(), 0u);
  EXPECT_EQ(in.caps.size(), 12u);
}

// The bundled default scene (glTF, KHR_lights_punctual point and directional
// lights; 27 closed boxes and an open ground): the pipeline emits one exact
// volume per declared light, the laws hold for each, and the report names
// what every rule saved.
TEST(ShadowVolume, DefaultSceneLights) {
  geom::ImportResult r = geom::import_file(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
  ASSERT_TRUE(r.ok) << r.error;
  const std::vector<geom::Light>& lights = r.scene.lights;
  ASSERT_EQ(lights.size(), 2u);
  const geom::Pipeline sb = geom::run_pipeline(geom::positions_of(r.scene.positions.data(), r.scene.vertex_count()),
                                               r.scene.indices.data(), r.scene.triangle_count(), lights);
  const std::string report = geom::silhouette_report(sb);
  for (const char* rule : {"rule coplanar", "rule concave", "rule per-light", "per emitted edge"})
    EXPECT_NE(report.find(rule), std::string::npos) << report;
  EXPECT_EQ(sb.adjacency.size(), 6 * r.scene.triangle_count());
  Mesh m;
  m.name = "default_scene";
  m.positions = r.scene.positions;
  m.indices = r.scene.indices;
  const fixtures::Baked b = fixtures::bake(m);
  std::mt19937 rng(3);
  for (const geom::LightVolume& l : sb.lights) {
    ASSERT_TRUE(l.volume.per_light);
    EXPECT_GT(l.volume.stats.light_one_sided, 20u) << l.light.name;  // the closed boxes
    EXPECT_LT(l.volume.stats.bytes, sb.volume.stats.bytes / 2) << l.light.name;
    LawStats stats;
    double h[4];
    geom::light_homogeneous(l.light, h);
    Light light{{h[0], h[1], h[2]}, h[3], "scene light " + l.light.name};
    check_laws(m, b, light, false, rng, stats, 300, &l.volume);
    EXPECT_GT(stats.shadowed, 10) << stats.checked << " checked, " << stats.excluded << " excluded";
  }
}

// A real game level (OpenArena's aggressor.bsp, Quake 3 IBSP through the
// importer): open, non-manifold (edges with up to 4 faces), inconsistent
// windings, duplicate and collapsed triangles. Lights anywhere in the level.
TEST(ShadowVolume, Quake3Level) {
  const std::string map = "/usr/share/games/openarena/baseoa/pak1-maps.pk3:maps/aggressor.bsp";
  geom::ImportResult r = geom::import_file(map);
  ASSERT_TRUE(r.ok) << r.error;
  Mesh m;
  m.name = "aggressor.bsp";
  m.positions = r.scene.positions;
  m.indices = r.scene.indices;
  const fixtures::Baked b = fixtures::bake(m);
  EXPECT_GT(b.topology.stats.non_manifold_edges, 0u);
  EXPECT_GT(b.topology.stats.inconsistent_edges, 0u);
  std::mt19937 rng(2718);
  std::vector<Light> lights = lights_for(m, rng, false);
  ASSERT_GT(lights.size(), 6u);
  LawStats stats;
  for (size_t i = 0; i < lights.size(); ++i) {
    check_laws(m, b, lights[i], false, rng, stats, 60);
    if (::testing::Test::HasFailure()) return;
    float lf[4];
    const double wl[4] = {lights[i].xyz[0], lights[i].xyz[1], lights[i].xyz[2], lights[i].w};
    geom::to_local_light(b.planes.origin, wl, lf);
    const geom::ShadowVolume lv = geom::build_light_volume(b.volume, lf);
    check_laws(m, b, lights[i], false, rng, stats, 30, &lv);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(stats.shadowed, stats.checked / 20);
  EXPECT_LT(stats.excluded, stats.checked);
}

// The finite mesh of `geombake volume`: closed as an indexed mesh, and its
// crossing count equals the infinite volume's inside the scene's bounds.
TEST(ShadowVolume, FiniteVolumeMatchesInsideBounds) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u01(0, 1);
  for (const Mesh& m : {fixtures::stack(), fixtures::bowtie(), fixtures::sheet(4, 0.2)}) {
    const fixtures::Baked b = fixtures::bake(m);
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < m.vertex_count(); ++i)
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], double(m.positions[3 * i + k])),
        hi[k] = std::max(hi[k], double(m.positions[3 * i + k]));
    for (const Light& l : {Light{{0.3, 4, 0.2}, 1, "above"}, Light{{0.4, 1, 0.3}, 0, "directional"}}) {
      const double wl[4] = {l.xyz[0], l.xyz[1], l.xyz[2], l.w};
      float lf[4];
      geom::to_local_light(b.planes.origin, wl, lf);
      const geom::VolumeMesh vm = geom::finite_volume(b.volume, lf, lo, hi, 1.0);
      ASSERT_FALSE(vm.indices.empty());
      std::map<std::pair<uint32_t, uint32_t>, int> edges;
      for (size_t t = 0; t < vm.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) ++edges[{vm.indices[t + k], vm.indices[t + (k + 1) % 3]}];
      for (auto& e : edges) {
        const std::pair<uint32_t, uint32_t> rev(e.first.second, e.first.first);
        EXPECT_EQ(e.second, edges.count(rev) ? edges.at(rev) : 0) << m.name;
      }
      std::vector<float> finite;  // as homogeneous triangles in the local frame
      for (uint32_t i : vm.indices) {
        for (int k = 0; k < 3; ++k) finite.push_back(float(vm.positions[3 * i + k] - b.planes.origin[k]));
        finite.push_back(1.0f);
      }
      const std::vector<float> infinite = geom::extrude_volume(b.volume, lf, true);
      std::normal_distribution<double> gauss;
      int nonzero = 0;
      for (int i = 0; i < 400; ++i) {
        V p;
        for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * u01(rng) - b.planes.origin[k];
        const V r = {gauss(rng), gauss(rng), gauss(rng)};
        const int a = winding(infinite, p, r), c = winding(finite, p, r);
        nonzero += a != 0;
        EXPECT_EQ(a, c) << m.name << " " << l.what;
      }
      EXPECT_GT(nonzero, 10) << m.name;
    }
  }
}

// Tiny meshes drawn by hand: exact record counts.
//
//   one triangle (0,0,0) (1,0,0) (0,1,0), an open sheet: three boundary edges,
//   three single records (always open), one double-sided cap.
//   a box: 18 edges, 6 of them diagonals between coplanar triangles (skipped),
//   12 pair edges, each stored twice (double-sided multiplicity 2).
TEST(ShadowVolume, TinyMeshRecords) {
  Mesh tri;
  tri.add(0, 0, 0), tri.add(1, 0, 0), tri.add(0, 1, 0);
  tri.tri(0, 1, 2);
  fixtures::Baked b = fixtures::bake(tri);
  EXPECT_EQ(b.volume.sides.size(), 3u);
  EXPECT_EQ(b.volume.stats.single_records, 3u);
  ASSERT_EQ(b.volume.caps.size(), 1u);
  EXPECT_TRUE(b.volume.caps[0].plane & geom::SvCap::kDoubleSided);
  const float below[4] = {0.2f, 0.2f, -1.0f, 1.0f};  // local frame: the triangle is around its box centre
  float q[4][4];
  for (const geom::SvSide& s : b.volume.sides) EXPECT_TRUE(geom::side_corners(s, b.volume.planes.data(), below, q));

  b = fixtures::bake(fixtures::box(0, 0, 0, 1, 1, 1));
  EXPECT_EQ(b.topology.edges.size(), 18u);
  EXPECT_EQ(b.volume.stats.skipped_coplanar, 6u);
  EXPECT_EQ(b.volume.stats.skipped_coplanar_records, 12u);  // double-sided: 2 records each
  EXPECT_EQ(b.volume.stats.pair_edges, 12u);
  EXPECT_EQ(b.volume.sides.size(), 24u);
  EXPECT_EQ(b.volume.caps.size(), 12u);
  EXPECT_EQ(b.planes.plane_count(), 6u);
  geom::ShadowVolumeOptions one;
  one.one_sided_closed = true;
  b = fixtures::bake(fixtures::box(0, 0, 0, 1, 1, 1), one);
  EXPECT_EQ(b.volume.sides.size(), 12u);
  // A light above the top face, outside: 4 silhouette edges, 6 caps... one-sided:
  // front faces are the top only -> 1 face x 2 triangles, 4 open side quads.
  const float above[4] = {0.0f, 0.0f, 5.0f, 1.0f};
  int open = 0, caps = 0;
  float c6[6][4];
  for (const geom::SvSide& s : b.volume.sides) open += geom::side_corners(s, b.volume.planes.data(), above, q);
  for (const geom::SvCap& c : b.volume.caps) caps += geom::cap_corners(c, b.volume.planes.data(), above, c6);
  EXPECT_EQ(open, 4);
  EXPECT_EQ(caps, 2);
}

TEST(ShadowVolume, EmptyMesh) {
  Mesh empty;
  const fixtures::Baked b = fixtures::bake(empty);
  EXPECT_TRUE(b.volume.sides.empty());
  EXPECT_TRUE(b.volume.caps.empty());
  const float l[4] = {0, 1, 0, 1};
  EXPECT_TRUE(geom::extrude_volume(b.volume, l).empty());
}

// Lights exactly on the surface: at every vertex and inside faces (centroids
// and a point near an edge) of closed, open and non-manifold meshes. The faces
// through the light have flat frusta (weight 0, geom/shadow_volume.h), so the
// count equals the faces crossed before the light and is non-zero exactly
// when Embree says blocked, for the generic and the per-light volume, outside
// the band that check_laws excludes around every frustum boundary (the planes
// through the light among them). Before the three-state test these failed.
//   sheet(5, 0.3):  +--+--+   a light at a vertex shared by 6 faces of a
//                   |\ |\ |   gently folded sheet: every record through it
//                   +--L--+   collapses, no corner takes kAtLight
TEST(ShadowVolume, LightOnTheSurfaceCounts) {
  std::mt19937 rng(99);
  for (const Mesh& m : {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(8, 5), fixtures::stack(),
                        fixtures::sheet(5, 0.3), fixtures::open_box(), fixtures::book(4), fixtures::bowtie()}) {
    const fixtures::Baked b = fixtures::bake(m);
    std::vector<Light> spots;
    for (size_t v = 0; v < b.weld.vertex_count(); ++v)
      spots.push_back({{b.weld.positions[3 * v], b.weld.positions[3 * v + 1], b.weld.positions[3 * v + 2]}, 1, "at a vertex"});
    for (size_t f = 0; f < m.triangle_count(); f += 2) {
      V c = {0, 0, 0}, e = {0, 0, 0};
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) {
          const double x = double(m.positions[3 * m.indices[3 * f + k] + j]);
          c[j] += x / 3;
          e[j] += k < 2 ? x * 0.495 : x * 0.01;
        }
      spots.push_back({c, 1, "inside a face"});
      spots.push_back({e, 1, "inside a face near an edge"});
    }
    LawStats stats;
    for (const Light& l : spots) {
      check_laws(m, b, l, false, rng, stats, 40);
      if (::testing::Test::HasFailure()) return;
      const double wl[4] = {l.xyz[0], l.xyz[1], l.xyz[2], 1};
      float lf[4];
      geom::to_local_light(b.planes.origin, wl, lf);
      const geom::ShadowVolume lv = geom::build_light_volume(b.volume, lf);
      check_laws(m, b, l, false, rng, stats, 20, &lv);
      if (::testing::Test::HasFailure()) return;
      // No drawn corner lies on the light: kAtLight is never needed.
      auto at_light = [&](const float* c) { return c[0] == lf[0] && c[1] == lf[1] && c[2] == lf[2]; };
      for (const geom::ShadowVolume* v : {&b.volume, &lv}) {
        float q[6][4];
        for (const geom::SvSide& sd : v->sides)
          if (geom::side_corners(sd, v->planes.data(), lf, q)) ASSERT_FALSE(at_light(q[0]) || at_light(q[1])) << m.name;
        for (const geom::SvCap& cp : v->caps)
          if (geom::cap_corners(cp, v->planes.data(), lf, q))
            ASSERT_FALSE(at_light(q[0]) || at_light(q[1]) || at_light(q[2])) << m.name;
      }
    }
    EXPECT_GT(stats.shadowed, stats.checked / 20) << m.name;
    EXPECT_LT(stats.excluded, stats.checked) << m.name;
  }
}

}  // namespace
