// Extended-shadow-map silhouette quads (see geom/esm_quads.h). Bujnak 2004
// (Extended Shadow Maps), Sect. 3.1 (which edges) and Sect. 4.1 with
// Fig. 3-5 (degenerate quad, extrusion vector, bevel plane).
#include "geom/esm_quads.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "geom/precondition.h"
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
  // z = v[2] / s matters only by its sign: negative exactly when v[2] is,
  // unless the quotient underflows to -0, which needs s >= 2 (|v[2]| / s
  // <= 2^-1075); the division is left for that case (never a unit vector's).
  // s NaN (or 0): z = 1, no fold, as both comparisons with s fail.
  const bool fold = v[2] < 0 && (s < 2 || v[2] / s < 0);
  const double fx = (1 - std::fabs(y)) * (x >= 0 ? 1 : -1), fy = (1 - std::fabs(x)) * (y >= 0 ? 1 : -1);
  x = fold ? fx : x;
  y = fold ? fy : y;
  out[0] = snorm16(x);
  out[1] = snorm16(y);
}

// encode(unit(a)), the extrusion vector of a quad.
inline void encode_unit(Vec3 a, int16_t out[2]) {
  const Vec3 u = unit(a);
  const double v[3] = {u.x, u.y, u.z};
  encode(v, out);
}

// The extrusion vectors of the quads last emitted, before unit() and
// encode(): they wait here and are finished kSize at a time, so one quad's
// square root and divisions overlap the next quads' instead of closing each
// edge's chain of loads (each quad is still the same operations, in the same
// order).
class QBatch {
 public:
  static constexpr int kSize = 64;
  void push(std::vector<EsmQuad>& quads, Vec3 a) {
    x_[n_] = a.x, y_[n_] = a.y, z_[n_] = a.z;
    if (++n_ == kSize) flush(quads);
  }
  // Finishes the waiting vectors: theirs are the last n_ quads.
  void flush(std::vector<EsmQuad>& quads) {
    EsmQuad* q = quads.data() + (quads.size() - size_t(n_));
    int i = 0;
#if defined(__SSE2__)
    for (; i + 2 <= n_; i += 2)
      if (!encode_unit2(i, q[i].q, q[i + 1].q)) {
        encode_unit(Vec3{x_[i], y_[i], z_[i]}, q[i].q);
        encode_unit(Vec3{x_[i + 1], y_[i + 1], z_[i + 1]}, q[i + 1].q);
      }
#endif
    for (; i < n_; ++i) encode_unit(Vec3{x_[i], y_[i], z_[i]}, q[i].q);
    n_ = 0;
  }

