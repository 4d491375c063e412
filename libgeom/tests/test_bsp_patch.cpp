// Quake 3 Bezier patches (libgeom/src/bsp_patch.cpp): tiny patches drawn
// here, the crack-free law on random shared borders, and watertight patches on
// OpenArena's real maps.
#include <gtest/gtest.h>

#include "bsp_patch.h"
#include "quake3_fixtures.h"

using namespace geom;
using namespace q3test;

// ---------------------------------------------------------------------------
// Bezier patches.

namespace {

std::vector<float> random_grid(std::mt19937& rng, int w, int h, double offset, double scale) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<float> g(size_t(w) * size_t(h) * 3);
  for (float& x : g) x = float(offset + scale * u(rng));
  return g;
}

// Control point (x, y) of a w-wide grid.
float* at(std::vector<float>& g, int w, int x, int y) { return &g[(size_t(y) * size_t(w) + size_t(x)) * 3]; }

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

}  // namespace

//  A 3x3 patch at level 2 is a 3x3 grid of points and 8 triangles:
//
//    6---7---8      y
//    | / | / |      ^
//    3---4---5      |
//    | / | / |      +--> x
//    0---1---2
//
// A flat patch in z = 0 interpolates its corners, passes through the middle
// of the control net, and every triangle faces +z (x cross y).
TEST(Quake3Patch, TinyFlatPatch) {
  std::vector<float> c;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) c.insert(c.end(), {float(x), float(y), 0.0f});
  std::vector<float> pts;
  detail::tessellate_patch(c.data(), 3, 3, 3, 2, pts);
  ASSERT_EQ(pts.size(), 27u);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      EXPECT_EQ(pts[size_t(3 * (3 * y + x))], float(x));
      EXPECT_EQ(pts[size_t(3 * (3 * y + x) + 1)], float(y));
      EXPECT_EQ(pts[size_t(3 * (3 * y + x) + 2)], 0.0f);
    }
  std::vector<uint32_t> idx;
  detail::patch_grid_triangles(3, 3, 10, idx);
  ASSERT_EQ(idx.size(), 24u);
  EXPECT_EQ((std::vector<uint32_t>(idx.begin(), idx.begin() + 6)), (std::vector<uint32_t>{10, 11, 14, 10, 14, 13}));
  for (size_t t = 0; t < 8; ++t) {
    const float* p[3];
    for (int j = 0; j < 3; ++j) p[j] = &pts[3 * (idx[3 * t + size_t(j)] - 10)];
    float z = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    EXPECT_GT(z, 0) << "triangle " << t;
  }
  EXPECT_EQ(detail::patch_triangle_count(3, 3, 2), 8u);
  EXPECT_EQ(detail::patch_triangle_count(9, 7, 4), 2u * 16 * 12);
}

