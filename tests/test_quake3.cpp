// Quake 3 BSP and MD3 import (libgeom/src/import_bsp.cpp, bsp_patch.cpp,
// import_md3.cpp) on OpenArena's real maps and models (Debian packages
// openarena-081-maps and openarena-081-players), on a tiny map built here, and
// on hostile files.
//
// The "independent parse" below reads the lumps with its own code (memcpy of
// little-endian records), never through the importer.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include <embree3/rtcore.h>

#include "archive.h"
#include "bsp_patch.h"
#include "geom/extrude.h"
#include "geom/face_planes.h"
#include "geom/import.h"
#include "geom/report.h"
#include "geom/shadow_volume.h"
#include "geom/topology.h"
#include "geom/weld.h"

using namespace geom;

namespace {

const std::string kBaseoa = "/usr/share/games/openarena/baseoa/";
const std::string kMaps = kBaseoa + "pak1-maps.pk3";
const std::string kPlayers = kBaseoa + "pak2-players.pk3";

std::vector<unsigned char> member(const std::string& archive, const std::string& name) {
  std::vector<unsigned char> bytes;
  std::string error;
  EXPECT_TRUE(detail::read_archive_member(archive, name, bytes, 0, error)) << error;
  return bytes;
}

template <class T>
T get(const std::vector<unsigned char>& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}
template <class T>
void put(std::vector<unsigned char>& b, size_t at, T v) {
  std::memcpy(b.data() + at, &v, sizeof v);
}

uint64_t count_of(const Scene& s, const std::string& key) {
  for (auto& [k, v] : s.source_counts)
    if (k == key) return v;
  ADD_FAILURE() << "no source count " << key;
  return ~uint64_t(0);
}

// ---------------------------------------------------------------------------
// Independent parse of a BSP's lumps.
struct RawFace {
  int32_t texture, type, vertex, vertex_count, meshvert, meshvert_count, width, height;
  float normal[3];
};
struct RawBsp {
  std::vector<unsigned char> bytes;
  std::vector<RawFace> faces;
  std::vector<int32_t> texture_flags;
  std::vector<std::pair<int32_t, int32_t>> models;  // first face, face count
  std::vector<std::array<float, 3>> vertices;
  std::vector<int32_t> meshverts;
  int32_t lump_offset(int l) const { return get<int32_t>(bytes, 8 + 8 * l); }
  int32_t lump_length(int l) const { return get<int32_t>(bytes, 12 + 8 * l); }
  size_t face_offset(size_t f) const { return size_t(lump_offset(13)) + 104 * f; }
  int model_of(size_t f) const {
    for (size_t m = 0; m < models.size(); ++m)
      if (int64_t(f) >= models[m].first && int64_t(f) < models[m].first + models[m].second) return int(m);
    return -1;
  }
  bool nodraw(const RawFace& f) const { return texture_flags[size_t(f.texture)] & 0x80; }
};

RawBsp parse_raw(std::vector<unsigned char> bytes) {
  RawBsp r;
  r.bytes = std::move(bytes);
  for (int32_t o = r.lump_offset(1), n = r.lump_length(1) / 72, i = 0; i < n; ++i)
    r.texture_flags.push_back(get<int32_t>(r.bytes, size_t(o) + 72 * size_t(i) + 64));
  for (int32_t o = r.lump_offset(7), n = r.lump_length(7) / 40, i = 0; i < n; ++i)
    r.models.push_back({get<int32_t>(r.bytes, size_t(o) + 40 * size_t(i) + 24),
                        get<int32_t>(r.bytes, size_t(o) + 40 * size_t(i) + 28)});
  for (int32_t o = r.lump_offset(10), n = r.lump_length(10) / 44, i = 0; i < n; ++i)
    r.vertices.push_back(get<std::array<float, 3>>(r.bytes, size_t(o) + 44 * size_t(i)));
  for (int32_t o = r.lump_offset(11), n = r.lump_length(11) / 4, i = 0; i < n; ++i)
    r.meshverts.push_back(get<int32_t>(r.bytes, size_t(o) + 4 * size_t(i)));
  for (int32_t n = r.lump_length(13) / 104, i = 0; i < n; ++i) {
    size_t at = r.face_offset(size_t(i));
    RawFace f;
    f.texture = get<int32_t>(r.bytes, at);
    f.type = get<int32_t>(r.bytes, at + 8);
    f.vertex = get<int32_t>(r.bytes, at + 12);
    f.vertex_count = get<int32_t>(r.bytes, at + 16);
    f.meshvert = get<int32_t>(r.bytes, at + 20);
    f.meshvert_count = get<int32_t>(r.bytes, at + 24);
    std::memcpy(f.normal, r.bytes.data() + at + 84, 12);
    f.width = get<int32_t>(r.bytes, at + 96);
    f.height = get<int32_t>(r.bytes, at + 100);
    r.faces.push_back(f);
  }
  return r;
}

RawBsp raw_map(const std::string& name) { return parse_raw(member(kMaps, "maps/" + name)); }

ImportResult import_bytes(const std::string& name, const std::vector<unsigned char>& b, int level = 4) {
  ImportOptions o;
  o.patch_level = level;
  return import_memory(name, b.data(), b.size(), o);
}

// Maps chosen for their mix: brush models and mesh faces (oa_dm1), 9x7 patches
// and sky (oa_ctf2), many patch sizes (oa_dm3, oa_dm5), never-drawn patches
// (delta, oa_spirit3), polygons only (q3dm6ish).
const char* const kCountMaps[] = {"oa_dm1.bsp", "oa_ctf2.bsp", "oa_dm3.bsp", "oa_dm5.bsp",
                                  "delta.bsp",  "oa_spirit3.bsp", "q3dm6ish.bsp"};

}  // namespace

