// Static shadow volumes for any mesh (see geom/shadow_volume.h for why the
// stencil counts are right). Arneson n.d. (Real-Time Shadows), Sect. 4, and
// the z-fail baseline of Kenzel 2013, Sect. 5 (Everitt and Kilgard 2002).
//
// One walk over the edge table (double-sided, the default): each edge's live
// faces are gathered once, the components joined (a union-find whose roots
// are each component's smallest face) and the side records written, each
// record's component id holding its face for now. Then one pass over the
// faces numbers the components in face order (in place, in the union-find's
// own array), one over the ids turns faces into components, one writes the
// caps. One-sided closed components need their closedness before their
// pairs' records: a walk joining the components comes first.
#include "geom/shadow_volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "live_faces.h"
#include "vec3.h"

namespace geom {
namespace {

// parent[x] <= x throughout: a root is its component's smallest face.
inline uint32_t find_root(uint32_t* parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

inline void unite(uint32_t* parent, uint32_t a, uint32_t b) {
  a = find_root(parent, a), b = find_root(parent, b);
  if (a < b)
    parent[b] = a;
  else
    parent[a] = b;
}

// The volume; `planes` (fp's plane table, copied or moved) becomes sv.planes.
ShadowVolume build(PositionSpan positions, const uint32_t* indices, size_t triangle_count, const Topology& topology,
                   const FacePlanes& fp, std::vector<float> planes, const ShadowVolumeOptions& options) {
  ShadowVolume sv;
  ShadowVolumeStats& st = sv.stats;
  for (int a = 0; a < 3; ++a) sv.origin[a] = fp.origin[a];
  sv.planes = std::move(planes);
  st.edges = topology.edges.size();
  const uint32_t* face_plane = fp.face_plane.data();
  const bool ids = options.component_ids || options.one_sided_closed;
  // Streamed (options.sides_out, caps_out), the records go out a piece at a
  // time and only a piece is ever held.
  constexpr size_t kPiece = 4096;
  const bool stream_sides = bool(options.sides_out), stream_caps = bool(options.caps_out);
  const bool side_ids = ids && !stream_sides, cap_ids = ids && !stream_caps;
  uint64_t sides_sent = 0, caps_sent = 0;

  // The vertices in the local frame, each converted once (the records copy them).
  std::vector<float> local(3 * positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    const Float3& p = positions[v];
    local[3 * v] = float(double(p.x) - sv.origin[0]);
    local[3 * v + 1] = float(double(p.y) - sv.origin[1]);
    local[3 * v + 2] = float(double(p.z) - sv.origin[2]);
  }
  const float* lp = local.data();

  // Components over non-degenerate faces (a component is closed when each of
  // its edges has exactly two such faces in opposite directions): a
  // union-find, then in the same array each face's dense id, in face order.
  std::vector<uint32_t> component(ids ? triangle_count : 0);
  uint32_t* parent = component.data();
  for (size_t f = 0; f < component.size(); ++f) parent[f] = uint32_t(f);
  std::vector<uint32_t> open_faces;  // a face of each edge that is not a pair: its component is open
  detail::LiveFaces live;            // the non-degenerate faces of one edge, as edge_faces entries
  const auto is_pair = [&]() { return live.size() == 2 && ((live[0] ^ live[1]) & 1u); };
  const auto join = [&]() {  // the gathered edge's faces
    for (size_t i = 1; i < live.size(); ++i) unite(parent, live[0] >> 1, live[i] >> 1);
    if (!is_pair()) open_faces.push_back(live[0] >> 1);
  };
  bool numbered = false;
  const auto number = [&]() {  // a face's parent is never after it: its slot already holds the id
    for (size_t f = 0; f < triangle_count; ++f) {
      if (face_plane[f] == FacePlanes::kNone) continue;
      const uint32_t p = parent[f];
      if (p == f) {
        component[f] = uint32_t(sv.component_closed.size());
        sv.component_closed.push_back(1);
      } else {
        component[f] = component[p];
      }
    }
    for (uint32_t f : open_faces) sv.component_closed[component[f]] = 0;
    std::vector<uint32_t>().swap(open_faces);
    numbered = true;
  };
  const auto double_sided = [&](uint32_t f) { return !options.one_sided_closed || !sv.component_closed[component[f]]; };
  // One-sided, a pair's multiplicity depends on its component's closedness:
  // the components first. Double-sided, they are joined in the records' walk.
  if (options.one_sided_closed) {
    for (const Edge& e : topology.edges) {
      live.gather(topology, fp, e);
      if (!live.empty()) join();
    }
    number();
  }

  // Side records, in edge order; room for the most (a pair: two records, else
  // one per face), so the buffers never grow.
  if (stream_sides) {
    sv.sides.reserve(kPiece);
  } else {
    const size_t most = topology.edge_faces.size();  // the sum of those over the edges
    sv.sides.reserve(most);
    if (side_ids) sv.side_component.reserve(most);
  }
  const auto send_sides = [&] {
    options.sides_out(sv.sides.data(), sv.sides.size());
    sides_sent += sv.sides.size();
    sv.sides.clear();
  };
  // Each record written in place, field by field (one built aside and copied
  // in stalls on its partly written bytes). Its id: the component once
  // numbered, else its face for now.
  const auto add_side = [&](uint32_t v0, uint32_t v1, uint32_t plane_a, uint32_t plane_b, uint32_t face) {
    SvSide& s = sv.sides.emplace_back();
    std::memcpy(s.p0, lp + 3 * size_t(v0), 12);
    std::memcpy(s.p1, lp + 3 * size_t(v1), 12);
    s.plane_a = plane_a;
    s.plane_b = plane_b;
    if (side_ids)
      sv.side_component.push_back(numbered ? component[face] : face);
    else if (stream_sides && sv.sides.size() == kPiece)
      send_sides();
  };
  for (const Edge& e : topology.edges) {
    live.gather(topology, fp, e);
    if (live.empty()) continue;
    st.naive_sides += live.size();
    if (ids && !numbered) join();
    if (is_pair()) {
      const uint32_t fa = (live[0] & 1u) ? live[1] >> 1 : live[0] >> 1;  // traverses v0 -> v1
      const uint32_t fb = (live[0] & 1u) ? live[0] >> 1 : live[1] >> 1;
      const uint32_t pa = face_plane[fa], pb = face_plane[fb];
      const bool ds = double_sided(fa);
      if (pa == pb) {
        ++st.skipped_coplanar;
        st.skipped_coplanar_records += ds ? 2 : 1;
        continue;
      }
      ++st.pair_edges;
      add_side(e.v0, e.v1, pa, pb, fa);
      if (ds) add_side(e.v0, e.v1, pa | SvSide::kSecond, pb, fa);  // multiplicity up to 2: the second copy
      continue;
    }
    for (uint32_t ef : live) {
      const bool reversed = ef & 1u;
      const uint32_t plane = face_plane[ef >> 1];
      ++st.single_records;
      add_side(reversed ? e.v1 : e.v0, reversed ? e.v0 : e.v1, plane, plane | SvSide::kFlip, ef >> 1);
    }
  }
  if (stream_sides) {
    if (!sv.sides.empty()) send_sides();
    std::vector<SvSide>().swap(sv.sides);
  }
  if (ids && !numbered) {
    number();
    for (uint32_t& id : sv.side_component) id = component[id];  // faces to components
  }
  st.components = sv.component_closed.size();
  for (uint8_t c : sv.component_closed) st.closed_components += c;

  // Caps: every non-degenerate face.
  if (stream_caps) {
    sv.caps.reserve(kPiece);
  } else {
    const size_t caps = triangle_count - std::min<uint64_t>(fp.degenerate_faces, triangle_count);
    sv.caps.reserve(caps);
    if (cap_ids) sv.cap_component.reserve(caps);
  }
  const auto send_caps = [&] {
    options.caps_out(sv.caps.data(), sv.caps.size());
    caps_sent += sv.caps.size();
    sv.caps.clear();
  };
  for (size_t f = 0; f < triangle_count; ++f) {
    if (face_plane[f] == FacePlanes::kNone) {
      ++st.degenerate_faces;
      continue;
    }
    SvCap& c = sv.caps.emplace_back();
    const uint32_t* v = indices + 3 * f;
    std::memcpy(c.a, lp + 3 * size_t(v[0]), 12);
    std::memcpy(c.b, lp + 3 * size_t(v[1]), 12);
    std::memcpy(c.c, lp + 3 * size_t(v[2]), 12);
    const bool ds = double_sided(uint32_t(f));
    c.plane = face_plane[f] | (ds ? SvCap::kDoubleSided : 0u);
    ++(ds ? st.double_sided_faces : st.one_sided_faces);
    if (cap_ids)
      sv.cap_component.push_back(component[f]);
    else if (stream_caps && sv.caps.size() == kPiece)
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

}  // namespace

ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, const FacePlanes& fp, const ShadowVolumeOptions& options) {
  return build(positions, indices, triangle_count, topology, fp, fp.planes, options);
}

ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, FacePlanes&& fp, const ShadowVolumeOptions& options) {
  std::vector<float> planes = std::move(fp.planes);
  return build(positions, indices, triangle_count, topology, fp, std::move(planes), options);
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
