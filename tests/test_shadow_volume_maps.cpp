// The shadow-volume law (geom/shadow_volume.h) on OpenArena's real maps, with
// Embree's occlusion ray as the blocked oracle.
#include <gtest/gtest.h>

#include "quake3_fixtures.h"

using namespace geom;
using namespace q3test;

// ---------------------------------------------------------------------------
// The shadow-volume law on real maps:
// for a point light inside the level, a point P is inside the volume (its
// stencil count is non-zero) exactly when the segment from P to the light is
// blocked. The count is that of depth-fail: the volume triangles that
// geom::extrude_volume rasterizes (homogeneous, corners at infinity with
// w = 0), crossed by the view ray from a camera E through P beyond P, up to
// and including its point at infinity, back faces +1 and front faces -1.
// Computed exactly as a cone intersection in R^4 (long double minors): the
// ray beyond P is the cone {aP + bQ, a, b >= 0} with Q = (P - E, 0), a triangle
// the cone {sum c_i V_i, c_i >= 0}; they meet when the null vector of the 4x5
// matrix [P Q V0 V1 V2] has signs (+ + - - -) or (- - + + +). Two cameras must
// give the same count (the volume is closed). The blocked oracle is Embree's
// occlusion ray on the imported triangles; samples whose answer changes when P
// moves by 1/20 unit (on a shadow boundary), or whose minors are too small to
// trust, are skipped and counted; the oracle's segment stops 1/100 unit short
// of the light. Lights: the maps' own spawn points (info_player_deathmatch),
// 40 units above the floor, and a hard case: a light exactly on the plane of
// axis-aligned walls, outside them; and lights exactly at a map vertex or
// inside a face (oa_dm1 (320, 1412, -48) and (320, 1416, -80), oa_ctf2
// (1832, 891.75, 232)): the faces through the light have flat frusta and
// collapse (geom/shadow_volume.h); before that rule these gave counts that
// differ between cameras or miss blocked points.
namespace {

using LD = double;

LD det3(const LD* a, const LD* b, const LD* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}
// Determinant of the 4x4 matrix whose columns are a, b, c, d.
LD det4(const LD* a, const LD* b, const LD* c, const LD* d) {
  const LD* col[4] = {a, b, c, d};
  LD sum = 0;
  for (int j = 0; j < 4; ++j) {  // expand along row 3 (w)
    if (col[j][3] == 0) continue;
    LD m[3][3];
    for (int k = 0, c2 = 0; k < 4; ++k)
      if (k != j) {
        for (int r = 0; r < 3; ++r) m[c2][r] = col[k][r];
        ++c2;
      }
    const LD minor = det3(m[0], m[1], m[2]);
    sum += ((3 + j) % 2 ? -1 : 1) * col[j][3] * minor;
  }
  return sum;
}
LD norm4(const LD* a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]); }

// Plucker coordinates of the line through 4-vectors a and b: L_ij = a_i b_j - a_j b_i
// for ij = 01, 02, 03, 12, 13, 23; det4(a, b, c, d) = plucker_dot(L(a, b), L(c, d)).
using Plucker = std::array<LD, 6>;
Plucker plucker(const LD* a, const LD* b) {
  return {a[0] * b[1] - a[1] * b[0], a[0] * b[2] - a[2] * b[0], a[0] * b[3] - a[3] * b[0],
          a[1] * b[2] - a[2] * b[1], a[1] * b[3] - a[3] * b[1], a[2] * b[3] - a[3] * b[2]};
}
LD plucker_dot(const Plucker& x, const Plucker& y) {
  return x[0] * y[5] - x[1] * y[4] + x[2] * y[3] + x[3] * y[2] - x[4] * y[1] + x[5] * y[0];
}
LD norm6(const Plucker& x) {
  LD s = 0;
  for (LD c : x) s += c * c;
  return std::sqrt(s);
}

struct VolumeTriangle {
  LD v[3][4];
  LD h[4];  // h . X = det4(v0, v1, v2, X)
  LD h_norm;
  Plucker edge[3];  // L(v1, v2), L(v0, v2), L(v0, v1)
  LD edge_norm[3];
  bool at_infinity;
};