// ---------------------------------------------------------------------------
// Counts per face type and per face equal the independent parse; every
// polygon/mesh triangle is the file's triangle with its winding reversed.
namespace {

void check_counts(const std::string& map, const RawBsp& raw, int level) {
  SCOPED_TRACE(map + " level " + std::to_string(level));
  ImportResult r = import_bytes(map, raw.bytes, level);
  ASSERT_TRUE(r.ok) << r.error;
  const Scene& s = r.scene;
  std::map<int, uint64_t> faces, tris;
  uint64_t nodraw = 0, sky = 0;
  std::vector<uint64_t> per_face(raw.faces.size(), 0);
  for (size_t f = 0; f < raw.faces.size(); ++f) {
    const RawFace& face = raw.faces[f];
    faces[face.type]++;
    nodraw += raw.nodraw(face);
    sky += (raw.texture_flags[size_t(face.texture)] & 0x4) != 0;
    if (raw.nodraw(face) || raw.model_of(f) < 0) continue;
    if (face.type == 1 || face.type == 3) per_face[f] = uint64_t(face.meshvert_count / 3);
    if (face.type == 2) {
      uint64_t cells_x = uint64_t(face.width - 1) / 2 * uint64_t(level), cells_y = uint64_t(face.height - 1) / 2 * uint64_t(level);
      per_face[f] = 2 * cells_x * cells_y;
    }
    tris[face.type] += per_face[f];
  }
  EXPECT_EQ(count_of(s, "polygon.faces"), faces[1]);
  EXPECT_EQ(count_of(s, "patch.faces"), faces[2]);
  EXPECT_EQ(count_of(s, "mesh.faces"), faces[3]);
  EXPECT_EQ(count_of(s, "billboard.faces"), faces[4]);
  EXPECT_EQ(count_of(s, "polygon.triangles"), tris[1]);
  EXPECT_EQ(count_of(s, "patch.triangles"), tris[2]);
  EXPECT_EQ(count_of(s, "mesh.triangles"), tris[3]);
  EXPECT_EQ(count_of(s, "nodraw.faces"), nodraw);
  EXPECT_EQ(count_of(s, "sky.faces"), sky);
  EXPECT_EQ(s.triangle_count(), tris[1] + tris[2] + tris[3]);
  ASSERT_EQ(s.sources.size(), s.triangle_count());

  // Per face: the triangles it produced, their model, and (polygons and
  // meshes) their corners, in the file's order reversed.
  size_t t = 0;
  for (size_t m = 0; m < raw.models.size(); ++m) {
    for (int32_t f = raw.models[m].first; f < raw.models[m].first + raw.models[m].second; ++f) {
      const RawFace& face = raw.faces[size_t(f)];
      for (uint64_t k = 0; k < per_face[size_t(f)]; ++k, ++t) {
        ASSERT_LT(t, s.sources.size());
        ASSERT_EQ(s.sources[t].primitive, uint32_t(f));
        ASSERT_EQ(s.sources[t].mesh, uint32_t(m));
        if (face.type == 2) continue;
        const int order[3] = {0, 2, 1};
        for (int j = 0; j < 3; ++j) {
          const auto& want =
              raw.vertices[size_t(face.vertex + raw.meshverts[size_t(face.meshvert) + 3 * k + size_t(order[j])])];
          const float* got = &s.positions[3 * size_t(s.indices[3 * t + size_t(j)])];
          ASSERT_EQ(0, std::memcmp(got, want.data(), 12)) << "face " << f << " triangle " << k;
        }
      }
    }
  }
  EXPECT_EQ(t, s.triangle_count());
  // No vertex is kept that no triangle uses.
  std::vector<bool> used(s.vertex_count(), false);
  for (uint32_t i : s.indices) used[i] = true;
  EXPECT_EQ(size_t(std::count(used.begin(), used.end(), true)), s.vertex_count());
}

}  // namespace

TEST(Quake3Bsp, CountsEqualIndependentParse) {
  for (const char* map : kCountMaps) {
    const RawBsp raw = raw_map(map);
    for (int level : {1, 4, 7}) check_counts(map, raw, level);
  }
}

// Every map of Debian's openarena-081-maps, at the default level.
TEST(Quake3Bsp, EveryShippedMapEqualsIndependentParse) {
  std::vector<std::string> names;
  std::string error;
  ASSERT_TRUE(detail::list_archive_members(kMaps, ".bsp", names, error)) << error;
  ASSERT_GE(names.size(), 40u);
  for (const std::string& name : names) check_counts(name, parse_raw(member(kMaps, name)), 4);
}

// The front of every polygon triangle (counter-clockwise after import) faces
// the same way as its face's stored normal (allowing the rare sliver the map
// compiler wound the other way).
TEST(Quake3Bsp, PolygonWindingFollowsFaceNormal) {
  for (const char* map : {"oa_dm1.bsp", "oa_ctf2.bsp", "oa_dm4.bsp"}) {
    SCOPED_TRACE(map);
    const RawBsp raw = raw_map(map);
    ImportResult r = import_bytes(map, raw.bytes);
    ASSERT_TRUE(r.ok) << r.error;
    const Scene& s = r.scene;
    size_t agree = 0, disagree = 0;
    for (size_t t = 0; t < s.triangle_count(); ++t) {
      const RawFace& face = raw.faces[s.sources[t].primitive];
      if (face.type != 1) continue;
      const float* p[3];
      for (int j = 0; j < 3; ++j) p[j] = &s.positions[3 * size_t(s.indices[3 * t + size_t(j)])];
      double u[3], v[3];
      for (int k = 0; k < 3; ++k) u[k] = p[1][k] - p[0][k], v[k] = p[2][k] - p[0][k];
      double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      double d = n[0] * face.normal[0] + n[1] * face.normal[1] + n[2] * face.normal[2];
      if (std::fabs(d) < 1e-3) continue;  // slivers
      (d > 0 ? agree : disagree)++;
    }
    EXPECT_GT(agree, 1000u);
    EXPECT_LE(disagree * 100, agree) << disagree << " triangles face against their face normal";
  }
}

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
        case 0: return {i, 0};          // bottom, x increasing
        case 1: return {w - 1, i};      // right, y increasing
        case 2: return {i, h - 1};      // top
        default: return {0, i};         // left
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
    Topology topo = build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(),
                                   idx.size() / 3);
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

CrackStats check_patches(const RawBsp& raw, const Scene& s, int level) {
  CrackStats st;
  // Where each patch's grid lies in the scene (its first triangle starts at the grid's first point).
  std::vector<PatchRef> patches;
  std::vector<uint32_t> patch_tris;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const uint32_t f = s.sources[t].primitive;
    if (raw.faces[f].type != 2) continue;
    patch_tris.insert(patch_tris.end(), &s.indices[3 * t], &s.indices[3 * t] + 3);
    if (!patches.empty() && patches.back().face == f) continue;
    const RawFace& face = raw.faces[f];
    patches.push_back({f, s.indices[3 * t], uint32_t((face.width - 1) / 2 * level + 1),
                       uint32_t((face.height - 1) / 2 * level + 1)});
  }
  st.patches = patches.size();
  // Border curves keyed by their control points (bits, -0 as +0), in a canonical direction.
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
  // Cracks: distinct boundary vertices of the welded patch surface that almost coincide.
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

// ---------------------------------------------------------------------------
// A tiny map built here, and hostile variants of it and of real maps.
namespace {

struct TinyFace {
  int32_t texture = 0, type = 1, vertex = 0, vertex_count = 0, meshvert = 0, meshvert_count = 0;
  int32_t width = 0, height = 0;
};

// Writes an IBSP 46 file: header, then textures, models, vertexes, mesh
// vertices and faces; the other lumps empty.
struct BspBuilder {
  std::vector<int32_t> shader_flags{0};
  std::vector<std::array<float, 3>> vertices;
  std::vector<int32_t> meshverts;
  std::vector<TinyFace> faces;
  std::vector<std::pair<int32_t, int32_t>> models;