 private:
#if defined(__SSE2__)
  // encode_unit() of vectors i and i + 1, two lanes at a time: each lane the
  // same IEEE operations in the same order (so the same bits); false, and
  // nothing written, where a lane's s is not in (0, 2) (see encode()).
  bool encode_unit2(int i, int16_t out0[2], int16_t out1[2]) const {
    const __m128d zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0), minus_one = _mm_set1_pd(-1.0);
    const __m128d sign = _mm_set1_pd(-0.0);
    const auto abs = [&](__m128d v) { return _mm_andnot_pd(sign, v); };
    const auto select = [](__m128d m, __m128d a, __m128d b) {
      return _mm_or_pd(_mm_and_pd(m, a), _mm_andnot_pd(m, b));
    };
    const __m128d ax = _mm_loadu_pd(x_ + i), ay = _mm_loadu_pd(y_ + i), az = _mm_loadu_pd(z_ + i);
    // unit(): a * (1 / |a|), or +z.
    const __m128d l = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(ax, ax), _mm_mul_pd(ay, ay)), _mm_mul_pd(az, az)));
    const __m128d ok = _mm_cmpgt_pd(l, zero), inv = _mm_div_pd(one, l);
    const __m128d ux = _mm_and_pd(ok, _mm_mul_pd(ax, inv)), uy = _mm_and_pd(ok, _mm_mul_pd(ay, inv));
    const __m128d uz = select(ok, _mm_mul_pd(az, inv), one);
    // encode()
    const __m128d s = _mm_add_pd(_mm_add_pd(abs(ux), abs(uy)), abs(uz));
    if (_mm_movemask_pd(_mm_and_pd(_mm_cmpgt_pd(s, zero), _mm_cmplt_pd(s, _mm_set1_pd(2.0)))) != 3) return false;
    const __m128d x = _mm_div_pd(ux, s), y = _mm_div_pd(uy, s);
    const __m128d fx = _mm_mul_pd(_mm_sub_pd(one, abs(y)), select(_mm_cmpge_pd(x, zero), one, minus_one));
    const __m128d fy = _mm_mul_pd(_mm_sub_pd(one, abs(x)), select(_mm_cmpge_pd(y, zero), one, minus_one));
    const __m128d fold = _mm_cmplt_pd(uz, zero);
    const __m128i tx = snorm16x2(select(fold, fx, x)), ty = snorm16x2(select(fold, fy, y));
    const __m128i xy = _mm_packs_epi32(_mm_unpacklo_epi32(tx, ty), _mm_setzero_si128());  // x0 y0 x1 y1
    const int32_t w0 = _mm_cvtsi128_si32(xy), w1 = _mm_cvtsi128_si32(_mm_srli_si128(xy, 4));
    std::memcpy(out0, &w0, 4);
    std::memcpy(out1, &w1, 4);
    return true;
  }
  // snorm16() of two lanes, as two int32 (lanes 0 and 1).
  static __m128i snorm16x2(__m128d v) {
    const __m128d x = _mm_mul_pd(_mm_max_pd(_mm_min_pd(v, _mm_set1_pd(1.0)), _mm_set1_pd(-1.0)), _mm_set1_pd(32767.0));
    const __m128i t = _mm_cvttpd_epi32(x);
    const __m128d r = _mm_sub_pd(x, _mm_cvtepi32_pd(t));
    const __m128i up = _mm_shuffle_epi32(_mm_castpd_si128(_mm_cmpge_pd(r, _mm_set1_pd(0.5))), _MM_SHUFFLE(2, 0, 2, 0));
    const __m128i dn = _mm_shuffle_epi32(_mm_castpd_si128(_mm_cmple_pd(r, _mm_set1_pd(-0.5))), _MM_SHUFFLE(2, 0, 2, 0));
    return _mm_add_epi32(_mm_sub_epi32(t, up), dn);  // a true mask is -1
  }
#endif
  double x_[kSize], y_[kSize], z_[kSize];
  int n_ = 0;
};

// Builds the quads of one mesh: the state the walk over the edges shares.
class QuadBuilder {
 public:
  QuadBuilder(PositionSpan positions, const uint32_t* indices, const Topology& topology, const FacePlanes& fp,
              const EsmOptions& options)
      : positions_(positions),
        indices_(indices),
        topology_(topology),
        fp_(fp),
        options_(options),
        remap_(fp.plane_count(), FacePlanes::kNone),
        bevel_dot_(-std::cos(options.bevel_below_degrees * M_PI / 180.0)) {
    for (int a = 0; a < 3; ++a) r_.origin[a] = fp.origin[a];
    r_.stats.edges = topology.edges.size();
  }

  EsmQuads build() {
    EsmStats& st = r_.stats;
    reserve();
    for (const Edge& e : topology_.edges) {
      if (options_.quads_out && r_.quads.size() >= kPiece) send();  // streamed: a piece of whole edges
      live_.gather(topology_, fp_, e);
      if (live_.empty()) continue;
      ++st.candidate_edges;
      const size_t before = r_.quads.size();
      if (live_.size() == 2)
        pair_quads(e);
      else
        knife_quads(e);
      if (r_.quads.size() > before) ++st.emitted_edges;
    }
    batch_.flush(r_.quads);
    if (options_.quads_out) {
      if (!r_.quads.empty()) send();
      std::vector<EsmQuad>().swap(r_.quads);
    }
    st.quads = quads_sent_ + r_.quads.size();
    st.bytes = st.quads * sizeof(EsmQuad) + 16 * uint64_t(r_.planes.size() / 4);
    st.naive_bytes = 160 * st.candidate_edges;
    return std::move(r_);
  }

 private:
  static constexpr size_t kPiece = 4096;  // quads per piece when streamed