std::vector<VolumeTriangle> volume_triangles(const std::vector<float>& tris) {
  std::vector<VolumeTriangle> out(tris.size() / 12);
  for (size_t t = 0; t < out.size(); ++t) {
    VolumeTriangle& vt = out[t];
    vt.at_infinity = true;
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 4; ++k) vt.v[j][k] = tris[12 * t + 4 * size_t(j) + size_t(k)];
      vt.at_infinity = vt.at_infinity && vt.v[j][3] == 0;
    }
    for (int k = 0; k < 4; ++k) {
      LD e[4] = {0, 0, 0, 0};
      e[k] = 1;
      vt.h[k] = det4(vt.v[0], vt.v[1], vt.v[2], e);
    }
    vt.h_norm = norm4(vt.h);
    vt.edge[0] = plucker(vt.v[1], vt.v[2]), vt.edge[1] = plucker(vt.v[0], vt.v[2]),
    vt.edge[2] = plucker(vt.v[0], vt.v[1]);
    for (int j = 0; j < 3; ++j) vt.edge_norm[j] = norm6(vt.edge[j]);
  }
  return out;
}

// The sign of h . X on the outward side of a counter-clockwise triangle.
int outward_sign() {
  std::vector<float> t = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1};
  VolumeTriangle vt = volume_triangles(t)[0];
  return vt.h[2] + vt.h[3] > 0 ? 1 : -1;  // X = (0, 0, 1, 1), above the +z front
}

// Depth-fail count at p (local frame) seen from camera e; false when a minor
// that decides a crossing is too close to zero to trust.
bool stencil_count(const std::vector<VolumeTriangle>& vol, const LD p[4], const LD e[4], int& count) {
  static const int out_sign = outward_sign();
  const LD q[4] = {p[0] - e[0], p[1] - e[1], p[2] - e[2], 0};
  const LD np = norm4(p), nq = norm4(q);
  const Plucker pq = plucker(p, q);
  const LD npq = norm6(pq);
  const LD eps = 1e-13L;
  count = 0;
  for (const VolumeTriangle& vt : vol) {
    if (vt.h_norm == 0) continue;  // no area: never crossed
    const LD hp = vt.h[0] * p[0] + vt.h[1] * p[1] + vt.h[2] * p[2] + vt.h[3] * p[3];
    const LD hq = vt.h[0] * q[0] + vt.h[1] * q[1] + vt.h[2] * q[2];
    const bool hp_tiny = std::fabs(hp) <= eps * vt.h_norm * np, hq_tiny = std::fabs(hq) <= eps * vt.h_norm * nq;
    bool crossed;
    if (vt.at_infinity) {
      // Q (the ray's end) inside the far triangle's cone of directions.
      const LD s = det3(vt.v[0], vt.v[1], vt.v[2]);
      const LD t0 = det3(q, vt.v[1], vt.v[2]), t1 = det3(vt.v[0], q, vt.v[2]), t2 = det3(vt.v[0], vt.v[1], q);
      const LD t[3] = {t0, t1, t2};
      int pos = 0, neg = 0, tiny = 0;
      for (int j = 0; j < 3; ++j) {
        const LD tol = eps * nq * vt.edge_norm[j];
        (std::fabs(t[j]) <= tol ? tiny : t[j] > 0 ? pos : neg)++;
      }
      if (pos && neg) continue;
      if (tiny) {
        return false;
      }
      crossed = (pos == 3) == (s > 0);
    } else {
      if (!hp_tiny && !hq_tiny && (hp > 0) == (hq > 0)) continue;  // P and Q on one side of its plane
      // Null vector of [P Q V0 V1 V2]: (-h.Q, h.P, det(P,Q,V1,V2), -det(P,Q,V0,V2), det(P,Q,V0,V1)).
      const LD n[3] = {plucker_dot(pq, vt.edge[0]), -plucker_dot(pq, vt.edge[1]), plucker_dot(pq, vt.edge[2])};
      int pos = 0, neg = 0, tiny = 0;
      for (int j = 0; j < 3; ++j) (std::fabs(n[j]) <= eps * npq * vt.edge_norm[j] ? tiny : n[j] > 0 ? pos : neg)++;
      if (pos && neg) continue;  // the line misses the triangle
      if (tiny) {
        return false;
      }
      if (hp_tiny || hq_tiny) {  // the line goes through the triangle, P (or Q) almost on it
        return false;
      }
      const bool sigma = pos == 3;
      crossed = (hp > 0) != sigma;  // n_P = -h.Q and n_Q = h.P (equal signs here) opposite to the edges' sign
    }
    if (!crossed) continue;
    const LD he = vt.h[0] * e[0] + vt.h[1] * e[1] + vt.h[2] * e[2] + vt.h[3] * e[3];
    const bool front = (he > 0 ? 1 : -1) == out_sign;
    count += front ? -1 : 1;
  }
  return true;
}