  std::vector<unsigned char> bytes() const {
    std::vector<unsigned char> b(8 + 17 * 8, 0);
    std::memcpy(b.data(), "IBSP", 4);
    put<int32_t>(b, 4, 46);
    auto lump = [&](int l, const std::vector<unsigned char>& data) {
      put<int32_t>(b, 8 + 8 * size_t(l), int32_t(b.size()));
      put<int32_t>(b, 12 + 8 * size_t(l), int32_t(data.size()));
      b.insert(b.end(), data.begin(), data.end());
    };
    for (int l = 0; l < 17; ++l) put<int32_t>(b, 8 + 8 * size_t(l), int32_t(b.size()));
    std::vector<unsigned char> d;
    for (int32_t fl : shader_flags) {
      std::vector<unsigned char> rec(72, 0);
      std::memcpy(rec.data(), "textures/tiny", 13);
      put(rec, 64, fl);
      d.insert(d.end(), rec.begin(), rec.end());
    }
    lump(1, d);
    d.clear();
    for (auto [first, count] : models) {
      std::vector<unsigned char> rec(40, 0);
      put(rec, 24, first), put(rec, 28, count);
      d.insert(d.end(), rec.begin(), rec.end());
    }
    lump(7, d);
    d.clear();
    for (auto& v : vertices) {
      std::vector<unsigned char> rec(44, 0);
      std::memcpy(rec.data(), v.data(), 12);
      d.insert(d.end(), rec.begin(), rec.end());
    }
    lump(10, d);
    d.assign(meshverts.size() * 4, 0);
    if (!meshverts.empty()) std::memcpy(d.data(), meshverts.data(), d.size());
    lump(11, d);
    d.clear();
    for (const TinyFace& f : faces) {
      std::vector<unsigned char> rec(104, 0);
      put(rec, 0, f.texture), put(rec, 4, int32_t(-1)), put(rec, 8, f.type), put(rec, 12, f.vertex);
      put(rec, 16, f.vertex_count), put(rec, 20, f.meshvert), put(rec, 24, f.meshvert_count);
      put(rec, 96, f.width), put(rec, 100, f.height);
      d.insert(d.end(), rec.begin(), rec.end());
    }
    lump(13, d);
    return b;
  }
};

//  The tiny map. Model 0 (the world):
//    face 0, polygon: the unit square in z = 0, stored clockwise seen from +z
//    (Quake's front) as (0,2,1) (0,3,2):
//        3-------2
//        |     / |
//        |   /   |
//        | /     |
//        0-------1
//    face 1, patch: 3x3 control points, flat in z = 1 over [0,2]^2 (vertices 4..12)
//    face 2, billboard
//  Model 1 (a door):
//    face 3, mesh: one triangle (13, 14, 15) stored clockwise
BspBuilder tiny_map() {
  BspBuilder b;
  b.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) b.vertices.push_back({float(x), float(y), 1});
  b.vertices.insert(b.vertices.end(), {{5, 0, 0}, {5, 1, 0}, {6, 0, 0}});
  b.meshverts = {0, 2, 1, 0, 3, 2, 0, 1, 2};
  TinyFace polygon;
  polygon.vertex = 0, polygon.vertex_count = 4, polygon.meshvert = 0, polygon.meshvert_count = 6;
  TinyFace patch;
  patch.type = 2, patch.vertex = 4, patch.vertex_count = 9, patch.width = 3, patch.height = 3;
  TinyFace billboard;
  billboard.type = 4, billboard.vertex = 0, billboard.vertex_count = 4;
  TinyFace mesh;
  mesh.type = 3, mesh.vertex = 13, mesh.vertex_count = 3, mesh.meshvert = 6, mesh.meshvert_count = 3;
  b.faces = {polygon, patch, billboard, mesh};
  b.models = {{0, 3}, {3, 1}};
  return b;
}

std::string refusal(const std::vector<unsigned char>& bytes, const std::string& name = "hostile.bsp",
                    ImportOptions options = {}) {
  ImportResult r = import_memory(name, bytes.data(), bytes.size(), options);
  if (r.ok) return "accepted";
  EXPECT_EQ(r.error.rfind(name + ": ", 0), 0u) << r.error;  // names the file first
  EXPECT_TRUE(r.scene.positions.empty() && r.scene.indices.empty());
  return r.error;
}

}  // namespace

TEST(Quake3Bsp, TinyMap) {
  const std::vector<unsigned char> bytes = tiny_map().bytes();
  ImportOptions o;
  o.patch_level = 2;
  ImportResult r = import_memory("tiny.bsp", bytes.data(), bytes.size(), o);
  ASSERT_TRUE(r.ok) << r.error;
  const Scene& s = r.scene;
  // 2 polygon triangles, 8 patch triangles (level 2), 1 mesh triangle.
  ASSERT_EQ(s.triangle_count(), 11u);
  EXPECT_EQ(count_of(s, "polygon.faces"), 1u);
  EXPECT_EQ(count_of(s, "polygon.triangles"), 2u);
  EXPECT_EQ(count_of(s, "patch.faces"), 1u);
  EXPECT_EQ(count_of(s, "patch.triangles"), 8u);
  EXPECT_EQ(count_of(s, "mesh.faces"), 1u);
  EXPECT_EQ(count_of(s, "mesh.triangles"), 1u);
  EXPECT_EQ(count_of(s, "billboard.faces"), 1u);
  EXPECT_EQ(count_of(s, "nodraw.faces"), 0u);
  // The polygon, counter-clockwise from +z now: (0,1,2) (0,2,3).
  auto corner = [&](size_t t, int j) {
    const float* p = &s.positions[3 * size_t(s.indices[3 * t + size_t(j)])];
    return std::array<float, 3>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(corner(0, 0), (std::array<float, 3>{0, 0, 0}));
  EXPECT_EQ(corner(0, 1), (std::array<float, 3>{1, 0, 0}));
  EXPECT_EQ(corner(0, 2), (std::array<float, 3>{1, 1, 0}));
  EXPECT_EQ(corner(1, 2), (std::array<float, 3>{0, 1, 0}));
  // Every triangle faces +z, and the sources say where each came from.
  for (size_t t = 0; t < 11; ++t) {
    auto a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0) << t;
    const uint32_t face = t < 2 ? 0 : t < 10 ? 1 : 3;
    EXPECT_EQ(s.sources[t].primitive, face);
    EXPECT_EQ(s.sources[t].mesh, face == 3 ? 1u : 0u);
  }
  // Vertices: 4 polygon (shared by its 2 triangles) + 9 patch + 3 mesh; the
  // billboard adds none.
  EXPECT_EQ(s.vertex_count(), 16u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("1 billboard faces skipped"), std::string::npos) << s.warnings[0];

  // A never-drawn shader on the patch: counted and skipped.
  BspBuilder nodraw = tiny_map();
  nodraw.shader_flags.push_back(0x80);
  nodraw.faces[1].texture = 1;
  r = import_memory("tiny.bsp", nodraw.bytes().data(), nodraw.bytes().size(), o);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.triangle_count(), 3u);
  EXPECT_EQ(count_of(r.scene, "nodraw.faces"), 1u);
  EXPECT_EQ(count_of(r.scene, "patch.faces"), 1u);
  EXPECT_EQ(count_of(r.scene, "patch.triangles"), 0u);
}