  // Room is reserved: four plain stores (a range insert is a general-purpose
  // call per plane).
  void push_plane(float a, float b, float c, float d) {
    r_.planes.push_back(a), r_.planes.push_back(b), r_.planes.push_back(c), r_.planes.push_back(d);
  }
  // A face's plane in the quads' own table, added on first use.
  uint32_t plane_of(uint32_t face) {
    const uint32_t p = fp_.face_plane[face];
    if (remap_[p] == FacePlanes::kNone) {
      remap_[p] = uint32_t(r_.planes.size() / 4);
      const float* q = fp_.planes.data() + 4 * size_t(p);
      push_plane(q[0], q[1], q[2], q[3]);
    }
    return remap_[p];
  }
  Vec3 pos(uint32_t v) const {
    const Float3& p = positions_[v];
    return Vec3{double(p.x) - fp_.origin[0], double(p.y) - fp_.origin[1], double(p.z) - fp_.origin[2]};
  }
  Vec3 normal(uint32_t f) const { return Vec3{fp_.normals[3 * f], fp_.normals[3 * f + 1], fp_.normals[3 * f + 2]}; }
  // q: the extrusion vector before unit() (finished in the batch).
  void emit(Vec3 p0, Vec3 p1, uint32_t pa, uint32_t pb, Vec3 q) {
    EsmQuad& e = r_.quads.emplace_back();  // in place (one built aside and copied in stalls on its bytes)
    e.p0[0] = float(p0.x), e.p0[1] = float(p0.y), e.p0[2] = float(p0.z);
    e.p1[0] = float(p1.x), e.p1[1] = float(p1.y), e.p1[2] = float(p1.z);
    e.plane_a = pa;
    e.plane_b = pb;
    batch_.push(r_.quads, q);
  }

  // Room for the most an edge can emit (a pair: two quads and a bevel plane;
  // otherwise two quads and a plane per face), so the buffers never grow
  // (a grown vector copies itself; the unused tail is never paged in).
  void reserve() {
    // Sums over the edges, from the table's totals: every face entry, less
    // one per edge of two faces (a manifold or inconsistent edge).
    const TopologyStats& ts = topology_.stats;
    size_t pairs = size_t(ts.manifold_edges + ts.inconsistent_edges);
    if (ts.edges != topology_.edges.size()) {  // stats not filled in: count
      pairs = 0;
      for (const Edge& e : topology_.edges) pairs += e.face_count == 2;
    }
    const size_t entries = topology_.edge_faces.size();
    const size_t quads = 2 * (entries - pairs), planes = 4 * fp_.plane_count() + 4 * (entries - pairs);
    r_.quads.reserve(options_.quads_out ? kPiece + 4 : quads);
    r_.planes.reserve(planes);
  }
  void send() {
    batch_.flush(r_.quads);  // the piece's last extrusion vectors
    options_.quads_out(r_.quads.data(), r_.quads.size());
    quads_sent_ += r_.quads.size();
    r_.quads.clear();
  }

  // A pair: manifold (opposite directions) or inconsistent (B flipped). One
  // quad, or two against a bevel plane where the faces meet under
  // bevel_below_degrees; none for coplanar faces, nor concave ones unless kept.
  void pair_quads(const Edge& e) {
    EsmStats& st = r_.stats;
    const Vec3 v0 = pos(e.v0), v1 = pos(e.v1);
    const bool inconsistent = !((live_[0] ^ live_[1]) & 1u);
    const uint32_t ea = inconsistent || !(live_[0] & 1u) ? live_[0] : live_[1];
    const uint32_t eb = ea == live_[0] ? live_[1] : live_[0];
    const uint32_t fa = ea >> 1, fb = eb >> 1;
    if (!inconsistent && fp_.face_plane[fa] == fp_.face_plane[fb]) {
      ++st.skipped_coplanar;
      return;
    }
    const Vec3 p0 = (ea & 1u) ? v1 : v0, p1 = (ea & 1u) ? v0 : v1;  // A traverses p0 -> p1
    const Vec3 na = normal(fa), nb = normal(fb) * (inconsistent ? -1.0 : 1.0);
    const uint32_t* w = indices_ + 3 * size_t(fb);
    // The first of B's vertices off the edge, selected by masks: which it
    // is follows no pattern a branch predictor could learn.
    const uint32_t m0 = 0u - uint32_t(w[0] != e.v0 && w[0] != e.v1), m1 = 0u - uint32_t(w[1] != e.v0 && w[1] != e.v1);
    const uint32_t far = (w[0] & m0) | (~m0 & ((w[1] & m1) | (~m1 & w[2])));
    const bool concave = dot(na, pos(far) - p0) > 0;
    if (concave && !options_.keep_concave) {
      ++st.skipped_concave;
      return;
    }
    const uint32_t pa = plane_of(fa), pb = plane_of(fb) | (inconsistent ? EsmQuad::kFlip : 0u);
    if (dot(na, nb) >= bevel_dot_) {
      emit(p0, p1, pa, pb, na + nb);
      return;
    }
    // Bevel plane: the normalized sum of the two planes, through the edge.
    Vec3 s = na + nb;
    const Vec3 nbev = length(s) > 1e-6 ? unit(s) : unit(cross(p1 - p0, na));
    const Vec3 mid = (p0 + p1) * 0.5;
    const uint32_t pbev = uint32_t(r_.planes.size() / 4);
    push_plane(float(nbev.x), float(nbev.y), float(nbev.z), float(-dot(nbev, mid)));
    emit(p0, p1, pa, pbev, na + nbev);
    emit(p0, p1, pbev, pb, nbev + nb);
    ++st.bevel_edges;
  }