struct Occluder {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit Occluder(const Scene& s) {
    device = rtcNewDevice("threads=1");
    scene = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, s.vertex_count()));
    std::memcpy(v, s.positions.data(), s.positions.size() * 4);
    auto* i = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, s.triangle_count()));
    std::memcpy(i, s.indices.data(), s.indices.size() * 4);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~Occluder() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  bool blocked(const double p[3], const double l[3]) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray{};
    ray.org_x = float(p[0]), ray.org_y = float(p[1]), ray.org_z = float(p[2]);
    ray.dir_x = float(l[0] - p[0]), ray.dir_y = float(l[1] - p[1]), ray.dir_z = float(l[2] - p[2]);
    const double length = std::hypot(l[0] - p[0], l[1] - p[1], l[2] - p[2]);
    ray.tnear = 0, ray.tfar = float(1 - 0.01 / length), ray.mask = 0xffffffffu;  // stop 1/100 unit short of the light
    rtcOccluded1(scene, &ctx, &ray);
    return ray.tfar < 0;
  }
};

// Spawn points of a map (entities lump), as "x y z".
std::vector<std::array<double, 3>> spawn_points(const RawBsp& raw) {
  const std::string text(reinterpret_cast<const char*>(raw.bytes.data()) + raw.lump_offset(0),
                         size_t(raw.lump_length(0)));
  std::vector<std::array<double, 3>> out;
  size_t at = 0;
  while ((at = text.find('{', at)) != std::string::npos) {
    const size_t end = text.find('}', at);
    const std::string block = text.substr(at, end - at);
    at = end;
    if (block.find("\"info_player_deathmatch\"") == std::string::npos) continue;
    const size_t o = block.find("\"origin\"");
    if (o == std::string::npos) continue;
    std::array<double, 3> p;
    if (std::sscanf(block.c_str() + o + 8, " \"%lf %lf %lf\"", &p[0], &p[1], &p[2]) == 3) out.push_back(p);
  }
  return out;
}

// How many triangles have `l` on their plane (within 1/1000 unit), and how
// many of those contain it.
struct PlaneContact {
  size_t on_plane = 0, on_face = 0;
};
PlaneContact plane_contact(const Scene& s, const std::array<double, 3>& l) {
  PlaneContact c;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const float* v[3];
    for (int j = 0; j < 3; ++j) v[j] = &s.positions[3 * size_t(s.indices[3 * t + size_t(j)])];
    auto cross = [](const double* a, const double* b, double* o) {
      o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
    };
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; ++k) e1[k] = double(v[1][k]) - v[0][k], e2[k] = double(v[2][k]) - v[0][k];
    cross(e1, e2, n);
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nn == 0) continue;
    const double dist = (n[0] * (l[0] - v[0][0]) + n[1] * (l[1] - v[0][1]) + n[2] * (l[2] - v[0][2])) / nn;
    if (std::fabs(dist) > 1e-3) continue;
    ++c.on_plane;
    bool inside = true;
    for (int j = 0; j < 3; ++j) {
      double e[3], f[3], x[3];
      for (int k = 0; k < 3; ++k) e[k] = double(v[(j + 1) % 3][k]) - v[j][k], f[k] = l[size_t(k)] - v[j][k];
      cross(e, f, x);
      inside = inside && x[0] * n[0] + x[1] * n[1] + x[2] * n[2] >= -1e-6 * nn * nn;
    }
    c.on_face += inside;
  }
  return c;
}

