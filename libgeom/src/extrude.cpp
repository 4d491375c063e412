// CPU reference of shaders/shadow_volume.vert and shaders/esm_quad.vert (see
// geom/extrude.h). Every per-corner decision and coordinate is computed with
// the same float expressions as the GLSL, in the same order; the finite
// volume of `geombake volume` only replaces the points at infinity.
#include "geom/extrude.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace geom {
namespace {

inline bool front_of(const float* planes, uint32_t index, const float light[4]) {
  return light_in_front(planes + 4 * size_t(index & 0x7fffffffu), light);
}

inline int side_of(const float* planes, uint32_t index, const float light[4]) {
  return light_side(planes + 4 * size_t(index & 0x7fffffffu), light);
}

inline void near_corner(const float v[3], float out[4]) {
  out[0] = v[0];
  out[1] = v[1];
  out[2] = v[2];
  out[3] = 1.0f;
}

// v at infinity: (v * L.w - L.xyz, 0); a corner on the light itself has no
// direction and goes to (0, 0, -1, 0) (see kAtLight in shaders/shadow_volume.vert;
// a guard: the records through a vertex at the light collapse).
inline void far_corner(const float v[3], const float light[4], float out[4]) {
  out[0] = v[0] * light[3] - light[0];
  out[1] = v[1] * light[3] - light[1];
  out[2] = v[2] * light[3] - light[2];
  out[3] = 0.0f;
  if (out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f) out[2] = -1.0f;
}

// The shader's side instance; `base` receives each corner's vertex.
bool side_eval(const SvSide& s, const float* planes, const float light[4], float out[4][4], const float* base[4]) {
  const int sa = side_of(planes, s.plane_a, light);
  const int sb = (s.plane_b & SvSide::kFlip) ? -side_of(planes, s.plane_b, light) : side_of(planes, s.plane_b, light);
  const bool second = s.plane_a & SvSide::kSecond;
  const bool fa = second ? sa >= 0 : sa > 0;
  const bool fb = second ? sb >= 0 : sb > 0;
  if (fa == fb) {
    for (int k = 0; k < 4; ++k) near_corner(s.p0, out[k]);
    return false;
  }
  const float* a = fa ? s.p1 : s.p0;
  const float* b = fa ? s.p0 : s.p1;
  near_corner(a, out[0]);
  near_corner(b, out[1]);
  far_corner(a, light, out[2]);
  far_corner(b, light, out[3]);
  base[0] = base[2] = a;
  base[1] = base[3] = b;
  return true;
}

bool cap_eval(const SvCap& c, const float* planes, const float light[4], float out[6][4], const float* base[6]) {
  const int side = side_of(planes, c.plane, light);
  const bool front = side > 0;
  const bool ds = c.plane & SvCap::kDoubleSided;
  if (side == 0 || (!front && !ds)) {
    for (int k = 0; k < 6; ++k) near_corner(c.a, out[k]);
    return false;
  }
  const float* second = front ? c.b : c.c;
  const float* third = front ? c.c : c.b;
  near_corner(c.a, out[0]);
  near_corner(second, out[1]);
  near_corner(third, out[2]);
  far_corner(c.a, light, out[3]);
  far_corner(third, light, out[4]);
  far_corner(second, light, out[5]);
  base[0] = base[3] = c.a;
  base[1] = base[5] = second;
  base[2] = base[4] = third;
  return true;
}

}  // namespace

void to_local_light(const double origin[3], const double light[4], float out[4]) {
  for (int k = 0; k < 3; ++k) out[k] = float(light[k] - origin[k] * light[3]);
  out[3] = float(light[3]);
}

bool side_corners(const SvSide& s, const float* planes, const float light[4], float out[4][4]) {
  const float* base[4];
  return side_eval(s, planes, light, out, base);
}

bool cap_corners(const SvCap& c, const float* planes, const float light[4], float out[6][4]) {
  const float* base[6];
  return cap_eval(c, planes, light, out, base);
}

std::vector<float> extrude_volume(const ShadowVolume& v, const float light[4], bool caps) {
  std::vector<float> tris;
  const float* planes = v.planes.data();
  float q[6][4];
  auto emit = [&](int a, int b, int c) {
    for (int k : {a, b, c}) tris.insert(tris.end(), q[k], q[k] + 4);
  };
  for (const SvSide& s : v.sides) {
    if (!side_corners(s, planes, light, q)) continue;
    emit(0, 1, 2);
    emit(2, 1, 3);
  }
  if (caps)
    for (const SvCap& c : v.caps) {
      if (!cap_corners(c, planes, light, q)) continue;
      emit(0, 1, 2);
      emit(3, 4, 5);
    }
  return tris;
}