// Hostile files: each refused with a message naming the problem.
TEST(Quake3Bsp, HostileFilesRefused) {
  auto with = [](auto edit) {
    BspBuilder b = tiny_map();
    edit(b);
    return b.bytes();
  };
  auto expect_refused = [](const std::vector<unsigned char>& bytes, const std::string& words,
                           ImportOptions options = {}) {
    const std::string e = refusal(bytes, "hostile.bsp", options);
    EXPECT_NE(e.find(words), std::string::npos) << "wanted '" << words << "' in: " << e;
  };
  const std::vector<unsigned char> good = tiny_map().bytes();
  ASSERT_EQ(refusal(good), "accepted");

  // Header and lumps.
  expect_refused({}, "shorter than the 144-byte BSP header");
  std::vector<unsigned char> b = good;
  b[0] = 'X';
  expect_refused(b, "no 'IBSP' magic");
  b = good, put<int32_t>(b, 4, 47);
  expect_refused(b, "version 47");
  b = good, put<int32_t>(b, 8 + 8 * 13, int32_t(good.size()) + 1);  // faces lump offset past the end
  expect_refused(b, "faces lump (offset");
  b = good, put<int32_t>(b, 8 + 8 * 10, 0x7fffff00), put<int32_t>(b, 12 + 8 * 10, 0x7fffff00);  // sum overflows 32 bits
  expect_refused(b, "vertexes lump (offset 2147483392, length 2147483392) lies outside the file");
  b = good, put<int32_t>(b, 12 + 8 * 3, -8);
  expect_refused(b, "nodes lump");
  b = good, put<int32_t>(b, 12 + 8 * 13, 103);
  expect_refused(b, "not a multiple of its 104-byte record");

  // Faces.
  expect_refused(with([](BspBuilder& m) { m.faces[0].type = 0; }), "face 0 (face) has unknown type 0");
  expect_refused(with([](BspBuilder& m) { m.faces[0].type = 5; }), "unknown type 5");
  expect_refused(with([](BspBuilder& m) { m.faces[0].texture = 1; }), "face 0 (polygon) uses shader 1, out of range");
  expect_refused(with([](BspBuilder& m) { m.faces[0].texture = -1; }), "uses shader -1");
  expect_refused(with([](BspBuilder& m) { m.faces[0].vertex = 0x7ffffffe, m.faces[0].vertex_count = 10; }),
                 "uses vertices 2147483646 to 2147483656, out of range");
  expect_refused(with([](BspBuilder& m) { m.faces[0].meshvert_count = 0x7fffffff; }), "uses mesh vertices 0 to");
  expect_refused(with([](BspBuilder& m) { m.faces[0].meshvert = -3; }), "uses mesh vertices -3");
  expect_refused(with([](BspBuilder& m) { m.meshverts[4] = 4; }),
                 "face 0 (polygon) mesh vertex 4 = 4, out of range (the face has 4 vertices)");
  expect_refused(with([](BspBuilder& m) { m.meshverts[7] = -1; }), "face 3 (mesh) mesh vertex 7 = -1");
  expect_refused(with([](BspBuilder& m) { m.faces[0].meshvert_count = 5; }), "5 mesh vertices, not a multiple of 3");
  expect_refused(with([](BspBuilder& m) { m.vertices[2][1] = NAN; }), "face 0 (polygon) uses vertex 2 with a non-finite");
  expect_refused(with([](BspBuilder& m) { m.vertices[3][0] = INFINITY; }), "non-finite");

  // Patches: even, absurd, too small, inconsistent with the vertex count, NaN.
  expect_refused(with([](BspBuilder& m) { m.faces[1].width = 4, m.faces[1].height = 3, m.faces[1].vertex_count = 12; }),
                 "face 1 (patch) has 4 x 3 control points (each side must be odd, from 3 to 65)");
  expect_refused(with([](BspBuilder& m) { m.faces[1].width = 1000001; }), "has 1000001 x 3 control points");
  expect_refused(with([](BspBuilder& m) { m.faces[1].height = 1000000, m.faces[1].vertex_count = 3000000; }),
                 "vertices 4 to 3000004, out of range");
  expect_refused(with([](BspBuilder& m) { m.faces[1].width = 1; }), "has 1 x 3 control points");
  expect_refused(with([](BspBuilder& m) { m.faces[1].width = -3; }), "has -3 x 3 control points");
  expect_refused(with([](BspBuilder& m) { m.faces[1].vertex_count = 8; }), "has 3 x 3 control points but 8 vertices");
  expect_refused(with([](BspBuilder& m) { m.vertices[8][2] = NAN; }),
                 "face 1 (patch) control point 4 has a non-finite coordinate");

  // Models.
  expect_refused(with([](BspBuilder& m) { m.models[1] = {3, 2}; }), "model 1 uses faces 3 to 5, out of range (4 faces)");
  expect_refused(with([](BspBuilder& m) { m.models[0] = {-1, 2}; }), "model 0 uses faces -1 to 1");
  expect_refused(with([](BspBuilder& m) { m.models[1] = {2, 2}; }), "face 2 belongs to both model 0 and model 1");
  expect_refused(with([](BspBuilder& m) { m.models.clear(); }), "models lump is empty");

  // Amplification: mesh-vertex and vertex ranges may overlap, so a small file
  // can claim any number of triangles; the total is checked before allocating.
  expect_refused(with([](BspBuilder& m) {
                   // 65 x 65 control points on one shared block of vertices, 8 faces at level 64:
                   // 8 x 2 x 2048^2 = 67M triangles (plus the tiny map's own at level 64) from 70 kB.
                   m.vertices.resize(13 + 65 * 65, {1, 2, 3});
                   for (int i = 0; i < 8; ++i) {
                     TinyFace f;
                     f.type = 2, f.vertex = 13, f.vertex_count = 65 * 65, f.width = 65, f.height = 65;
                     m.faces.push_back(f);
                   }
                   m.models[0] = {0, 3}, m.models[1] = {3, 9};
                 }),
                 "would produce 67117059 triangles (67117056 from patches at level 64), over the limit of 16777216", [] {
                   ImportOptions o;
                   o.patch_level = 64;
                   return o;
                 }());
  ImportOptions small;
  small.max_triangles = 4;
  expect_refused(good, "would produce 35 triangles (32 from patches at level 4), over the limit of 4", small);
  ImportOptions level;
  level.patch_level = 0;
  expect_refused(good, "patch level 0 is out of range (1 to 64)", level);
  level.patch_level = 65;
  expect_refused(good, "patch level 65 is out of range", level);
}

// Real-map mutations: corrupt fields of oa_ctf2's faces, models and lump
// directory; whatever is changed, the import either succeeds with a valid
// scene or is refused with a message, never crashes.
TEST(Quake3Bsp, RealMapMutationsRefusedCleanly) {
  const RawBsp raw = raw_map("oa_ctf2.bsp");
  std::mt19937 rng(3);
  const int32_t values[] = {-1, 0, 1, 2, 3, 4, 5, 7, 65, 66, 1000001, 0x7fffffff, int32_t(0x80000000), 104, 1 << 20};
  size_t refused = 0, accepted = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<unsigned char> b = raw.bytes;
    size_t at;
    switch (trial % 3) {
      case 0: at = 8 + 4 * (rng() % 34); break;                                        // lump directory
      case 1: at = raw.face_offset(rng() % raw.faces.size()) + 4 * (rng() % 26); break;  // a face field
      default: at = size_t(raw.lump_offset(7)) + 40 * (rng() % raw.models.size()) + 24 + 4 * (rng() % 2); break;
    }
    put<int32_t>(b, at, values[rng() % (sizeof values / sizeof values[0])]);
    ImportOptions o;
    o.max_triangles = 1u << 20;
    ImportResult r = import_memory("mutant.bsp", b.data(), b.size(), o);
    if (r.ok) {
      ++accepted;
      for (uint32_t i : r.scene.indices) ASSERT_LT(i, r.scene.vertex_count());
    } else {
      ++refused;
      EXPECT_EQ(r.error.rfind("mutant.bsp: ", 0), 0u);
      EXPECT_GT(r.error.size(), 20u);
    }
  }
  EXPECT_GT(refused, 100u);
  EXPECT_GT(accepted, 10u);
}