// The law behind crack-free tessellation: a border shared by two patches (the
// same control points, forwards or backwards, on any side of either) comes out
// bit-identical, so an exact weld joins the two grids along the whole border.
// Random patches, far from the origin too, and with negative zeros.
TEST(Quake3Patch, SharedBordersAreBitIdentical) {
  std::mt19937 rng(46);
  std::uniform_int_distribution<int> half(1, 4), side(0, 3), coin(0, 1), lv(1, 9);
  for (int trial = 0; trial < 400; ++trial) {
    const int wa = 2 * half(rng) + 1, ha = 2 * half(rng) + 1;
    const double offset = trial % 3 == 0 ? 0.0 : trial % 3 == 1 ? 1e5 : -3e3;
    const double scale = trial % 5 == 0 ? 1e-3 : 100.0;
    std::vector<float> a = random_grid(rng, wa, ha, offset, scale);
    if (trial % 7 == 0)
      for (float& x : a) x = coin(rng) ? -0.0f : 0.0f;  // all zeros of both signs: a collapsed patch
    // The border of A along side sa, as a list of control points (a curve of length la).
    auto border = [](int w, int h, int side, int i) -> std::pair<int, int> {
      switch (side) {
        case 0:
          return {i, 0};  // bottom, x increasing
        case 1:
          return {w - 1, i};  // right, y increasing
        case 2:
          return {i, h - 1};  // top
        default:
          return {0, i};  // left
      }
    };
    const int sa = side(rng), la = (sa % 2 == 0) ? wa : ha;
    // B: another patch whose side sb has the same number of control points.
    const int sb = side(rng);
    const int other = 2 * half(rng) + 1;
    const int wb = (sb % 2 == 0) ? la : other, hb = (sb % 2 == 0) ? other : la;
    std::vector<float> b = random_grid(rng, wb, hb, offset, scale);
    const bool reversed = coin(rng);
    for (int i = 0; i < la; ++i) {
      auto [xa, ya] = border(wa, ha, sa, i);
      auto [xb, yb] = border(wb, hb, sb, reversed ? la - 1 - i : i);
      std::memcpy(at(b, wb, xb, yb), at(a, wa, xa, ya), 12);
    }
    const int level = lv(rng);
    std::vector<float> pa, pb;
    detail::tessellate_patch(a.data(), 3, wa, ha, level, pa);
    detail::tessellate_patch(b.data(), 3, wb, hb, level, pb);
    const int ca = int(detail::patch_columns(wa, level)), ra = int(detail::patch_rows(ha, level));
    const int cb = int(detail::patch_columns(wb, level)), rb = int(detail::patch_rows(hb, level));
    ASSERT_EQ(pa.size(), size_t(ca) * size_t(ra) * 3);
    const int n = (la - 1) / 2 * level + 1;  // tessellated points along the border
    for (int i = 0; i < n; ++i) {
      auto [xa, ya] = border(ca, ra, sa, i);
      auto [xb, yb] = border(cb, rb, sb, reversed ? n - 1 - i : i);
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(bits(pa[(size_t(ya) * size_t(ca) + size_t(xa)) * 3 + size_t(k)]),
                  bits(pb[(size_t(yb) * size_t(cb) + size_t(xb)) * 3 + size_t(k)]))
            << "trial " << trial << " point " << i << " level " << level;
    }
    if (trial % 7 == 0 || scale < 1) continue;  // collapsed or quantised patches: the weld merges more
    // Welded together, the shared border's 2(n-1) boundary edges become n-1 manifold ones.
    std::vector<float> pos = pa;
    pos.insert(pos.end(), pb.begin(), pb.end());
    std::vector<uint32_t> idx;
    detail::patch_grid_triangles(uint32_t(ca), uint32_t(ra), 0, idx);
    detail::patch_grid_triangles(uint32_t(cb), uint32_t(rb), uint32_t(ca * ra), idx);
    WeldResult w = weld(positions_of(pos.data(), pos.size() / 3), idx.data(), idx.size(), 0.0f);
    Topology topo =
        build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(), idx.size() / 3);
    const uint64_t boundary = 2u * uint64_t(ca - 1 + ra - 1) + 2u * uint64_t(cb - 1 + rb - 1);
    EXPECT_EQ(topo.stats.boundary_edges, boundary - 2u * uint64_t(n - 1)) << "trial " << trial;
    EXPECT_EQ(w.vertex_count(), pos.size() / 3 - size_t(n)) << "trial " << trial;
  }
}

