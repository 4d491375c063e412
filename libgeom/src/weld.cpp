// Vertex welding by position (see geom/weld.h for the contract).
//
// Exact mode: an open-addressing hash table keyed by the coordinates' bit
// patterns (-0 folded onto +0), one probe sequence per vertex: O(n).
// Tolerance mode: a uniform grid of cell size `tolerance`; a vertex looks for
// the earliest representative within the tolerance in the 27 cells around it.
#include "geom/weld.h"

#include <cmath>
#include <cstring>
#include <unordered_map>

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

void weld_exact(PositionSpan p, WeldResult& r) {
  const size_t n = p.size();
  size_t capacity = 16;
  while (capacity < n * 2) capacity *= 2;
  std::vector<uint32_t> table(capacity, 0xffffffffu);  // welded vertex index per slot
  // At most n welded vertices: one allocation, never grown (its untouched tail
  // is never paged in). A slot's key is read back from the welded position.
  r.positions.reserve(3 * n);
  for (size_t i = 0; i < n; ++i) {
    const Float3& v = p[i];
    if (std::isnan(v.x) || std::isnan(v.y) || std::isnan(v.z)) {  // NaN never merges
      r.remap[i] = uint32_t(r.positions.size() / 3);
      r.positions.push_back(v.x), r.positions.push_back(v.y), r.positions.push_back(v.z);
      continue;
    }
    const uint32_t kx = float_key(v.x), ky = float_key(v.y), kz = float_key(v.z);
    uint64_t h = mix((uint64_t(kx) << 32 | ky) ^ mix(kz));
    size_t slot = h & (capacity - 1);
    for (;;) {
      uint32_t w = table[slot];
      if (w == 0xffffffffu) {
        w = uint32_t(r.positions.size() / 3);
        table[slot] = w;
        r.positions.push_back(v.x), r.positions.push_back(v.y), r.positions.push_back(v.z);
        r.remap[i] = w;
        break;
      }
      const float* q = r.positions.data() + 3 * size_t(w);
      if (float_key(q[0]) == kx && float_key(q[1]) == ky && float_key(q[2]) == kz) {
        r.remap[i] = w;
        break;
      }
      slot = (slot + 1) & (capacity - 1);
    }
  }
}

void weld_tolerance(PositionSpan p, float tolerance, WeldResult& r) {
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
              const float* q = &r.positions[3 * size_t(w)];
              double ex = double(q[0]) - v.x, ey = double(q[1]) - v.y, ez = double(q[2]) - v.z;
              if (ex * ex + ey * ey + ez * ez <= tol2) best = w;
            }
          }
    }
    if (best != 0xffffffffu) {
      r.remap[i] = best;
      continue;
    }
    uint32_t w = uint32_t(r.positions.size() / 3);
    r.positions.insert(r.positions.end(), {v.x, v.y, v.z});
    auto [it, inserted] = head.try_emplace(cell_hash(cx, cy, cz), w);
    next.push_back(inserted ? 0xffffffffu : it->second);
    it->second = w;
    r.remap[i] = w;
  }
}

}  // namespace

WeldResult weld(PositionSpan positions, const uint32_t* indices, size_t index_count, float tolerance) {
  WeldResult r;
  r.remap.resize(positions.size());
  if (tolerance > 0.0f && std::isfinite(tolerance))
    weld_tolerance(positions, tolerance, r);
  else
    weld_exact(positions, r);
  r.indices.resize(index_count);
  for (size_t i = 0; i < index_count; ++i) r.indices[i] = r.remap[indices[i]];
  return r;
}

}  // namespace geom