// Every truncation of a small real map is refused cleanly: all of the first
// 200 prefix lengths, and 300 more spread over the file.
TEST(Quake3Bsp, TruncationsRefused) {
  const std::vector<unsigned char> full = member(kMaps, "maps/oa_ctf2.bsp");
  ASSERT_GT(full.size(), 600000u);
  ASSERT_EQ(refusal(full, "oa_ctf2.bsp"), "accepted");
  std::vector<size_t> lengths;
  for (size_t n = 0; n < 200; ++n) lengths.push_back(n);
  for (size_t k = 0; k < 300; ++k) lengths.push_back(200 + (full.size() - 201) * k / 299);
  lengths.push_back(full.size() - 1);
  for (size_t n : lengths) {
    ASSERT_LT(n, full.size());
    const std::vector<unsigned char> prefix(full.begin(), full.begin() + long(n));
    const std::string e = refusal(prefix, "oa_ctf2.bsp");
    ASSERT_NE(e, "accepted") << n << " bytes";
    if (n < 144)
      EXPECT_NE(e.find("truncated"), std::string::npos) << e;
    else
      EXPECT_NE(e.find("lies outside the file"), std::string::npos) << e;
  }
}

// Through the pipeline: the report of a real map carries the counts per face
// type, and the topology of the world is that of a game level: open, with
// non-manifold edges (seed 004, section 2.2: "each edge in the world can be
// shared by more than two faces").
TEST(Quake3Bsp, ReportOfRealMap) {
  ImportResult r = import_file(kMaps + ":maps/oa_ctf2.bsp");
  ASSERT_TRUE(r.ok) << r.error;
  Report report;
  report.file = "oa_ctf2.bsp";
  analyze(r.scene, 0.0f, {}, false, report);
  const std::string json = report_json(report);
  EXPECT_NE(json.find("\"source_faces\":{\"polygon\":{\"faces\":1290,\"triangles\":3065},\"mesh\":{\"faces\":0,"
                      "\"triangles\":0},\"patch\":{\"faces\":42,\"triangles\":16128},\"billboard\":{\"faces\":34},"
                      "\"nodraw\":{\"faces\":0},\"sky\":{\"faces\":6}}"),
            std::string::npos)
      << json;
  EXPECT_FALSE(report.stats.closed);
  EXPECT_GT(report.stats.non_manifold_edges, 0u);
  EXPECT_GT(report.stats.boundary_edges, 0u);
  EXPECT_EQ(report.stats.triangles, 3065u + 16128u);
  // A missing member names the archive and the member.
  ImportResult missing = import_file(kMaps + ":maps/no_such_map.bsp");
  EXPECT_FALSE(missing.ok);
  EXPECT_NE(missing.error.find("no member 'maps/no_such_map.bsp'"), std::string::npos) << missing.error;
}

// ---------------------------------------------------------------------------
// MD3 models.
namespace {

// Independent parse: per surface, its triangles and the positions of one frame.
struct RawSurface {
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<std::array<float, 3>> positions;
};
std::vector<RawSurface> parse_md3(const std::vector<unsigned char>& b, int frame) {
  std::vector<RawSurface> out;
  size_t at = size_t(get<int32_t>(b, 100));
  for (int32_t s = 0; s < get<int32_t>(b, 84); ++s) {
    RawSurface rs;
    const int32_t nv = get<int32_t>(b, at + 80), nt = get<int32_t>(b, at + 84);
    for (int32_t t = 0; t < nt; ++t)
      rs.triangles.push_back(get<std::array<int32_t, 3>>(b, at + size_t(get<int32_t>(b, at + 88)) + 12 * size_t(t)));
    for (int32_t v = 0; v < nv; ++v) {
      auto xyz = get<std::array<int16_t, 3>>(b, at + size_t(get<int32_t>(b, at + 100)) + 8 * (size_t(frame) * size_t(nv) + size_t(v)));
      rs.positions.push_back({xyz[0] / 64.0f, xyz[1] / 64.0f, xyz[2] / 64.0f});
    }
    out.push_back(rs);
    at += size_t(get<int32_t>(b, at + 104));
  }
  return out;
}

}  // namespace

namespace {

void check_md3(const std::string& model, const std::vector<unsigned char>& b, int frame) {
  SCOPED_TRACE(model + " frame " + std::to_string(frame));
  ImportOptions o;
  o.md3_frame = frame;
  ImportResult r = import_memory(model, b.data(), b.size(), o);
  ASSERT_TRUE(r.ok) << r.error;
  const std::vector<RawSurface> raw = parse_md3(b, frame);
  size_t t = 0, v = 0;
  for (size_t s = 0; s < raw.size(); ++s) {
    v += raw[s].positions.size();
    for (auto& tri : raw[s].triangles) {
      ASSERT_LT(t, r.scene.triangle_count());
      EXPECT_EQ(r.scene.sources[t].mesh, s);
      const int order[3] = {0, 2, 1};  // reversed to counter-clockwise
      for (int j = 0; j < 3; ++j) {
        const float* p = &r.scene.positions[3 * size_t(r.scene.indices[3 * t + size_t(j)])];
        ASSERT_EQ(0, std::memcmp(p, raw[s].positions[size_t(tri[size_t(order[j])])].data(), 12));
      }
      ++t;
    }
  }
  EXPECT_EQ(t, r.scene.triangle_count());
  EXPECT_EQ(v, r.scene.vertex_count());
}

}  // namespace

TEST(Quake3Md3, SurfacesOfAFrameEqualIndependentParse) {
  for (const char* model : {"gargoyle/head.md3", "gargoyle/upper_2.md3", "gargoyle/lower.md3"}) {
    const std::vector<unsigned char> b = member(kPlayers, std::string("models/players/") + model);
    const int frames = get<int32_t>(b, 76);
    for (int frame : {0, frames / 2, frames - 1}) check_md3(model, b, frame);
  }
  // Closed surfaces enclose positive volume once reversed (outward fronts).
  const std::vector<unsigned char> head = member(kPlayers, "models/players/gargoyle/head.md3");
  ImportResult r = import_memory("head.md3", head.data(), head.size());
  ASSERT_TRUE(r.ok) << r.error;
  WeldResult w = weld(positions_of(r.scene.positions.data(), r.scene.vertex_count()), r.scene.indices.data(),
                      r.scene.indices.size());
  Topology topo = build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(),
                                 r.scene.triangle_count());
  ASSERT_TRUE(topo.stats.closed);
  EXPECT_EQ(topo.stats.inconsistent_edges, 0u);
  double volume = 0;
  for (size_t t = 0; t < r.scene.triangle_count(); ++t) {
    const float* a = &r.scene.positions[3 * size_t(r.scene.indices[3 * t])];
    const float* b = &r.scene.positions[3 * size_t(r.scene.indices[3 * t + 1])];
    const float* c = &r.scene.positions[3 * size_t(r.scene.indices[3 * t + 2])];
    volume += (a[0] * (double(b[1]) * c[2] - double(b[2]) * c[1]) - a[1] * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
               a[2] * (double(b[0]) * c[1] - double(b[1]) * c[0])) / 6;
  }
  EXPECT_GT(volume, 100.0);
}