// ---------------------------------------------------------------------------
// Real maps: every border curve (three control points along a patch side) that
// two patches share is tessellated into bit-identical points in both, read
// from the imported scene; and welding all patch triangles exactly leaves no
// crack: no two distinct boundary vertices of the patch surface closer than
// 1/100 unit. OpenArena's maps themselves hold control points that should
// coincide but differ in the last bit (832 -31.9999924 0 against 832 -32 0 in
// oa_dm3): on the maps as shipped, the gaps left are those (under 1e-3); with
// the control points snapped to a 1/16 grid first, none is left.
namespace {

struct PatchRef {
  uint32_t face, base, columns, rows;
};

struct CrackStats {
  size_t patches = 0, shared_curves = 0, near_pairs = 0;
  double max_gap = 0;
};

// Where each patch's grid lies in the scene (its first triangle starts at the
// grid's first point); the patches' triangles into `patch_tris`.
std::vector<PatchRef> locate_patches(const RawBsp& raw, const Scene& s, int level, std::vector<uint32_t>& patch_tris) {
  std::vector<PatchRef> patches;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const uint32_t f = s.sources[t].primitive;
    if (raw.faces[f].type != 2) continue;
    patch_tris.insert(patch_tris.end(), &s.indices[3 * t], &s.indices[3 * t] + 3);
    if (!patches.empty() && patches.back().face == f) continue;
    const RawFace& face = raw.faces[f];
    patches.push_back(
        {f, s.indices[3 * t], uint32_t((face.width - 1) / 2 * level + 1), uint32_t((face.height - 1) / 2 * level + 1)});
  }
  return patches;
}

// Border curves keyed by their control points (bits, -0 as +0), in a
// canonical direction: every patch that shares a curve has the same
// tessellated points along it.
void check_shared_curves(const RawBsp& raw, const Scene& s, const std::vector<PatchRef>& patches, int level,
                         CrackStats& st) {
  using Key = std::array<uint32_t, 9>;
  struct Use {
    size_t patch;
    int side, piece;
    bool reversed;
  };
  std::map<Key, std::vector<Use>> curves;
  for (size_t p = 0; p < patches.size(); ++p) {
    const RawFace& face = raw.faces[patches[p].face];
    const int w = face.width, h = face.height;
    auto cp = [&](int x, int y) { return raw.vertices[size_t(face.vertex) + size_t(y) * size_t(w) + size_t(x)]; };
    for (int side = 0; side < 4; ++side) {
      const int len = side % 2 == 0 ? w : h;
      for (int piece = 0; piece < (len - 1) / 2; ++piece) {
        Key fwd, bwd;
        for (int j = 0; j < 3; ++j) {
          const int i = 2 * piece + j;
          auto q = side == 0 ? cp(i, 0) : side == 1 ? cp(w - 1, i) : side == 2 ? cp(i, h - 1) : cp(0, i);
          for (int k = 0; k < 3; ++k) fwd[size_t(3 * j + k)] = bwd[size_t(3 * (2 - j) + k)] = bits(q[size_t(k)] + 0.0f);
        }
        const bool reversed = bwd < fwd;
        curves[reversed ? bwd : fwd].push_back({p, side, piece, reversed});
      }
    }
  }
  auto point = [&](const Use& u, int i) {  // i-th tessellated point along the curve, canonical direction
    const PatchRef& pr = patches[u.patch];
    const int j = u.piece * level + (u.reversed ? level - i : i);
    const uint32_t x = u.side == 0 || u.side == 2 ? uint32_t(j) : u.side == 1 ? pr.columns - 1 : 0;
    const uint32_t y = u.side == 1 || u.side == 3 ? uint32_t(j) : u.side == 2 ? pr.rows - 1 : 0;
    return &s.positions[3 * size_t(pr.base + y * pr.columns + x)];
  };
  for (auto& [key, uses] : curves) {
    if (uses.size() < 2) continue;
    ++st.shared_curves;
    for (size_t u = 1; u < uses.size(); ++u)
      for (int i = 0; i <= level; ++i)
        EXPECT_EQ(0, std::memcmp(point(uses[0], i), point(uses[u], i), 12))
            << "faces " << patches[uses[0].patch].face << " and " << patches[uses[u].patch].face << " point " << i;
  }
}