struct LawStats {
  size_t checked = 0, blocked = 0, skipped = 0, violations = 0;
};

void check_law(const ShadowVolume& volume, const std::array<double, 3>& light, std::mt19937& rng, const double lo[3],
               const double hi[3], size_t samples, LawStats& st, const Occluder& occluder, bool report = true) {
  const double light4[4] = {light[0], light[1], light[2], 1};
  float local_light[4];
  to_local_light(volume.origin, light4, local_light);
  const std::vector<VolumeTriangle> vol = volume_triangles(extrude_volume(volume, local_light, true));
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  for (size_t k = 0; k < samples; ++k) {
    double p[3];
    for (int a = 0; a < 3; ++a)  // half near the light, half anywhere in the level's box
      p[a] = k % 2 ? light[size_t(a)] + (u(rng) - 0.5) * 512 : lo[a] + (hi[a] - lo[a]) * u(rng);
    const bool blocked = occluder.blocked(p, light.data());
    bool boundary = false;
    for (int j = 0; j < 3 && !boundary; ++j) {
      double d[3] = {g(rng), g(rng), g(rng)}, n = std::hypot(d[0], d[1], d[2]);
      double pj[3] = {p[0] + d[0] / n / 20, p[1] + d[1] / n / 20, p[2] + d[2] / n / 20};
      boundary = occluder.blocked(pj, light.data()) != blocked;
    }
    int counts[2];
    bool trusted = !boundary;
    for (int c = 0; c < 2 && trusted; ++c) {
      LD lp[4] = {p[0] - volume.origin[0], p[1] - volume.origin[1], p[2] - volume.origin[2], 1};
      LD le[4] = {lo[0] - volume.origin[0] + (hi[0] - lo[0]) * u(rng) + 3000 * g(rng),
                  lo[1] - volume.origin[1] + (hi[1] - lo[1]) * u(rng) + 3000 * g(rng),
                  lo[2] - volume.origin[2] + (hi[2] - lo[2]) * u(rng), 1};
      trusted = stencil_count(vol, lp, le, counts[c]);
    }
    if (!trusted) {
      ++st.skipped;
      continue;
    }
    ++st.checked;
    st.blocked += blocked;
    const bool ok = counts[0] == counts[1] && (counts[0] != 0) == blocked;
    if (!ok && st.violations++ < 5 && report)
      ADD_FAILURE() << "P = (" << p[0] << ", " << p[1] << ", " << p[2] << "), light (" << light[0] << ", " << light[1]
                    << ", " << light[2] << "): counts " << counts[0] << " and " << counts[1] << ", Embree says "
                    << (blocked ? "blocked" : "lit");
  }
}

}  // namespace

