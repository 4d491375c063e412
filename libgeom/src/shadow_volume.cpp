// Static shadow volumes for any mesh (see geom/shadow_volume.h for why the
// stencil counts are right). Seeds: 004_3832d04cb6bd7525.txt section 4, the
// z-fail baseline of 001_0225cc27c0669b01.txt section 5.
#include "geom/shadow_volume.h"

#include <cmath>

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
                                 const Topology& topology, const FacePlanes& fp,
                                 const ShadowVolumeOptions& options) {
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
  std::vector<uint32_t> live;  // the non-degenerate faces of one edge, as edge_faces entries
  std::vector<uint8_t> open_root(triangle_count, 0);
  auto gather = [&](const Edge& e) {
    live.clear();
    for (uint32_t i = 0; i < e.face_count; ++i) {
      const uint32_t ef = topology.edge_faces[e.first + i];
      if (has_plane(ef >> 1)) live.push_back(ef);
    }
  };
  auto is_pair = [&]() { return live.size() == 2 && ((live[0] ^ live[1]) & 1u); };
  for (const Edge& e : topology.edges) {
    gather(e);
    for (size_t i = 1; i < live.size(); ++i) {
      const uint32_t a = find_root(parent, live[0] >> 1), b = find_root(parent, live[i] >> 1);
      if (a != b) parent[b] = a;
    }
  }
  for (const Edge& e : topology.edges) {
    gather(e);
    if (!live.empty() && !is_pair()) open_root[find_root(parent, live[0] >> 1)] = 1;
  }
  std::vector<uint8_t> double_sided(triangle_count, 0);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (!has_plane(uint32_t(f))) {
      ++st.degenerate_faces;
      continue;
    }
    double_sided[f] = !options.one_sided_closed || open_root[find_root(parent, uint32_t(f))];
    ++(double_sided[f] ? st.double_sided_faces : st.one_sided_faces);
  }

  // Side records, in edge order.
  sv.sides.reserve(topology.edges.size());
  for (const Edge& e : topology.edges) {
    gather(e);
    if (live.empty()) continue;
    st.naive_sides += live.size();
    if (is_pair()) {
      const uint32_t fa = (live[0] & 1u) ? live[1] >> 1 : live[0] >> 1;  // traverses v0 -> v1
      const uint32_t fb = (live[0] & 1u) ? live[0] >> 1 : live[1] >> 1;
      if (fp.face_plane[fa] == fp.face_plane[fb]) {
        ++st.skipped_coplanar;
        continue;
      }
      SvSide s;
      put(s.p0, positions[e.v0], sv.origin);
      put(s.p1, positions[e.v1], sv.origin);
      s.plane_a = fp.face_plane[fa];
      s.plane_b = fp.face_plane[fb];
      ++st.pair_edges;
      sv.sides.push_back(s);
      if (double_sided[fa]) sv.sides.push_back(s);  // multiplicity 2
      continue;
    }
    for (uint32_t ef : live) {
      SvSide s;
      const bool reversed = ef & 1u;
      put(s.p0, positions[reversed ? e.v1 : e.v0], sv.origin);
      put(s.p1, positions[reversed ? e.v0 : e.v1], sv.origin);
      s.plane_a = fp.face_plane[ef >> 1];
      s.plane_b = s.plane_a | SvSide::kFlip;
      ++st.single_records;
      sv.sides.push_back(s);
    }
  }

  // Caps: every non-degenerate face.
  sv.caps.reserve(triangle_count - st.degenerate_faces);
  for (size_t f = 0; f < triangle_count; ++f) {
    if (!has_plane(uint32_t(f))) continue;
    SvCap c;
    put(c.a, positions[indices[3 * f]], sv.origin);
    put(c.b, positions[indices[3 * f + 1]], sv.origin);
    put(c.c, positions[indices[3 * f + 2]], sv.origin);
    c.plane = fp.face_plane[f] | (double_sided[f] ? SvCap::kDoubleSided : 0u);
    sv.caps.push_back(c);
  }
  st.sides = sv.sides.size();
  st.caps = sv.caps.size();
  const uint64_t plane_bytes = 16 * uint64_t(sv.planes.size() / 4);
  st.bytes = st.sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + plane_bytes;
  st.naive_bytes = st.naive_sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + plane_bytes;
  return sv;
}

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
  const float* planes = generic.planes.data();
  auto front = [&](uint32_t index) { return light_in_front(planes + 4 * size_t(index & 0x7fffffffu), light); };
  for (const SvSide& s : generic.sides) {
    const bool fa = front(s.plane_a);
    const bool fb = front(s.plane_b) != bool(s.plane_b & SvSide::kFlip);
    if (fa == fb) continue;
    SvSide o = s;
    o.plane_a = fa ? 0 : 1;
    o.plane_b = fb ? 0 : 1;
    lv.sides.push_back(o);
  }
  for (const SvCap& c : generic.caps) {
    const bool f = front(c.plane);
    const bool ds = c.plane & SvCap::kDoubleSided;
    if (!f && !ds) continue;
    SvCap o = c;
    o.plane = (f ? 0u : 1u) | (ds ? SvCap::kDoubleSided : 0u);
    lv.caps.push_back(o);
  }
  ShadowVolumeStats& st = lv.stats;
  st = generic.stats;
  st.sides = lv.sides.size();
  st.caps = lv.caps.size();
  st.bytes = st.sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + 32;
  return lv;
}

}  // namespace geom