// Every model of Debian's openarena-081-players, first and last frame.
TEST(Quake3Md3, EveryShippedModelEqualsIndependentParse) {
  std::vector<std::string> names;
  std::string error;
  ASSERT_TRUE(detail::list_archive_members(kPlayers, ".md3", names, error)) << error;
  ASSERT_GE(names.size(), 50u);
  for (const std::string& name : names) {
    const std::vector<unsigned char> b = member(kPlayers, name);
    check_md3(name, b, 0);
    check_md3(name, b, get<int32_t>(b, 76) - 1);
  }
}

TEST(Quake3Md3, HostileAndTruncatedRefused) {
  const std::vector<unsigned char> good = member(kPlayers, "models/players/gargoyle/head_2.md3");
  ASSERT_EQ(refusal(good, "head_2.md3"), "accepted");
  // Every truncation.
  for (size_t n = 0; n < good.size(); ++n) {
    const std::vector<unsigned char> prefix(good.begin(), good.begin() + long(n));
    ASSERT_NE(refusal(prefix, "head_2.md3"), "accepted") << n << " bytes";
  }
  auto expect_refused = [&](size_t at, int32_t value, const std::string& words, int frame = 0) {
    std::vector<unsigned char> b = good;
    if (at) put(b, at, value);
    ImportOptions o;
    o.md3_frame = frame;
    const std::string e = refusal(b, "head_2.md3", o);
    EXPECT_NE(e.find(words), std::string::npos) << "wanted '" << words << "' in: " << e;
  };
  const size_t surf = size_t(get<int32_t>(good, 100));
  const int32_t frames = get<int32_t>(good, 76);
  expect_refused(0, 0, "frame " + std::to_string(frames) + " requested", frames);
  expect_refused(0, 0, "frame -1 requested", -1);
  expect_refused(4, 16, "MD3 version 16");
  expect_refused(76, 0, "has 0 frames");
  expect_refused(84, 0x7fffffff, "2147483647 surfaces at offset");
  expect_refused(100, int32_t(good.size()), "surfaces at offset");
  expect_refused(surf + 72, frames + 1, "surface 0 has " + std::to_string(frames + 1) + " frames");
  expect_refused(surf + 84, 0x7fffffff, "surface 0: 2147483647 triangles at offset");
  expect_refused(surf + 80, 0x40000000, "frames of 1073741824 vertices");
  expect_refused(surf + 80, -5, "frames of -5 vertices");
  expect_refused(surf + 104, 0, "surface 0 ends at offset 0");
  expect_refused(surf + size_t(get<int32_t>(good, surf + 88)) + 4, get<int32_t>(good, surf + 80),
                 "surface 0 triangle 0 uses vertex " + std::to_string(get<int32_t>(good, surf + 80)) + ", out of range");
  std::vector<unsigned char> b = good;
  b[surf] = 'X';
  EXPECT_NE(refusal(b, "head_2.md3").find("surface 0 at offset"), std::string::npos);
}

// ---------------------------------------------------------------------------
// The shadow-volume law on real maps (MISSION.md, "What correctness means"):
// for a point light inside the level, a point P is inside the volume (its
// stencil count is non-zero) exactly when the segment from P to the light is
// blocked. The count is that of depth-fail: the volume triangles that
// geom::extrude_volume rasterizes (homogeneous, corners at infinity with
// w = 0), crossed by the view ray from a camera E through P beyond P, up to
// and including its point at infinity, back faces +1 and front faces -1.
// Computed exactly as a cone intersection in R^4 (long double minors): the
// ray beyond P is the cone {aP + bQ, a, b >= 0} with Q = (P - E, 0), a triangle
// the cone {sum c_i V_i, c_i >= 0}; they meet when the null vector of the 4x5
// matrix [P Q V0 V1 V2] has signs (+ + - - -) or (- - + + +). Two cameras must
// give the same count (the volume is closed). The blocked oracle is Embree's
// occlusion ray on the imported triangles; samples whose answer changes when P
// moves by 1/20 unit (on a shadow boundary), or whose minors are too small to
// trust, are skipped and counted; the oracle's segment stops 1/100 unit short
// of the light. Lights: the maps' own spawn points (info_player_deathmatch),
// 40 units above the floor, and a hard case: a light exactly on the plane of
// axis-aligned walls, outside them. Not checked: a light exactly at a map
// vertex or inside a face (oa_dm1 (320, 1412, -48) and (320, 1416, -80),
// oa_ctf2 (1832, 891.75, 232)), where the volume of geom/shadow_volume.h gives
// counts that differ between cameras or miss blocked points.
namespace {

using LD = double;

LD det3(const LD* a, const LD* b, const LD* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}
// Determinant of the 4x4 matrix whose columns are a, b, c, d.
LD det4(const LD* a, const LD* b, const LD* c, const LD* d) {
  const LD* col[4] = {a, b, c, d};
  LD sum = 0;
  for (int j = 0; j < 4; ++j) {  // expand along row 3 (w)
    if (col[j][3] == 0) continue;
    LD m[3][3];
    for (int k = 0, c2 = 0; k < 4; ++k)
      if (k != j) {
        for (int r = 0; r < 3; ++r) m[c2][r] = col[k][r];
        ++c2;
      }
    const LD minor = det3(m[0], m[1], m[2]);
    sum += ((3 + j) % 2 ? -1 : 1) * col[j][3] * minor;
  }
  return sum;
}
LD norm4(const LD* a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]); }

// Plucker coordinates of the line through 4-vectors a and b: L_ij = a_i b_j - a_j b_i
// for ij = 01, 02, 03, 12, 13, 23; det4(a, b, c, d) = plucker_dot(L(a, b), L(c, d)).
using Plucker = std::array<LD, 6>;
Plucker plucker(const LD* a, const LD* b) {
  return {a[0] * b[1] - a[1] * b[0], a[0] * b[2] - a[2] * b[0], a[0] * b[3] - a[3] * b[0],
          a[1] * b[2] - a[2] * b[1], a[1] * b[3] - a[3] * b[1], a[2] * b[3] - a[3] * b[2]};
}
LD plucker_dot(const Plucker& x, const Plucker& y) {
  return x[0] * y[5] - x[1] * y[4] + x[2] * y[3] + x[3] * y[2] - x[4] * y[1] + x[5] * y[0];
}
LD norm6(const Plucker& x) {
  LD s = 0;
  for (LD c : x) s += c * c;
  return std::sqrt(s);
}

struct VolumeTriangle {
  LD v[3][4];
  LD h[4];          // h . X = det4(v0, v1, v2, X)
  LD h_norm;
  Plucker edge[3];  // L(v1, v2), L(v0, v2), L(v0, v1)
  LD edge_norm[3];
  bool at_infinity;
};

