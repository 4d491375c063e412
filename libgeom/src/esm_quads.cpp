// Extended-shadow-map silhouette quads (see geom/esm_quads.h). Seed
// 000_4e3b0bad7883dc3e.txt, section 3.1 (which edges) and section 4.1 with
// figures 3-5 (degenerate quad, extrusion vector, bevel plane).
#include "geom/esm_quads.h"

#include <algorithm>
#include <cmath>

#include "live_faces.h"
#include "vec3.h"

namespace geom {
namespace {

using namespace vec3;
// A unit vector along a; +z for the zero vector.
inline Vec3 unit(Vec3 a) { return normalize_or(a, Vec3{0, 0, 1}); }

// std::lround(clamp(v) * 32767), inline (lround is a library call, 5% of a
// small mesh's bake): the truncation toward zero is exact at these sizes, so
// is the remainder, and halves go away from zero as lround's do.
// Branch-free where the data decide (the signs and the rounding of each
// normal are as good as random: a branch on them mispredicts every other call).
inline int16_t snorm16(double v) {
  const double x = std::max(-1.0, std::min(1.0, v)) * 32767.0;
  const int t = int(x);
  const double r = x - double(t);
  return int16_t(t + int(r >= 0.5) - int(r <= -0.5));
}

inline void encode(const double v[3], int16_t out[2]) {
  const double s = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  double x = s > 0 ? v[0] / s : 0, y = s > 0 ? v[1] / s : 0;
  const double z = s > 0 ? v[2] / s : 1;
  const double fx = (1 - std::fabs(y)) * (x >= 0 ? 1 : -1), fy = (1 - std::fabs(x)) * (y >= 0 ? 1 : -1);
  const bool fold = z < 0;
  x = fold ? fx : x;
  y = fold ? fy : y;
  out[0] = snorm16(x);
  out[1] = snorm16(y);
}

}  // namespace

void octahedral_encode(const double v[3], int16_t out[2]) { encode(v, out); }

void octahedral_decode(const int16_t in[2], float v[3]) {
  // As shaders/esm_quad.vert: snorm16 attribute, then the octahedral unfold.
  float x = std::max(float(in[0]) / 32767.0f, -1.0f), y = std::max(float(in[1]) / 32767.0f, -1.0f);
  float z = 1.0f - std::fabs(x) - std::fabs(y);
  if (z < 0.0f) {
    const float ox = x, oy = y;
    x = (1.0f - std::fabs(oy)) * (ox >= 0.0f ? 1.0f : -1.0f);
    y = (1.0f - std::fabs(ox)) * (oy >= 0.0f ? 1.0f : -1.0f);
  }
  const float l = std::sqrt(x * x + y * y + z * z);
  v[0] = x / l;
  v[1] = y / l;
  v[2] = z / l;
}

EsmQuads build_esm_quads(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                         const Topology& topology, const FacePlanes& fp, const EsmOptions& options) {
  EsmQuads r;
  EsmStats& st = r.stats;
  for (int a = 0; a < 3; ++a) r.origin[a] = fp.origin[a];
  st.edges = topology.edges.size();
  std::vector<uint32_t> remap(fp.plane_count(), FacePlanes::kNone);
  // Room is reserved below: four plain stores (a range insert is a
  // general-purpose call per plane).
  auto push_plane = [&](float a, float b, float c, float d) {
    r.planes.push_back(a), r.planes.push_back(b), r.planes.push_back(c), r.planes.push_back(d);
  };
  auto plane_of = [&](uint32_t face) {
    const uint32_t p = fp.face_plane[face];
    if (remap[p] == FacePlanes::kNone) {
      remap[p] = uint32_t(r.planes.size() / 4);
      const float* q = fp.planes.data() + 4 * size_t(p);
      push_plane(q[0], q[1], q[2], q[3]);
    }
    return remap[p];
  };
  auto pos = [&](uint32_t v) {
    const Float3& p = positions[v];
    return Vec3{double(p.x) - fp.origin[0], double(p.y) - fp.origin[1], double(p.z) - fp.origin[2]};
  };
  auto normal = [&](uint32_t f) { return Vec3{fp.normals[3 * f], fp.normals[3 * f + 1], fp.normals[3 * f + 2]}; };
  auto emit = [&](Vec3 p0, Vec3 p1, uint32_t pa, uint32_t pb, Vec3 q) {
    EsmQuad& e = r.quads.emplace_back();  // in place (one built aside and copied in stalls on its bytes)
    e.p0[0] = float(p0.x), e.p0[1] = float(p0.y), e.p0[2] = float(p0.z);
    e.p1[0] = float(p1.x), e.p1[1] = float(p1.y), e.p1[2] = float(p1.z);
    e.plane_a = pa;
    e.plane_b = pb;
    const double qd[3] = {q.x, q.y, q.z};
    encode(qd, e.q);
  };
  const double bevel_dot = -std::cos(options.bevel_below_degrees * M_PI / 180.0);

  // Room for the most an edge can emit (a pair: two quads and a bevel plane;
  // otherwise two quads and a plane per face), so the buffers never grow
  // (a grown vector copies itself; the unused tail is never paged in).
  constexpr size_t kPiece = 4096;  // quads per piece when streamed
  {
    // Sums over the edges, from the table's totals: every face entry, less
    // one per edge of two faces (a manifold or inconsistent edge).
    const TopologyStats& ts = topology.stats;
    size_t pairs = size_t(ts.manifold_edges + ts.inconsistent_edges);
    if (ts.edges != topology.edges.size()) {  // stats not filled in: count
      pairs = 0;
      for (const Edge& e : topology.edges) pairs += e.face_count == 2;
    }
    const size_t entries = topology.edge_faces.size();
    const size_t quads = 2 * (entries - pairs), planes = 4 * fp.plane_count() + 4 * (entries - pairs);
    r.quads.reserve(options.quads_out ? kPiece + 4 : quads);
    r.planes.reserve(planes);
  }
  uint64_t quads_sent = 0;
  const auto send = [&] {
    options.quads_out(r.quads.data(), r.quads.size());
    quads_sent += r.quads.size();
    r.quads.clear();
  };
  detail::LiveFaces live;
  for (const Edge& e : topology.edges) {
    if (options.quads_out && r.quads.size() >= kPiece) send();  // streamed: a piece of whole edges
    live.gather(topology, fp, e);
    if (live.empty()) continue;
    ++st.candidate_edges;
    const Vec3 v0 = pos(e.v0), v1 = pos(e.v1);
    const size_t before = r.quads.size();
    if (live.size() == 2) {
      // A pair: manifold (opposite directions) or inconsistent (B flipped).
      const bool inconsistent = !((live[0] ^ live[1]) & 1u);
      const uint32_t ea = inconsistent || !(live[0] & 1u) ? live[0] : live[1];
      const uint32_t eb = ea == live[0] ? live[1] : live[0];
      const uint32_t fa = ea >> 1, fb = eb >> 1;
      if (!inconsistent && fp.face_plane[fa] == fp.face_plane[fb]) {
        ++st.skipped_coplanar;
        continue;
      }
      const Vec3 p0 = (ea & 1u) ? v1 : v0, p1 = (ea & 1u) ? v0 : v1;  // A traverses p0 -> p1
      const Vec3 na = normal(fa), nb = normal(fb) * (inconsistent ? -1.0 : 1.0);
      const uint32_t* w = indices + 3 * size_t(fb);
      const uint32_t far = w[0] != e.v0 && w[0] != e.v1 ? w[0] : w[1] != e.v0 && w[1] != e.v1 ? w[1] : w[2];
      const bool concave = dot(na, pos(far) - p0) > 0;
      if (concave && !options.keep_concave) {
        ++st.skipped_concave;
        continue;
      }
      const uint32_t pa = plane_of(fa), pb = plane_of(fb) | (inconsistent ? EsmQuad::kFlip : 0u);
      if (dot(na, nb) >= bevel_dot) {
        emit(p0, p1, pa, pb, unit(na + nb));
      } else {
        // Bevel plane: the normalized sum of the two planes, through the edge.
        Vec3 s = na + nb;
        const Vec3 nbev = length(s) > 1e-6 ? unit(s) : unit(cross(p1 - p0, na));
        const Vec3 mid = (p0 + p1) * 0.5;
        const uint32_t pbev = uint32_t(r.planes.size() / 4);
        push_plane(float(nbev.x), float(nbev.y), float(nbev.z), float(-dot(nbev, mid)));
        emit(p0, p1, pa, pbev, unit(na + nbev));
        emit(p0, p1, pbev, pb, unit(nbev + nb));
        ++st.bevel_edges;
      }
    } else {
      // Boundary or non-manifold: each face is a knife edge (its plane and the
      // same plane flipped, 180 degrees apart), split against the bevel plane
      // through the edge with normal u, in the face's plane pointing away
      // from it: two quads, exactly one open for any light off the planes.
      for (uint32_t ef : live) {
        const uint32_t f = ef >> 1;
        const Vec3 p0 = (ef & 1u) ? v1 : v0, p1 = (ef & 1u) ? v0 : v1;
        const Vec3 n = normal(f), u = unit(cross(p1 - p0, n));
        const uint32_t pa = plane_of(f), pbev = uint32_t(r.planes.size() / 4);
        const Vec3 mid = (p0 + p1) * 0.5;
        push_plane(float(u.x), float(u.y), float(u.z), float(-dot(u, mid)));
        emit(p0, p1, pa, pbev, unit(n + u));
        emit(p0, p1, pbev, pa | EsmQuad::kFlip, unit(u - n));
        ++st.bevel_edges;
      }
    }
    if (r.quads.size() > before) ++st.emitted_edges;
  }
  if (options.quads_out) {
    if (!r.quads.empty()) send();
    std::vector<EsmQuad>().swap(r.quads);
  }
  st.quads = quads_sent + r.quads.size();
  st.bytes = st.quads * sizeof(EsmQuad) + 16 * uint64_t(r.planes.size() / 4);
  st.naive_bytes = 160 * st.candidate_edges;
  return r;
}

}  // namespace geom
