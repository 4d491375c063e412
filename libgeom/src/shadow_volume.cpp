// Static shadow volumes for any mesh (see geom/shadow_volume.h for why the
// stencil counts are right). Seeds: 004_3832d04cb6bd7525.txt section 4, the
// z-fail baseline of 001_0225cc27c0669b01.txt section 5.
#include "geom/shadow_volume.h"

#include <algorithm>
#include <cmath>

#include "live_faces.h"
#include "vec3.h"

namespace geom {
namespace {

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

void put(float out[3], const Float3& p, const double origin[3]) {
  out[0] = float(double(p.x) - origin[0]);
  out[1] = float(double(p.y) - origin[1]);
  out[2] = float(double(p.z) - origin[2]);
}

}  // namespace

ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, const FacePlanes& fp, const ShadowVolumeOptions& options) {
  ShadowVolume sv;
  ShadowVolumeStats& st = sv.stats;
  for (int a = 0; a < 3; ++a) sv.origin[a] = fp.origin[a];
  sv.planes = fp.planes;
  st.edges = topology.edges.size();
  auto has_plane = [&](uint32_t f) { return fp.face_plane[f] != FacePlanes::kNone; };

  // Components over non-degenerate faces; a component is closed (one-sided)
  // when each of its edges has exactly two such faces in opposite directions.
  std::vector<uint32_t> parent(triangle_count);
  for (size_t f = 0; f < triangle_count; ++f) parent[f] = uint32_t(f);
  detail::LiveFaces live;  // the non-degenerate faces of one edge, as edge_faces entries
  std::vector<uint8_t> open_root(triangle_count, 0);
  auto gather = [&](const Edge& e) { live.gather(topology, fp, e); };
  auto is_pair = [&]() { return live.size() == 2 && ((live[0] ^ live[1]) & 1u); };
  std::vector<uint32_t> open_faces;  // a face of each edge that is not a pair: its component is open
  for (const Edge& e : topology.edges) {
    gather(e);
    for (size_t i = 1; i < live.size(); ++i) {
      const uint32_t a = find_root(parent, live[0] >> 1), b = find_root(parent, live[i] >> 1);
      if (a != b) parent[b] = a;
    }
    if (!live.empty() && !is_pair()) open_faces.push_back(live[0] >> 1);
  }
  for (uint32_t f : open_faces) open_root[find_root(parent, f)] = 1;
  // Dense component ids, in face order; which faces are double-sided.
  std::vector<uint32_t> component(triangle_count, FacePlanes::kNone), dense(triangle_count, FacePlanes::kNone);
  std::vector<uint8_t> double_sided(triangle_count, 0);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (!has_plane(uint32_t(f))) {
      ++st.degenerate_faces;
      continue;
    }
    const uint32_t root = find_root(parent, uint32_t(f));
    if (dense[root] == FacePlanes::kNone) {
      dense[root] = uint32_t(sv.component_closed.size());
      sv.component_closed.push_back(!open_root[root]);
    }
    component[f] = dense[root];
    double_sided[f] = !options.one_sided_closed || open_root[root];
    ++(double_sided[f] ? st.double_sided_faces : st.one_sided_faces);
  }
  st.components = sv.component_closed.size();
  for (uint8_t c : sv.component_closed) st.closed_components += c;

  // Side records, in edge order; room for the most (a pair: two records, else
  // one per face), so the buffers never grow.
  // Streamed (options.sides_out), the records go out a piece at a time and
  // only a piece is ever held.
  constexpr size_t kPiece = 4096;
  const bool stream_sides = bool(options.sides_out), stream_caps = bool(options.caps_out);
  uint64_t sides_sent = 0, caps_sent = 0;
  if (stream_sides) {
    sv.sides.reserve(kPiece);
  } else {
    const size_t most = topology.edge_faces.size();  // the sum of those over the edges
    sv.sides.reserve(most);
    sv.side_component.reserve(most);
  }
  const auto send_sides = [&] {
    options.sides_out(sv.sides.data(), sv.sides.size());
    sides_sent += sv.sides.size();
    sv.sides.clear();
  };
  // Each record written in place, field by field (one built aside and copied
  // in stalls on its partly written bytes).
  const auto add_side = [&](const Float3& p0, const Float3& p1, uint32_t plane_a, uint32_t plane_b,
                            uint32_t component_id) {
    SvSide& s = sv.sides.emplace_back();
    put(s.p0, p0, sv.origin);
    put(s.p1, p1, sv.origin);
    s.plane_a = plane_a;
    s.plane_b = plane_b;
    if (!stream_sides)
      sv.side_component.push_back(component_id);
    else if (sv.sides.size() == kPiece)
      send_sides();
  };
  for (const Edge& e : topology.edges) {
    gather(e);
    if (live.empty()) continue;
    st.naive_sides += live.size();
    if (is_pair()) {
      const uint32_t fa = (live[0] & 1u) ? live[1] >> 1 : live[0] >> 1;  // traverses v0 -> v1
      const uint32_t fb = (live[0] & 1u) ? live[0] >> 1 : live[1] >> 1;
      if (fp.face_plane[fa] == fp.face_plane[fb]) {
        ++st.skipped_coplanar;
        st.skipped_coplanar_records += double_sided[fa] ? 2 : 1;
        continue;
      }
      ++st.pair_edges;
      add_side(positions[e.v0], positions[e.v1], fp.face_plane[fa], fp.face_plane[fb], component[fa]);
      if (double_sided[fa])  // multiplicity up to 2: the second copy
        add_side(positions[e.v0], positions[e.v1], fp.face_plane[fa] | SvSide::kSecond, fp.face_plane[fb],
                 component[fa]);
      continue;
    }
    for (uint32_t ef : live) {
      const bool reversed = ef & 1u;
      const uint32_t plane = fp.face_plane[ef >> 1];
      ++st.single_records;
      add_side(positions[reversed ? e.v1 : e.v0], positions[reversed ? e.v0 : e.v1], plane, plane | SvSide::kFlip,
               component[ef >> 1]);
    }
  }

  if (stream_sides) {
    if (!sv.sides.empty()) send_sides();
    std::vector<SvSide>().swap(sv.sides);
  }

  // Caps: every non-degenerate face.
  if (stream_caps) {
    sv.caps.reserve(kPiece);
  } else {
    sv.caps.reserve(triangle_count - st.degenerate_faces);
    sv.cap_component.reserve(triangle_count - st.degenerate_faces);
  }
  const auto send_caps = [&] {
    options.caps_out(sv.caps.data(), sv.caps.size());
    caps_sent += sv.caps.size();
    sv.caps.clear();
  };
  for (size_t f = 0; f < triangle_count; ++f) {
    if (!has_plane(uint32_t(f))) continue;
    SvCap& c = sv.caps.emplace_back();
    put(c.a, positions[indices[3 * f]], sv.origin);
    put(c.b, positions[indices[3 * f + 1]], sv.origin);
    put(c.c, positions[indices[3 * f + 2]], sv.origin);
    c.plane = fp.face_plane[f] | (double_sided[f] ? SvCap::kDoubleSided : 0u);
    if (!stream_caps)
      sv.cap_component.push_back(component[f]);
    else if (sv.caps.size() == kPiece)
      send_caps();
  }
  if (stream_caps) {
    if (!sv.caps.empty()) send_caps();
    std::vector<SvCap>().swap(sv.caps);
  }
  st.sides = sides_sent + sv.sides.size();
  st.caps = caps_sent + sv.caps.size();
  const uint64_t plane_bytes = 16 * uint64_t(sv.planes.size() / 4);
  st.bytes = st.sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + plane_bytes;
  st.naive_bytes = st.naive_sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + plane_bytes;
  return sv;
}

