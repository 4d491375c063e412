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

#include "geom/precondition.h"
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

// Builds one volume: the state the walks over edges and faces share.
// Streamed (options.sides_out, caps_out), the records go out a piece at a
// time and only a piece is ever held.
class VolumeBuilder {
 public:
  VolumeBuilder(PositionSpan positions, const uint32_t* indices, size_t triangle_count, const Topology& topology,
                const FacePlanes& fp, std::vector<float> planes, const ShadowVolumeOptions& options)
      : indices_(indices),
        triangle_count_(triangle_count),
        topology_(topology),
        fp_(fp),
        options_(options),
        face_plane_(fp.face_plane.data()),
        ids_(options.component_ids || options.one_sided_closed),
        stream_sides_(bool(options.sides_out)),
        stream_caps_(bool(options.caps_out)),
        side_ids_(ids_ && !stream_sides_),
        cap_ids_(ids_ && !stream_caps_) {
    for (int a = 0; a < 3; ++a) sv_.origin[a] = fp.origin[a];
    sv_.planes = std::move(planes);
    sv_.stats.edges = topology.edges.size();
    to_local(positions);
    component_.resize(ids_ ? triangle_count : 0);
    parent_ = component_.data();
    for (size_t f = 0; f < component_.size(); ++f) parent_[f] = uint32_t(f);
  }

  ShadowVolume build() {
    // One-sided, a pair's multiplicity depends on its component's closedness:
    // the components first. Double-sided, they are joined in the records' walk.
    if (options_.one_sided_closed) {
      for (const Edge& e : topology_.edges) {
        live_.gather(topology_, fp_, e);
        if (!live_.empty()) join();
      }
      number();
    }
    write_sides();
    if (ids_ && !numbered_) {
      number();
      for (uint32_t& id : sv_.side_component) id = component_[id];  // faces to components
    }
    ShadowVolumeStats& st = sv_.stats;
    st.components = sv_.component_closed.size();
    for (uint8_t c : sv_.component_closed) st.closed_components += c;
    write_caps();
    st.sides = sides_sent_ + sv_.sides.size();
    st.caps = caps_sent_ + sv_.caps.size();
    const uint64_t plane_bytes = 16 * uint64_t(sv_.planes.size() / 4);
    st.bytes = st.sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + plane_bytes;
    st.naive_bytes = st.naive_sides * sizeof(SvSide) + st.caps * sizeof(SvCap) + plane_bytes;
    return std::move(sv_);
  }

 private:
  static constexpr size_t kPiece = 4096;

  // The vertices in the local frame, each converted once (the records copy them).
  void to_local(PositionSpan positions) {
    local_.resize(3 * positions.size());
    for (size_t v = 0; v < positions.size(); ++v) {
      const Float3& p = positions[v];
      local_[3 * v] = float(double(p.x) - sv_.origin[0]);
      local_[3 * v + 1] = float(double(p.y) - sv_.origin[1]);
      local_[3 * v + 2] = float(double(p.z) - sv_.origin[2]);
    }
    lp_ = local_.data();
  }

  // Components over non-degenerate faces (a component is closed when each of
  // its edges has exactly two such faces in opposite directions): a
  // union-find, then in the same array each face's dense id, in face order.
  bool is_pair() const { return live_.size() == 2 && ((live_[0] ^ live_[1]) & 1u); }
  void join() {  // the gathered edge's faces
    for (size_t i = 1; i < live_.size(); ++i) unite(parent_, live_[0] >> 1, live_[i] >> 1);
    if (!is_pair()) open_faces_.push_back(live_[0] >> 1);
  }
  void number() {  // a face's parent is never after it: its slot already holds the id
    for (size_t f = 0; f < triangle_count_; ++f) {
      if (face_plane_[f] == FacePlanes::kNone) continue;
      const uint32_t p = parent_[f];
      if (p == f) {
        component_[f] = uint32_t(sv_.component_closed.size());
        sv_.component_closed.push_back(1);
      } else {
        component_[f] = component_[p];
      }
    }
    for (uint32_t f : open_faces_) sv_.component_closed[component_[f]] = 0;
    std::vector<uint32_t>().swap(open_faces_);
    numbered_ = true;
  }
  bool double_sided(uint32_t f) const { return !options_.one_sided_closed || !sv_.component_closed[component_[f]]; }