  // Boundary or non-manifold: each face is a knife edge (its plane and the
  // same plane flipped, 180 degrees apart), split against the bevel plane
  // through the edge with normal u, in the face's plane pointing away from
  // it: two quads, exactly one open for any light off the planes.
  void knife_quads(const Edge& e) {
    const Vec3 v0 = pos(e.v0), v1 = pos(e.v1);
    for (uint32_t ef : live_) {
      const uint32_t f = ef >> 1;
      const Vec3 p0 = (ef & 1u) ? v1 : v0, p1 = (ef & 1u) ? v0 : v1;
      const Vec3 n = normal(f), u = unit(cross(p1 - p0, n));
      const uint32_t pa = plane_of(f), pbev = uint32_t(r_.planes.size() / 4);
      const Vec3 mid = (p0 + p1) * 0.5;
      push_plane(float(u.x), float(u.y), float(u.z), float(-dot(u, mid)));
      emit(p0, p1, pa, pbev, n + u);
      emit(p0, p1, pbev, pa | EsmQuad::kFlip, u - n);
      ++r_.stats.bevel_edges;
    }
  }

  PositionSpan positions_;
  const uint32_t* indices_;
  const Topology& topology_;
  const FacePlanes& fp_;
  const EsmOptions& options_;
  std::vector<uint32_t> remap_;  // fp's plane -> the quads' plane table
  const double bevel_dot_;
  EsmQuads r_;
  QBatch batch_;
  detail::LiveFaces live_;
  uint64_t quads_sent_ = 0;
};

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
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  GEOM_PRECONDITION(fp.face_plane.size() == triangle_count,
                    std::to_string(fp.face_plane.size()) + " face planes, expected " + std::to_string(triangle_count) +
                        " (compute_face_planes of these triangles)");
  return QuadBuilder(positions, indices, topology, fp, options).build();
}

EsmQuads build_esm_quads(EsmQuad* out, PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                         const Topology& topology, const FacePlanes& fp, const EsmOptions& options) {
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  GEOM_PRECONDITION(fp.face_plane.size() == triangle_count,
                    std::to_string(fp.face_plane.size()) + " face planes, expected " + std::to_string(triangle_count) +
                        " (compute_face_planes of these triangles)");
  GEOM_PRECONDITION(!options.quads_out, "options.quads_out is set: the quads go to `out`");
  GEOM_PRECONDITION(triangle_count == 0 || out, "null output for " + std::to_string(triangle_count) + " triangles");
  EsmOptions to_out = options;
  size_t written = 0;
  const size_t bound = esm_quads_bound(triangle_count);
  to_out.quads_out = [out, &written, bound](const EsmQuad* quads, size_t count) {
    if (written + count > bound) detail::precondition_failed("build_esm_quads", "more quads than esm_quads_bound");
    std::memcpy(out + written, quads, count * sizeof(EsmQuad));
    written += count;
  };
  return QuadBuilder(positions, indices, topology, fp, to_out).build();
}

}  // namespace geom
