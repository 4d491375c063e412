// Vertex welding by position (see geom/weld.h for the contract).
//
// Exact mode: an open-addressing hash table keyed by the coordinates' bit
// patterns (-0 folded onto +0), one probe sequence per vertex: O(n).
// Tolerance mode: a uniform grid of cell size `tolerance`; a vertex looks for
// the earliest representative within the tolerance in the 27 cells around it.
#include "geom/weld.h"

#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "geom/precondition.h"

namespace geom {
namespace {

inline uint32_t float_key(float f) {
  if (f == 0.0f) f = 0.0f;  // -0 and +0 weld
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

inline uint64_t mix(uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

// Where the welded positions go: a vector that grows (never reallocated: room
// for every vertex is reserved), or the caller's array of weld_bound floats x 3.
struct VectorOut {
  std::vector<float>& v;
  size_t size() const { return v.size() / 3; }
  void push(const Float3& p) { v.push_back(p.x), v.push_back(p.y), v.push_back(p.z); }
  const float* at(uint32_t w) const { return v.data() + 3 * size_t(w); }
};
struct ArrayOut {
  float* v;
  size_t n = 0;
  size_t size() const { return n; }
  void push(const Float3& p) { v[3 * n] = p.x, v[3 * n + 1] = p.y, v[3 * n + 2] = p.z, ++n; }
  const float* at(uint32_t w) const { return v + 3 * size_t(w); }
};

template <class Out>
void weld_exact(PositionSpan p, uint32_t* remap, Out& out) {
  const size_t n = p.size();
  size_t capacity = 16;
  while (capacity < n * 2) capacity *= 2;
  std::vector<uint32_t> table(capacity, 0xffffffffu);  // welded vertex index per slot
  // A slot's key is read back from the welded position.
  for (size_t i = 0; i < n; ++i) {
    const Float3& v = p[i];
    if (std::isnan(v.x) || std::isnan(v.y) || std::isnan(v.z)) {  // NaN never merges
      remap[i] = uint32_t(out.size());
      out.push(v);
      continue;
    }
    const uint32_t kx = float_key(v.x), ky = float_key(v.y), kz = float_key(v.z);
    uint64_t h = mix((uint64_t(kx) << 32 | ky) ^ mix(kz));
    size_t slot = h & (capacity - 1);
    for (;;) {
      uint32_t w = table[slot];
      if (w == 0xffffffffu) {
        w = uint32_t(out.size());
        table[slot] = w;
        out.push(v);
        remap[i] = w;
        break;
      }
      const float* q = out.at(w);
      if (float_key(q[0]) == kx && float_key(q[1]) == ky && float_key(q[2]) == kz) {
        remap[i] = w;
        break;
      }
      slot = (slot + 1) & (capacity - 1);
    }
  }
}

template <class Out>
void weld_tolerance(PositionSpan p, float tolerance, uint32_t* remap, Out& out) {
  const double cell = double(tolerance);
  const double tol2 = double(tolerance) * double(tolerance);
  auto cell_of = [&](double x) {
    double c = std::floor(x / cell);
    if (!(c > -1e15)) c = -1e15;  // also catches NaN
    if (c > 1e15) c = 1e15;
    return int64_t(c);
  };
  auto cell_hash = [](int64_t x, int64_t y, int64_t z) {
    return mix(uint64_t(x) * 0x9E3779B97F4A7C15ULL ^ mix(uint64_t(y)) ^ (mix(uint64_t(z)) << 1));
  };
  std::unordered_map<uint64_t, uint32_t> head;  // cell hash -> last representative in it
  std::vector<uint32_t> next;                   // chain of representatives sharing a cell hash (distance decides)
  head.reserve(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    const Float3& v = p[i];
    const int64_t cx = cell_of(v.x), cy = cell_of(v.y), cz = cell_of(v.z);
    uint32_t best = 0xffffffffu;
    if (!std::isnan(v.x) && !std::isnan(v.y) && !std::isnan(v.z)) {
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            auto it = head.find(cell_hash(cx + dx, cy + dy, cz + dz));
            if (it == head.end()) continue;
            for (uint32_t w = it->second; w != 0xffffffffu; w = next[w]) {
              if (w >= best) continue;
              const float* q = out.at(w);
              double ex = double(q[0]) - v.x, ey = double(q[1]) - v.y, ez = double(q[2]) - v.z;
              if (ex * ex + ey * ey + ez * ez <= tol2) best = w;
            }
          }
    }
    if (best != 0xffffffffu) {
      remap[i] = best;
      continue;
    }
    uint32_t w = uint32_t(out.size());
    out.push(v);
    auto [it, inserted] = head.try_emplace(cell_hash(cx, cy, cz), w);
    next.push_back(inserted ? 0xffffffffu : it->second);
    it->second = w;
    remap[i] = w;
  }
}

template <class Out>
void weld_into(Out& out, uint32_t* remap, uint32_t* out_indices, PositionSpan positions, const uint32_t* indices,
               size_t index_count, float tolerance) {
  if (tolerance > 0.0f && std::isfinite(tolerance))
    weld_tolerance(positions, tolerance, remap, out);
  else
    weld_exact(positions, remap, out);
  for (size_t i = 0; i < index_count; ++i) out_indices[i] = remap[indices[i]];
}

}  // namespace

size_t weld(float* out_positions, uint32_t* out_remap, uint32_t* out_indices, PositionSpan positions,
            const uint32_t* indices, size_t index_count, float tolerance) {
  GEOM_PRECONDITION_INDICES(indices, index_count, positions.size());
  GEOM_PRECONDITION(positions.empty() || (out_positions && out_remap),
                    "null output with " + std::to_string(positions.size()) + " vertices");
  ArrayOut out{out_positions};
  weld_into(out, out_remap, out_indices, positions, indices, index_count, tolerance);
  return out.size();
}

WeldResult weld(PositionSpan positions, const uint32_t* indices, size_t index_count, float tolerance) {
  GEOM_PRECONDITION_INDICES(indices, index_count, positions.size());
  WeldResult r;
  r.remap.resize(positions.size());
  r.indices.resize(index_count);
  // At most weld_bound welded vertices: one allocation, never grown (its
  // untouched tail is never paged in).
  r.positions.reserve(3 * weld_bound(positions.size()));
  VectorOut out{r.positions};
  weld_into(out, r.remap.data(), r.indices.data(), positions, indices, index_count, tolerance);
  return r;
}

}  // namespace geom
