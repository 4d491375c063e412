// Quake 3 BSP import (libgeom/src/import_bsp.cpp) on OpenArena's real maps, on
// a tiny map built here, and on hostile files: counts per face type against an
// independent parse (tests/quake3_fixtures.h), winding, refusals, the report.
#include <gtest/gtest.h>

#include "quake3_fixtures.h"

using namespace geom;
using namespace q3test;

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
      uint64_t cells_x = uint64_t(face.width - 1) / 2 * uint64_t(level),
               cells_y = uint64_t(face.height - 1) / 2 * uint64_t(level);
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
  ASSERT_TRUE(list_archive_members(kMaps, ".bsp", names, error)) << error;
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
  expect_refused(with([](BspBuilder& m) { m.vertices[2][1] = NAN; }),
                 "face 0 (polygon) uses vertex 2 with a non-finite");
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
  expect_refused(with([](BspBuilder& m) {
                   m.models[1] = {3, 2};
                 }),
                 "model 1 uses faces 3 to 5, out of range (4 faces)");
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
                 "would produce 67117059 triangles (67117056 from patches at level 64), over the limit of 16777216",
                 [] {
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
      case 0:
        at = 8 + 4 * (rng() % 34);
        break;  // lump directory
      case 1:
        at = raw.face_offset(rng() % raw.faces.size()) + 4 * (rng() % 26);
        break;  // a face field
      default:
        at = size_t(raw.lump_offset(7)) + 40 * (rng() % raw.models.size()) + 24 + 4 * (rng() % 2);
        break;
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
// non-manifold edges (Arneson n.d., Sect. 2.2: "each edge in the world can be
// shared by more than two faces").
TEST(Quake3Bsp, ReportOfRealMap) {
  ImportResult r = import_file(kMaps + ":maps/oa_ctf2.bsp");
  ASSERT_TRUE(r.ok) << r.error;
  Report report;
  report.file = "oa_ctf2.bsp";
  analyze(r.scene, {}, report);
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