  void send_sides() {
    options_.sides_out(sv_.sides.data(), sv_.sides.size());
    sides_sent_ += sv_.sides.size();
    sv_.sides.clear();
  }
  // Each record written in place, field by field (one built aside and copied
  // in stalls on its partly written bytes). Its id: the component once
  // numbered, else its face for now.
  void add_side(uint32_t v0, uint32_t v1, uint32_t plane_a, uint32_t plane_b, uint32_t face) {
    SvSide& s = sv_.sides.emplace_back();
    std::memcpy(s.p0, lp_ + 3 * size_t(v0), 12);
    std::memcpy(s.p1, lp_ + 3 * size_t(v1), 12);
    s.plane_a = plane_a;
    s.plane_b = plane_b;
    if (side_ids_)
      sv_.side_component.push_back(numbered_ ? component_[face] : face);
    else if (stream_sides_ && sv_.sides.size() == kPiece)
      send_sides();
  }

  // One edge's side records from its gathered live faces: a pair (two faces
  // in opposite directions) gives one record, or two where double-sided,
  // unless its planes are one; any other edge one record per face.
  void edge_sides(const Edge& e) {
    ShadowVolumeStats& st = sv_.stats;
    if (is_pair()) {
      const uint32_t fa = (live_[0] & 1u) ? live_[1] >> 1 : live_[0] >> 1;  // traverses v0 -> v1
      const uint32_t fb = (live_[0] & 1u) ? live_[0] >> 1 : live_[1] >> 1;
      const uint32_t pa = face_plane_[fa], pb = face_plane_[fb];
      const bool ds = double_sided(fa);
      if (pa == pb) {
        ++st.skipped_coplanar;
        st.skipped_coplanar_records += ds ? 2 : 1;
        return;
      }
      ++st.pair_edges;
      add_side(e.v0, e.v1, pa, pb, fa);
      if (ds) add_side(e.v0, e.v1, pa | SvSide::kSecond, pb, fa);  // multiplicity up to 2: the second copy
      return;
    }
    for (uint32_t ef : live_) {
      const bool reversed = ef & 1u;
      const uint32_t plane = face_plane_[ef >> 1];
      ++st.single_records;
      add_side(reversed ? e.v1 : e.v0, reversed ? e.v0 : e.v1, plane, plane | SvSide::kFlip, ef >> 1);
    }
  }

  // Side records, in edge order; room for the most (a pair: two records, else
  // one per face), so the buffers never grow.
  void write_sides() {
    if (stream_sides_) {
      sv_.sides.reserve(kPiece);
    } else {
      const size_t most = topology_.edge_faces.size();  // the sum of those over the edges
      sv_.sides.reserve(most);
      if (side_ids_) sv_.side_component.reserve(most);
    }
    for (const Edge& e : topology_.edges) {
      live_.gather(topology_, fp_, e);
      if (live_.empty()) continue;
      sv_.stats.naive_sides += live_.size();
      if (ids_ && !numbered_) join();
      edge_sides(e);
    }
    if (stream_sides_) {
      if (!sv_.sides.empty()) send_sides();
      std::vector<SvSide>().swap(sv_.sides);
    }
  }

  void send_caps() {
    options_.caps_out(sv_.caps.data(), sv_.caps.size());
    caps_sent_ += sv_.caps.size();
    sv_.caps.clear();
  }
  // Caps: every non-degenerate face.
  void write_caps() {
    ShadowVolumeStats& st = sv_.stats;
    if (stream_caps_) {
      sv_.caps.reserve(kPiece);
    } else {
      const size_t caps = triangle_count_ - std::min<uint64_t>(fp_.degenerate_faces, triangle_count_);
      sv_.caps.reserve(caps);
      if (cap_ids_) sv_.cap_component.reserve(caps);
    }
    for (size_t f = 0; f < triangle_count_; ++f) {
      if (face_plane_[f] == FacePlanes::kNone) {
        ++st.degenerate_faces;
        continue;
      }
      SvCap& c = sv_.caps.emplace_back();
      const uint32_t* v = indices_ + 3 * f;
      std::memcpy(c.a, lp_ + 3 * size_t(v[0]), 12);
      std::memcpy(c.b, lp_ + 3 * size_t(v[1]), 12);
      std::memcpy(c.c, lp_ + 3 * size_t(v[2]), 12);
      const bool ds = double_sided(uint32_t(f));
      c.plane = face_plane_[f] | (ds ? SvCap::kDoubleSided : 0u);
      ++(ds ? st.double_sided_faces : st.one_sided_faces);
      if (cap_ids_)
        sv_.cap_component.push_back(component_[f]);
      else if (stream_caps_ && sv_.caps.size() == kPiece)
        send_caps();
    }
    if (stream_caps_) {
      if (!sv_.caps.empty()) send_caps();
      std::vector<SvCap>().swap(sv_.caps);
    }
  }