namespace {

using namespace vec3;

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double point_triangle_distance(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  auto lerp = [](Vec3 a, Vec3 d, double t) { return Vec3{a.x + d.x * t, a.y + d.y * t, a.z + d.z * t}; };
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return length(ap);
  const Vec3 bp = p - b;
  const double d3v = dot(ab, bp), d4 = dot(ac, bp);
  if (d3v >= 0 && d4 <= d3v) return length(bp);
  const double vc = d1 * d4 - d3v * d2;
  if (vc <= 0 && d1 >= 0 && d3v <= 0) return length(p - lerp(a, ab, d1 / (d1 - d3v)));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return length(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return length(p - lerp(a, ac, d2 / (d2 - d6)));
  const double va = d3v * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3v) >= 0 && (d5 - d6) >= 0)
    return length(p - lerp(b, c - b, (d4 - d3v) / ((d4 - d3v) + (d5 - d6))));
  const double den = 1 / (va + vb + vc);
  const Vec3 q = lerp(lerp(a, ab, vb * den), ac, vc * den);
  return length(p - q);
}

// Is the light inside the solid bounded by a closed component's faces?
// 1 inside, 0 outside, -1 undecided (too close to a face, or every ray grazed).
int light_inside(const std::vector<const SvCap*>& faces, const float light[4]) {
  double volume = 0, lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const SvCap* c : faces) {
    const Vec3 a = of(c->a), b = of(c->b), cc = of(c->c);
    volume += dot(a, cross(b, cc));
    for (const float* p : {c->a, c->b, c->c})
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
  }
  if (volume == 0) return -1;
  const bool inverted = volume < 0;  // the solid is the unbounded outside (a room seen from within)
  if (light[3] == 0) return inverted ? 1 : 0;
  const Vec3 L = {light[0] / double(light[3]), light[1] / double(light[3]), light[2] / double(light[3])};
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  for (const SvCap* c : faces)
    if (point_triangle_distance(L, of(c->a), of(c->b), of(c->c)) < 1e-6 * diag) return -1;
  static const Vec3 dirs[4] = {
      {0.5773, 0.5775, 0.5773}, {-0.2673, 0.8018, -0.5346}, {0.7071, -0.1, -0.7}, {-0.45, -0.62, 0.64}};
  for (const Vec3& d : dirs) {
    int crossings = 0;
    bool grazing = false;
    for (const SvCap* c : faces) {
      // Moller-Trumbore with a margin: a hit within 1e-9 of an edge is a graze.
      const Vec3 a = of(c->a), e1 = of(c->b) - a, e2 = of(c->c) - a, h = cross(d, e2);
      const double det = dot(e1, h);
      const Vec3 s = L - a, q = cross(s, e1);
      const double u = dot(s, h), v = dot(d, q), t = dot(e2, q);
      if (det == 0) continue;  // the ray is parallel to the face: a graze only if it hits, see below
      const double su = u / det, sv = v / det, st = t / det;
      const double m = 1e-9;
      if (st <= 0 || su < -m || sv < -m || su + sv > 1 + m) continue;
      if (su < m || sv < m || su + sv > 1 - m) {
        grazing = true;
        break;
      }
      ++crossings;
    }
    if (!grazing) return (crossings & 1) != inverted ? 1 : 0;
  }
  return -1;
}

}  // namespace