// Cracks: distinct boundary vertices of the welded patch surface that almost coincide.
void count_cracks(const Scene& s, const std::vector<uint32_t>& patch_tris, CrackStats& st) {
  WeldResult w = weld(positions_of(s.positions.data(), s.vertex_count()), patch_tris.data(), patch_tris.size());
  Topology topo =
      build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(), patch_tris.size() / 3);
  std::set<uint32_t> rim;
  for (const Edge& e : topo.edges)
    if (e.kind == EdgeKind::Boundary) rim.insert({e.v0, e.v1});
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells;  // a 1-unit grid
  auto cell = [](float x) { return int64_t(std::floor(double(x))); };
  auto key3 = [](int64_t x, int64_t y, int64_t z) {
    return uint64_t(x & 0x1fffff) | uint64_t(y & 0x1fffff) << 21 | uint64_t(z & 0x1fffff) << 42;
  };
  for (uint32_t v : rim) {
    const float* p = &w.positions[3 * size_t(v)];
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          auto it = cells.find(key3(cell(p[0]) + dx, cell(p[1]) + dy, cell(p[2]) + dz));
          if (it == cells.end()) continue;
          for (uint32_t o : it->second) {
            const float* q = &w.positions[3 * size_t(o)];
            double d = std::hypot(double(p[0]) - q[0], double(p[1]) - q[1], double(p[2]) - q[2]);
            if (d < 0.01) ++st.near_pairs, st.max_gap = std::max(st.max_gap, d);
          }
        }
    cells[key3(cell(p[0]), cell(p[1]), cell(p[2]))].push_back(v);
  }
}

CrackStats check_patches(const RawBsp& raw, const Scene& s, int level) {
  CrackStats st;
  std::vector<uint32_t> patch_tris;
  const std::vector<PatchRef> patches = locate_patches(raw, s, level, patch_tris);
  st.patches = patches.size();
  check_shared_curves(raw, s, patches, level, st);
  count_cracks(s, patch_tris, st);
  return st;
}

}  // namespace

TEST(Quake3Patch, RealMapsWatertight) {
  size_t shared_total = 0, raw_near = 0;
  for (const char* map : {"oa_dm3.bsp", "oa_dm5.bsp", "pul1ctf.bsp", "oa_shouse.bsp", "kaos.bsp"}) {
    SCOPED_TRACE(map);
    const RawBsp raw = raw_map(map);
    // The same map with every patch control point snapped to a 1/16 grid.
    std::vector<unsigned char> snapped_bytes = raw.bytes;
    for (const RawFace& face : raw.faces) {
      if (face.type != 2) continue;
      for (int32_t v = face.vertex; v < face.vertex + face.vertex_count; ++v)
        for (int k = 0; k < 3; ++k) {
          const size_t at = size_t(raw.lump_offset(10)) + 44 * size_t(v) + 4 * size_t(k);
          put(snapped_bytes, at, std::round(get<float>(snapped_bytes, at) * 16.0f) / 16.0f);
        }
    }
    const RawBsp snapped = parse_raw(snapped_bytes);
    for (int level : {2, 4, 7}) {
      SCOPED_TRACE("level " + std::to_string(level));
      ImportResult r = import_bytes(map, raw.bytes, level);
      ASSERT_TRUE(r.ok) << r.error;
      CrackStats a = check_patches(raw, r.scene, level);
      EXPECT_LT(a.max_gap, 1e-3);
      ImportResult rs = import_bytes(map, snapped.bytes, level);
      ASSERT_TRUE(rs.ok) << rs.error;
      CrackStats b = check_patches(snapped, rs.scene, level);
      EXPECT_EQ(b.near_pairs, 0u) << "largest gap " << b.max_gap;
      EXPECT_EQ(a.patches, b.patches);
      EXPECT_GE(b.shared_curves, a.shared_curves);
      shared_total += a.shared_curves, raw_near += a.near_pairs;
      std::printf("%s level %d: %zu patches, %zu shared border curves (%zu snapped), %zu file-noise gaps (max %.3g)\n",
                  map, level, a.patches, a.shared_curves, b.shared_curves, a.near_pairs, a.max_gap);
    }
  }
  EXPECT_GT(shared_total, 1000u);
}