bool esm_corners(const EsmQuad& quad, const float* planes, const float light[4], const float m[16], float extrude_scale,
                 float out[4][4]) {
  float q[3];
  octahedral_decode(quad.q, q);
  const bool fa = front_of(planes, quad.plane_a, light) != bool(quad.plane_a & EsmQuad::kFlip);
  const bool fb = front_of(planes, quad.plane_b, light) != bool(quad.plane_b & EsmQuad::kFlip);
  for (int k = 0; k < 4; ++k) {
    const float* p = (k & 1) ? quad.p1 : quad.p0;
    const bool f = k < 2 ? fa : fb;
    float w = m[3] * p[0];
    w = w + m[7] * p[1];
    w = w + m[11] * p[2];
    w = w + m[15];
    const float len = extrude_scale * w;
    const float offset = f ? len : -0.5f * len;
    for (int j = 0; j < 3; ++j) out[k][j] = p[j] + q[j] * offset;
    out[k][3] = 1.0f;
  }
  return fa != fb;
}

namespace {

// Distance from the origin to triangle abc (Ericson, Real-Time Collision
// Detection 5.1.5, with p = 0).
double origin_triangle_distance(const double a[3], const double b[3], const double c[3]) {
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  double ab[3], ac[3], ap[3], bp[3], cp[3], q[3];
  for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = -a[k], bp[k] = -b[k], cp[k] = -c[k];
  auto at = [&](const double* base, const double* dir, double t) {
    for (int k = 0; k < 3; ++k) q[k] = base[k] + dir[k] * t;
    return std::sqrt(dot(q, q));
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return std::sqrt(dot(a, a));
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return std::sqrt(dot(b, b));
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(a, ab, d1 / (d1 - d3));
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return std::sqrt(dot(c, c));
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(a, ac, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double bc[3];
    for (int k = 0; k < 3; ++k) bc[k] = c[k] - b[k];
    return at(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double den = 1 / (va + vb + vc);
  for (int k = 0; k < 3; ++k) q[k] = a[k] + ab[k] * vb * den + ac[k] * vc * den;
  return std::sqrt(dot(q, q));
}

}  // namespace

VolumeMesh finite_volume(const ShadowVolume& v, const float light[4], const double lo[3], const double hi[3],
                         double distance) {
  VolumeMesh mesh;
  const float* planes = v.planes.data();
  float q[6][4];
  const float* base[6];
  // Where the points at infinity go. Directional light: every corner moves by
  // the same t = box diagonal + distance, so a far cap is its face translated
  // beyond the box. Point light: every corner lands on the sphere of radius rho
  // around the light, rho = (farthest box corner + distance) / c, c the least
  // distance from the centre to a far cap's triangle of unit directions: then
  // every far cap (and every far edge) stays `distance` outside the box.
  const bool point = light[3] != 0.0f;
  double L[3], reach = 0, diag2 = 0;
  for (int k = 0; k < 3; ++k) {
    L[k] = point ? double(light[k]) / light[3] + v.origin[k] : 0.0;
    const double far_side = std::max(std::fabs(lo[k] - L[k]), std::fabs(hi[k] - L[k]));
    reach += far_side * far_side;
    diag2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  }
  reach = std::sqrt(reach);
  auto unit = [](const float c[4], double u[3]) {
    const double n = std::sqrt(double(c[0]) * c[0] + double(c[1]) * c[1] + double(c[2]) * c[2]);
    for (int k = 0; k < 3; ++k) u[k] = c[k] / n;
  };
  double cmin = 1;
  if (point)
    for (const SvCap& c : v.caps) {
      if (!cap_eval(c, planes, light, q, base)) continue;
      double u[3][3];
      for (int i = 0; i < 3; ++i) unit(q[3 + i], u[i]);
      cmin = std::min(cmin, origin_triangle_distance(u[0], u[1], u[2]));
    }
  cmin = std::max(cmin, 1e-3);  // a face seen edge-on from the light (see geom/extrude.h)
  const double rho = (reach + distance) / cmin, shift = std::sqrt(diag2) + distance;

  std::map<std::tuple<double, double, double>, uint32_t> ids;
  auto vertex = [&](const double p[3]) {
    auto key = std::make_tuple(p[0], p[1], p[2]);
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    const uint32_t id = uint32_t(mesh.positions.size() / 3);
    mesh.positions.insert(mesh.positions.end(), {p[0], p[1], p[2]});
    ids.emplace(key, id);
    return id;
  };
  auto place = [&](const float c[4], const float* b, double out[3]) {
    double u[3];
    if (c[3] != 0.0f) {
      for (int k = 0; k < 3; ++k) out[k] = double(c[k]) + v.origin[k];
      return;
    }
    unit(c, u);
    for (int k = 0; k < 3; ++k) out[k] = point ? L[k] + u[k] * rho : double(b[k]) + v.origin[k] + u[k] * shift;
  };
  auto tri = [&](int a, int b, int c) {
    double p[3][3];
    const int ks[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) place(q[ks[i]], base[ks[i]], p[i]);
    for (int i = 0; i < 3; ++i) mesh.indices.push_back(vertex(p[i]));
  };
  for (const SvSide& s : v.sides) {
    if (!side_eval(s, planes, light, q, base)) continue;
    tri(0, 1, 2);
    tri(2, 1, 3);
  }
  for (const SvCap& c : v.caps) {
    if (!cap_eval(c, planes, light, q, base)) continue;
    tri(0, 1, 2);
    tri(3, 4, 5);
  }
  return mesh;
}

}  // namespace geom
