// Quake 3 MD3 import (libgeom/src/import_md3.cpp) on OpenArena's real models
// against an independent parse, and on hostile and truncated files.
#include <gtest/gtest.h>

#include "quake3_fixtures.h"

using namespace geom;
using namespace q3test;

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
      auto xyz = get<std::array<int16_t, 3>>(
          b, at + size_t(get<int32_t>(b, at + 100)) + 8 * (size_t(frame) * size_t(nv) + size_t(v)));
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
  Topology topo =
      build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(), r.scene.triangle_count());
  ASSERT_TRUE(topo.stats.closed);
  EXPECT_EQ(topo.stats.inconsistent_edges, 0u);
  double volume = 0;
  for (size_t t = 0; t < r.scene.triangle_count(); ++t) {
    const float* a = &r.scene.positions[3 * size_t(r.scene.indices[3 * t])];
    const float* b = &r.scene.positions[3 * size_t(r.scene.indices[3 * t + 1])];
    const float* c = &r.scene.positions[3 * size_t(r.scene.indices[3 * t + 2])];
    volume += (a[0] * (double(b[1]) * c[2] - double(b[2]) * c[1]) - a[1] * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
               a[2] * (double(b[0]) * c[1] - double(b[1]) * c[0])) /
              6;
  }
  EXPECT_GT(volume, 100.0);
}

// Every model of Debian's openarena-081-players, first and last frame.
TEST(Quake3Md3, EveryShippedModelEqualsIndependentParse) {
  std::vector<std::string> names;
  std::string error;
  ASSERT_TRUE(list_archive_members(kPlayers, ".md3", names, error)) << error;
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
  expect_refused(
      surf + size_t(get<int32_t>(good, surf + 88)) + 4, get<int32_t>(good, surf + 80),
      "surface 0 triangle 0 uses vertex " + std::to_string(get<int32_t>(good, surf + 80)) + ", out of range");
  std::vector<unsigned char> b = good;
  b[surf] = 'X';
  EXPECT_NE(refusal(b, "head_2.md3").find("surface 0 at offset"), std::string::npos);
}