TEST(Quake3ShadowVolume, LawOnRealMaps) {
  std::mt19937 rng(2004);
  for (const char* map : {"oa_dm1.bsp", "oa_ctf2.bsp"}) {
    SCOPED_TRACE(map);
    const RawBsp raw = raw_map(map);
    ImportResult r = import_bytes(map, raw.bytes, 3);
    ASSERT_TRUE(r.ok) << r.error;
    const Scene& s = r.scene;
    WeldResult w = weld(positions_of(s.positions.data(), s.vertex_count()), s.indices.data(), s.indices.size());
    const PositionSpan wp = positions_of(w.positions.data(), w.vertex_count());
    Topology topo = build_topology(wp, w.indices.data(), s.triangle_count());
    FacePlanes planes = compute_face_planes(wp, w.indices.data(), s.triangle_count(), topo);
    ShadowVolume generic = build_shadow_volume(wp, w.indices.data(), s.triangle_count(), topo, planes);
    ShadowVolumeOptions one_sided_options;
    one_sided_options.one_sided_closed = true;  // the lights float in the open: outside every closed solid
    ShadowVolume one_sided =
        build_shadow_volume(wp, w.indices.data(), s.triangle_count(), topo, planes, one_sided_options);
    Occluder occluder(s);
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
    for (size_t v = 0; v < s.vertex_count(); ++v)
      for (int a = 0; a < 3; ++a)
        lo[a] = std::min(lo[a], double(s.positions[3 * v + size_t(a)])),
        hi[a] = std::max(hi[a], double(s.positions[3 * v + size_t(a)]));
    std::vector<std::array<double, 3>> lights = spawn_points(raw);
    ASSERT_GE(lights.size(), 3u);
    lights.resize(3);
    for (auto& l : lights) l[2] += 40;  // spawn origins are 24 units above the floor; lights float above
    // Hard case: a light exactly on the plane of some faces (x = a vertex's x,
    // the plane of axis-aligned walls), outside all of them.
    std::vector<float> xs;
    for (size_t v = 0; v < s.vertex_count(); ++v) xs.push_back(s.positions[3 * v]);
    std::sort(xs.begin(), xs.end(),
              [&](float a, float b) { return std::fabs(a - lights[0][0]) < std::fabs(b - lights[0][0]); });
    bool placed = false;
    for (size_t i = 0; i < xs.size() && !placed; ++i) {
      std::array<double, 3> l = lights[0];
      l[0] = xs[i];
      const PlaneContact c = plane_contact(s, l);
      if (c.on_plane > 0 && c.on_face == 0) lights.push_back(l), placed = true;
    }
    ASSERT_TRUE(placed);
    // Lights on the surface: at a vertex, inside a face.
    const std::vector<std::array<double, 3>> on_surface =
        std::string(map) == "oa_dm1.bsp" ? std::vector<std::array<double, 3>>{{320, 1412, -48}, {320, 1416, -80}}
                                         : std::vector<std::array<double, 3>>{{1832, 891.75, 232}};
    for (const auto& l : on_surface) {
      EXPECT_GT(plane_contact(s, l).on_face, 0u) << l[0] << " " << l[1] << " " << l[2];
      lights.push_back(l);
    }
    LawStats st;
    for (size_t i = 0; i < lights.size(); ++i) {
      const auto& light = lights[i];
      check_law(generic, light, rng, lo, hi, 100, st, occluder);
      // One-sided closed solids need the light strictly outside them; a light
      // on a solid's surface is not (geom/shadow_volume.h, "Limits").
      if (i + on_surface.size() < lights.size()) check_law(one_sided, light, rng, lo, hi, 40, st, occluder);
      float local[4];
      const double l4[4] = {light[0], light[1], light[2], 1};
      to_local_light(generic.origin, l4, local);
      check_law(build_light_volume(generic, local), light, rng, lo, hi, 40, st, occluder);
    }
    std::printf("%s: %zu points checked (%zu in shadow), %zu skipped on shadow boundaries or by rounding\n", map,
                st.checked, st.blocked, st.skipped);
    EXPECT_EQ(st.violations, 0u);
    EXPECT_GT(st.blocked, st.checked / 10);
    EXPECT_LT(st.blocked, st.checked * 95 / 100);
    EXPECT_LT(st.skipped * 10, st.checked + st.skipped);

    // The check can fail: a volume missing its caps, or one side in five, breaks the law.
    ShadowVolume no_caps = generic, holes = generic;
    no_caps.caps.clear();
    holes.sides.clear();
    for (size_t i = 0; i < generic.sides.size(); ++i)
      if (i % 5) holes.sides.push_back(generic.sides[i]);
    for (const ShadowVolume* broken : {&no_caps, &holes}) {
      LawStats bs;
      check_law(*broken, lights[0], rng, lo, hi, 60, bs, occluder, false);
      EXPECT_GT(bs.violations, 0u);
    }
  }
}