  const uint32_t* indices_;
  size_t triangle_count_;
  const Topology& topology_;
  const FacePlanes& fp_;
  const ShadowVolumeOptions& options_;
  const uint32_t* face_plane_;
  const bool ids_, stream_sides_, stream_caps_, side_ids_, cap_ids_;
  ShadowVolume sv_;
  std::vector<float> local_;
  const float* lp_ = nullptr;
  std::vector<uint32_t> component_;
  uint32_t* parent_ = nullptr;
  std::vector<uint32_t> open_faces_;  // a face of each edge that is not a pair: its component is open
  detail::LiveFaces live_;            // the non-degenerate faces of one edge, as edge_faces entries
  bool numbered_ = false;
  uint64_t sides_sent_ = 0, caps_sent_ = 0;
};

// The volume; `planes` (fp's plane table, copied or moved) becomes sv.planes.
ShadowVolume build(PositionSpan positions, const uint32_t* indices, size_t triangle_count, const Topology& topology,
                   const FacePlanes& fp, std::vector<float> planes, const ShadowVolumeOptions& options) {
  return VolumeBuilder(positions, indices, triangle_count, topology, fp, std::move(planes), options).build();
}

}  // namespace

ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, const FacePlanes& fp, const ShadowVolumeOptions& options) {
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  GEOM_PRECONDITION(fp.face_plane.size() == triangle_count,
                    std::to_string(fp.face_plane.size()) + " face planes, expected " + std::to_string(triangle_count) +
                        " (compute_face_planes of these triangles)");
  return build(positions, indices, triangle_count, topology, fp, fp.planes, options);
}

ShadowVolume build_shadow_volume(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                 const Topology& topology, FacePlanes&& fp, const ShadowVolumeOptions& options) {
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  GEOM_PRECONDITION(fp.face_plane.size() == triangle_count,
                    std::to_string(fp.face_plane.size()) + " face planes, expected " + std::to_string(triangle_count) +
                        " (compute_face_planes of these triangles)");
  std::vector<float> planes = std::move(fp.planes);
  return build(positions, indices, triangle_count, topology, fp, std::move(planes), options);
}

ShadowVolume build_shadow_volume(SvSide* sides, SvCap* caps, PositionSpan positions, const uint32_t* indices,
                                 size_t triangle_count, const Topology& topology, const FacePlanes& fp,
                                 const ShadowVolumeOptions& options) {
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  GEOM_PRECONDITION(fp.face_plane.size() == triangle_count,
                    std::to_string(fp.face_plane.size()) + " face planes, expected " + std::to_string(triangle_count) +
                        " (compute_face_planes of these triangles)");
  GEOM_PRECONDITION(!options.sides_out && !options.caps_out,
                    "options.sides_out or caps_out is set: the records go to "
                    "`sides` and `caps`");
  GEOM_PRECONDITION(triangle_count == 0 || (sides && caps),
                    "null output for " + std::to_string(triangle_count) + " triangles");
  ShadowVolumeOptions to_out = options;
  size_t side_count = 0, cap_count = 0;
  const size_t side_bound = shadow_volume_sides_bound(triangle_count);
  const size_t cap_bound = shadow_volume_caps_bound(triangle_count);
  to_out.sides_out = [sides, &side_count, side_bound](const SvSide* records, size_t count) {
    if (side_count + count > side_bound)
      detail::precondition_failed("build_shadow_volume", "more sides than shadow_volume_sides_bound");
    std::memcpy(sides + side_count, records, count * sizeof(SvSide));
    side_count += count;
  };
  to_out.caps_out = [caps, &cap_count, cap_bound](const SvCap* records, size_t count) {
    if (cap_count + count > cap_bound)
      detail::precondition_failed("build_shadow_volume", "more caps than shadow_volume_caps_bound");
    std::memcpy(caps + cap_count, records, count * sizeof(SvCap));
    cap_count += count;
  };
  return build(positions, indices, triangle_count, topology, fp, fp.planes, to_out);
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