std::vector<VolumeTriangle> volume_triangles(const std::vector<float>& tris) {
  std::vector<VolumeTriangle> out(tris.size() / 12);
  for (size_t t = 0; t < out.size(); ++t) {
    VolumeTriangle& vt = out[t];
    vt.at_infinity = true;
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 4; ++k) vt.v[j][k] = tris[12 * t + 4 * size_t(j) + size_t(k)];
      vt.at_infinity = vt.at_infinity && vt.v[j][3] == 0;
    }
    for (int k = 0; k < 4; ++k) {
      LD e[4] = {0, 0, 0, 0};
      e[k] = 1;
      vt.h[k] = det4(vt.v[0], vt.v[1], vt.v[2], e);
    }
    vt.h_norm = norm4(vt.h);
    vt.edge[0] = plucker(vt.v[1], vt.v[2]), vt.edge[1] = plucker(vt.v[0], vt.v[2]), vt.edge[2] = plucker(vt.v[0], vt.v[1]);
    for (int j = 0; j < 3; ++j) vt.edge_norm[j] = norm6(vt.edge[j]);
  }
  return out;
}

// The sign of h . X on the outward side of a counter-clockwise triangle.
int outward_sign() {
  std::vector<float> t = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1};
  VolumeTriangle vt = volume_triangles(t)[0];
  return vt.h[2] + vt.h[3] > 0 ? 1 : -1;  // X = (0, 0, 1, 1), above the +z front
}

// Depth-fail count at p (local frame) seen from camera e; false when a minor
// that decides a crossing is too close to zero to trust.
bool stencil_count(const std::vector<VolumeTriangle>& vol, const LD p[4], const LD e[4], int& count) {
  static const int out_sign = outward_sign();
  const LD q[4] = {p[0] - e[0], p[1] - e[1], p[2] - e[2], 0};
  const LD np = norm4(p), nq = norm4(q);
  const Plucker pq = plucker(p, q);
  const LD npq = norm6(pq);
  const LD eps = 1e-13L;
  count = 0;
  for (const VolumeTriangle& vt : vol) {
    if (vt.h_norm == 0) continue;  // no area: never crossed
    const LD hp = vt.h[0] * p[0] + vt.h[1] * p[1] + vt.h[2] * p[2] + vt.h[3] * p[3];
    const LD hq = vt.h[0] * q[0] + vt.h[1] * q[1] + vt.h[2] * q[2];
    const bool hp_tiny = std::fabs(hp) <= eps * vt.h_norm * np, hq_tiny = std::fabs(hq) <= eps * vt.h_norm * nq;
    bool crossed;
    if (vt.at_infinity) {
      // Q (the ray's end) inside the far triangle's cone of directions.
      const LD s = det3(vt.v[0], vt.v[1], vt.v[2]);
      const LD t0 = det3(q, vt.v[1], vt.v[2]), t1 = det3(vt.v[0], q, vt.v[2]), t2 = det3(vt.v[0], vt.v[1], q);
      const LD t[3] = {t0, t1, t2};
      int pos = 0, neg = 0, tiny = 0;
      for (int j = 0; j < 3; ++j) {
        const LD tol = eps * nq * vt.edge_norm[j];
        (std::fabs(t[j]) <= tol ? tiny : t[j] > 0 ? pos : neg)++;
      }
      if (pos && neg) continue;
      if (tiny) {
        return false;
      }
      crossed = (pos == 3) == (s > 0);
    } else {
      if (!hp_tiny && !hq_tiny && (hp > 0) == (hq > 0)) continue;  // P and Q on one side of its plane
      // Null vector of [P Q V0 V1 V2]: (-h.Q, h.P, det(P,Q,V1,V2), -det(P,Q,V0,V2), det(P,Q,V0,V1)).
      const LD n[3] = {plucker_dot(pq, vt.edge[0]), -plucker_dot(pq, vt.edge[1]), plucker_dot(pq, vt.edge[2])};
      int pos = 0, neg = 0, tiny = 0;
      for (int j = 0; j < 3; ++j) (std::fabs(n[j]) <= eps * npq * vt.edge_norm[j] ? tiny : n[j] > 0 ? pos : neg)++;
      if (pos && neg) continue;  // the line misses the triangle
      if (tiny) {
        return false;
      }
      if (hp_tiny || hq_tiny) {  // the line goes through the triangle, P (or Q) almost on it
        return false;
      }
      const bool sigma = pos == 3;
      crossed = (hp > 0) != sigma;  // n_P = -h.Q and n_Q = h.P (equal signs here) opposite to the edges' sign
    }
    if (!crossed) continue;
    const LD he = vt.h[0] * e[0] + vt.h[1] * e[1] + vt.h[2] * e[2] + vt.h[3] * e[3];
    const bool front = (he > 0 ? 1 : -1) == out_sign;
    count += front ? -1 : 1;
  }
  return true;
}

struct Occluder {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit Occluder(const Scene& s) {
    device = rtcNewDevice("threads=1");
    scene = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, s.vertex_count()));
    std::memcpy(v, s.positions.data(), s.positions.size() * 4);
    auto* i = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, s.triangle_count()));
    std::memcpy(i, s.indices.data(), s.indices.size() * 4);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~Occluder() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  bool blocked(const double p[3], const double l[3]) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray{};
    ray.org_x = float(p[0]), ray.org_y = float(p[1]), ray.org_z = float(p[2]);
    ray.dir_x = float(l[0] - p[0]), ray.dir_y = float(l[1] - p[1]), ray.dir_z = float(l[2] - p[2]);
    const double length = std::hypot(l[0] - p[0], l[1] - p[1], l[2] - p[2]);
    ray.tnear = 0, ray.tfar = float(1 - 0.01 / length), ray.mask = 0xffffffffu;  // stop 1/100 unit short of the light
    rtcOccluded1(scene, &ctx, &ray);
    return ray.tfar < 0;
  }
};

// Spawn points of a map (entities lump), as "x y z".
std::vector<std::array<double, 3>> spawn_points(const RawBsp& raw) {
  const std::string text(reinterpret_cast<const char*>(raw.bytes.data()) + raw.lump_offset(0),
                         size_t(raw.lump_length(0)));
  std::vector<std::array<double, 3>> out;
  size_t at = 0;
  while ((at = text.find('{', at)) != std::string::npos) {
    const size_t end = text.find('}', at);
    const std::string block = text.substr(at, end - at);
    at = end;
    if (block.find("\"info_player_deathmatch\"") == std::string::npos) continue;
    const size_t o = block.find("\"origin\"");
    if (o == std::string::npos) continue;
    std::array<double, 3> p;
    if (std::sscanf(block.c_str() + o + 8, " \"%lf %lf %lf\"", &p[0], &p[1], &p[2]) == 3) out.push_back(p);
  }
  return out;
}

// How many triangles have `l` on their plane (within 1/1000 unit), and how
// many of those contain it.
struct PlaneContact {
  size_t on_plane = 0, on_face = 0;
};
PlaneContact plane_contact(const Scene& s, const std::array<double, 3>& l) {
  PlaneContact c;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const float* v[3];
    for (int j = 0; j < 3; ++j) v[j] = &s.positions[3 * size_t(s.indices[3 * t + size_t(j)])];
    auto cross = [](const double* a, const double* b, double* o) {
      o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
    };
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; ++k) e1[k] = double(v[1][k]) - v[0][k], e2[k] = double(v[2][k]) - v[0][k];
    cross(e1, e2, n);
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nn == 0) continue;
    const double dist = (n[0] * (l[0] - v[0][0]) + n[1] * (l[1] - v[0][1]) + n[2] * (l[2] - v[0][2])) / nn;
    if (std::fabs(dist) > 1e-3) continue;
    ++c.on_plane;
    bool inside = true;
    for (int j = 0; j < 3; ++j) {
      double e[3], f[3], x[3];
      for (int k = 0; k < 3; ++k) e[k] = double(v[(j + 1) % 3][k]) - v[j][k], f[k] = l[size_t(k)] - v[j][k];
      cross(e, f, x);
      inside = inside && x[0] * n[0] + x[1] * n[1] + x[2] * n[2] >= -1e-6 * nn * nn;
    }
    c.on_face += inside;
  }
  return c;
}