ShadowVolume build_light_volume(const ShadowVolume& generic, const float light[4]) {
  ShadowVolume lv;
  for (int a = 0; a < 3; ++a) lv.origin[a] = generic.origin[a];
  double n2 = 0;
  for (int k = 0; k < 4; ++k) n2 += double(light[k]) * light[k];
  if (!(n2 > 0) || !std::isfinite(n2)) return lv;
  lv.per_light = true;
  for (int k = 0; k < 4; ++k) lv.light[k] = light[k];
  lv.planes.resize(8);
  for (int k = 0; k < 4; ++k) {
    lv.planes[k] = float(light[k] / n2);
    lv.planes[4 + k] = -lv.planes[k];
  }
  ShadowVolumeStats& st = lv.stats;
  st = generic.stats;
  st.light_one_sided = 0;

  // Where the light is, for each closed component that was stored double-sided.
  const size_t nc = generic.component_closed.size();
  const bool have_ids =
      generic.cap_component.size() == generic.caps.size() && generic.side_component.size() == generic.sides.size();
  std::vector<int> inside(nc, -1);
  if (have_ids) {
    std::vector<std::vector<const SvCap*>> faces(nc);
    for (size_t i = 0; i < generic.caps.size(); ++i)
      if (generic.component_closed[generic.cap_component[i]] && (generic.caps[i].plane & SvCap::kDoubleSided))
        faces[generic.cap_component[i]].push_back(&generic.caps[i]);
    for (size_t c = 0; c < nc; ++c)
      if (!faces[c].empty()) {
        inside[c] = light_inside(faces[c], light);
        st.light_one_sided += inside[c] >= 0;
      }
  }

  const float* planes = generic.planes.data();
  auto side = [&](uint32_t index) { return light_side(planes + 4 * size_t(index & 0x7fffffffu), light); };
  for (size_t i = 0; i < generic.sides.size(); ++i) {
    const SvSide& s = generic.sides[i];
    const int sa = side(s.plane_a), sb = (s.plane_b & SvSide::kFlip) ? -side(s.plane_b) : side(s.plane_b);
    const bool second = s.plane_a & SvSide::kSecond;
    const bool fa = second ? sa >= 0 : sa > 0, fb = second ? sb >= 0 : sb > 0;
    if (fa == fb) continue;
    // A double-sided pair of a closed component treated one-sided: the light
    // outside counts front faces (the first copy's rule), inside back faces
    // (the second copy's rule); the other copy goes.
    if (have_ids && inside[generic.side_component[i]] >= 0 && second != bool(inside[generic.side_component[i]]))
      continue;
    SvSide o = s;
    o.plane_a = fa ? 0 : 1;
    o.plane_b = fb ? 0 : 1;
    lv.sides.push_back(o);
  }
  for (size_t i = 0; i < generic.caps.size(); ++i) {
    const SvCap& c = generic.caps[i];
    const int sc = side(c.plane);
    const bool f = sc > 0;
    const bool ds = c.plane & SvCap::kDoubleSided;
    if (sc == 0 || (!f && !ds)) continue;
    // One-sided closed component: the light outside counts front faces, inside back faces.
    if (ds && have_ids && inside[generic.cap_component[i]] >= 0 && f == bool(inside[generic.cap_component[i]]))
      continue;
    SvCap o = c;
    o.plane = (f ? 0u : 1u) | (ds ? SvCap::kDoubleSided : 0u);
    lv.caps.push_back(o);
  }
  st.sides = lv.sides.size();
  st.caps = lv.caps.size();
  st.bytes = st.sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + 32;
  return lv;
}

}  // namespace geom