struct LawStats {
  size_t checked = 0, blocked = 0, skipped = 0, violations = 0;
};

void check_law(const ShadowVolume& volume, const std::array<double, 3>& light, std::mt19937& rng, const double lo[3],
               const double hi[3], size_t samples, LawStats& st, const Occluder& occluder, bool report = true) {
  const double light4[4] = {light[0], light[1], light[2], 1};
  float local_light[4];
  to_local_light(volume.origin, light4, local_light);
  const std::vector<VolumeTriangle> vol = volume_triangles(extrude_volume(volume, local_light, true));
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  for (size_t k = 0; k < samples; ++k) {
    double p[3];
    for (int a = 0; a < 3; ++a)  // half near the light, half anywhere in the level's box
      p[a] = k % 2 ? light[size_t(a)] + (u(rng) - 0.5) * 512 : lo[a] + (hi[a] - lo[a]) * u(rng);
    const bool blocked = occluder.blocked(p, light.data());
    bool boundary = false;
    for (int j = 0; j < 3 && !boundary; ++j) {
      double d[3] = {g(rng), g(rng), g(rng)}, n = std::hypot(d[0], d[1], d[2]);
      double pj[3] = {p[0] + d[0] / n / 20, p[1] + d[1] / n / 20, p[2] + d[2] / n / 20};
      boundary = occluder.blocked(pj, light.data()) != blocked;
    }
    int counts[2];
    bool trusted = !boundary;
    for (int c = 0; c < 2 && trusted; ++c) {
      LD lp[4] = {p[0] - volume.origin[0], p[1] - volume.origin[1], p[2] - volume.origin[2], 1};
      LD le[4] = {lo[0] - volume.origin[0] + (hi[0] - lo[0]) * u(rng) + 3000 * g(rng),
                  lo[1] - volume.origin[1] + (hi[1] - lo[1]) * u(rng) + 3000 * g(rng),
                  lo[2] - volume.origin[2] + (hi[2] - lo[2]) * u(rng), 1};
      trusted = stencil_count(vol, lp, le, counts[c]);
    }
    if (!trusted) {
      ++st.skipped;
      continue;
    }
    ++st.checked;
    st.blocked += blocked;
    const bool ok = counts[0] == counts[1] && (counts[0] != 0) == blocked;
    if (!ok && st.violations++ < 5 && report)
      ADD_FAILURE() << "P = (" << p[0] << ", " << p[1] << ", " << p[2] << "), light (" << light[0] << ", " << light[1]
                    << ", " << light[2] << "): counts " << counts[0] << " and " << counts[1] << ", Embree says "
                    << (blocked ? "blocked" : "lit");
  }
}

}  // namespace

TEST(Quake3ShadowVolume, LawOnRealMaps) {
  std::mt19937 rng(2004);
  for (const char* map : {"oa_dm1.bsp", "oa_ctf2.bsp"}) {
    SCOPED_TRACE(map);
    const RawBsp raw = raw_map(map);
    ImportResult r = import_bytes(map, raw.bytes, 3);
    ASSERT_TRUE(r.ok) << r.error;
    const Scene& s = r.scene;
    WeldResult w = weld(positions_of(s.positions.data(), s.vertex_count()), s.indices.data(), s.indices.size());
    const PositionSpan wp = positions_of(w.positions.data(), w.vertex_count());
    Topology topo = build_topology(wp, w.indices.data(), s.triangle_count());
    FacePlanes planes = compute_face_planes(wp, w.indices.data(), s.triangle_count(), topo);
    ShadowVolume generic = build_shadow_volume(wp, w.indices.data(), s.triangle_count(), topo, planes);
    ShadowVolumeOptions one_sided_options;
    one_sided_options.one_sided_closed = true;  // the lights float in the open: outside every closed solid
    ShadowVolume one_sided = build_shadow_volume(wp, w.indices.data(), s.triangle_count(), topo, planes, one_sided_options);
    Occluder occluder(s);
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
    for (size_t v = 0; v < s.vertex_count(); ++v)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double(s.positions[3 * v + size_t(a)])),
                                  hi[a] = std::max(hi[a], double(s.positions[3 * v + size_t(a)]));
    std::vector<std::array<double, 3>> lights = spawn_points(raw);
    ASSERT_GE(lights.size(), 3u);
    lights.resize(3);
    for (auto& l : lights) l[2] += 40;  // spawn origins are 24 units above the floor; lights float above
    // Hard case: a light exactly on the plane of some faces (x = a vertex's x,
    // the plane of axis-aligned walls), outside all of them.
    std::vector<float> xs;
    for (size_t v = 0; v < s.vertex_count(); ++v) xs.push_back(s.positions[3 * v]);
    std::sort(xs.begin(), xs.end(), [&](float a, float b) {
      return std::fabs(a - lights[0][0]) < std::fabs(b - lights[0][0]);
    });
    bool placed = false;
    for (size_t i = 0; i < xs.size() && !placed; ++i) {
      std::array<double, 3> l = lights[0];
      l[0] = xs[i];
      const PlaneContact c = plane_contact(s, l);
      if (c.on_plane > 0 && c.on_face == 0) lights.push_back(l), placed = true;
    }
    ASSERT_TRUE(placed);
    LawStats st;
    for (const auto& light : lights) {
      check_law(generic, light, rng, lo, hi, 100, st, occluder);
      check_law(one_sided, light, rng, lo, hi, 40, st, occluder);
      float local[4];
      const double l4[4] = {light[0], light[1], light[2], 1};
      to_local_light(generic.origin, l4, local);
      check_law(build_light_volume(generic, local), light, rng, lo, hi, 40, st, occluder);
    }
    std::printf("%s: %zu points checked (%zu in shadow), %zu skipped on shadow boundaries or by rounding\n", map,
                st.checked, st.blocked, st.skipped);
    EXPECT_EQ(st.violations, 0u);
    EXPECT_GT(st.blocked, st.checked / 10);
    EXPECT_LT(st.blocked, st.checked * 95 / 100);
    EXPECT_LT(st.skipped * 10, st.checked + st.skipped);

    // The check can fail: a volume missing its caps, or one side in five, breaks the law.
    ShadowVolume no_caps = generic, holes = generic;
    no_caps.caps.clear();
    holes.sides.clear();
    for (size_t i = 0; i < generic.sides.size(); ++i)
      if (i % 5) holes.sides.push_back(generic.sides[i]);
    for (const ShadowVolume* broken : {&no_caps, &holes}) {
      LawStats bs;
      check_law(*broken, lights[0], rng, lo, hi, 60, bs, occluder, false);
      EXPECT_GT(bs.violations, 0u);
    }
  }
}
