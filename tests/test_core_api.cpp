// geom::core's API style: the *_bound functions hold on random and
// adversarial meshes, the caller-owned overloads write the same bytes as the
// vector ones, validate_triangles and run_pipeline_checked return a code and
// a message for untrusted data (never a crash), and the trusted fast paths
// assert their preconditions with the function's name.
//
// The death tests exist only where the library checks preconditions
// (GEOM_PRECONDITIONS: builds without NDEBUG, i.e. Debug and the sanitizer
// build): in a Release build the checks are compiled out, so a death test
// there could not pass, and it is not compiled rather than skipped.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "geom/adjacency.h"
#include "geom/esm_quads.h"
#include "geom/face_planes.h"
#include "geom/pipeline.h"
#include "geom/precondition.h"
#include "geom/shadow_volume.h"
#include "geom/status.h"
#include "geom/topology.h"
#include "geom/validate.h"
#include "geom/weld.h"
#include "silhouette_fixtures.h"

using namespace geom;
using fixtures::Mesh;

namespace {

// A soup of `triangles` triangles over a pool of `pool` vertices on a coarse
// lattice (repeated positions weld, shared edges pile up past two faces,
// windings disagree, triangles collapse, lattice points line up).
Mesh random_soup(std::mt19937& rng, size_t pool, size_t triangles) {
  Mesh m;
  m.name = "soup";
  std::uniform_int_distribution<int> coord(-2, 2);
  for (size_t v = 0; v < pool; ++v) m.add(coord(rng), coord(rng), coord(rng) * 0.5);
  std::uniform_int_distribution<uint32_t> pick(0, uint32_t(pool - 1));
  for (size_t t = 0; t < triangles; ++t) m.tri(pick(rng), pick(rng), pick(rng));
  return m;
}

// Every fixture, two fans of many pages on one edge, a seam-split cube, the
// empty mesh and 300 random soups.
std::vector<Mesh> corpus() {
  using namespace fixtures;
  std::vector<Mesh> all = {box(0, 0, 0, 1, 2, 3),
                           sphere(9, 7),
                           torus(10, 6),
                           sheet(7, 0.4, 3, 0.01),
                           open_box(),
                           book(3),
                           book(40),
                           bowtie(),
                           flipped_box(),
                           degenerate_box(),
                           sliver_box(),
                           stack(),
                           Mesh()};
  Mesh seams;  // a cube as 12 separate triangles
  const Mesh cube = box(-1, -1, -1, 1, 1, 1);
  for (uint32_t i : cube.indices) {
    seams.indices.push_back(uint32_t(seams.vertex_count()));
    seams.positions.insert(seams.positions.end(), &cube.positions[3 * i], &cube.positions[3 * i] + 3);
  }
  all.push_back(seams);
  std::mt19937 rng(20261203);
  for (int i = 0; i < 300; ++i) {
    const size_t pool = 3 + rng() % 40;
    all.push_back(random_soup(rng, pool, 1 + rng() % 120));
  }
  return all;
}

template <class T>
bool same_bytes(const T* a, const T* b, size_t n) {
  return n == 0 || std::memcmp(a, b, n * sizeof(T)) == 0;
}

struct Stages {
  WeldResult weld;
  Topology topology;
  FacePlanes planes;
  PositionSpan welded() const { return positions_of(weld.positions.data(), weld.vertex_count()); }
  size_t triangles() const { return weld.indices.size() / 3; }
};

Stages stages(const Mesh& m) {
  Stages s;
  s.weld = weld(positions_of(m.positions.data(), m.vertex_count()), m.indices.data(), m.indices.size());
  s.topology = build_topology(s.welded(), s.weld.indices.data(), s.triangles());
  s.planes = compute_face_planes(s.welded(), s.weld.indices.data(), s.triangles(), s.topology);
  return s;
}

}  // namespace

TEST(CoreApi, WeldIntoCallerMemoryIsTheVectorWeldWithinItsBound) {
  std::mt19937 rng(7);
  for (const Mesh& m : corpus()) {
    // Half the meshes through an interleaved layout (position + 1 float), stride 16.
    const bool strided = rng() & 1;
    std::vector<float> interleaved;
    for (size_t v = 0; v < m.vertex_count(); ++v)
      interleaved.insert(interleaved.end(), {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2], -7});
    const PositionSpan span = strided ? PositionSpan(interleaved.data(), m.vertex_count(), 16)
                                      : positions_of(m.positions.data(), m.vertex_count());
    for (float tolerance : {0.0f, 0.3f}) {
      const WeldResult w = weld(span, m.indices.data(), m.indices.size(), tolerance);
      const size_t bound = weld_bound(m.vertex_count());
      ASSERT_LE(w.vertex_count(), bound) << m.name;
      // Caller-owned, with a guard past the bound that must stay untouched.
      std::vector<float> pos(3 * bound + 4, 123.0f);
      std::vector<uint32_t> remap(m.vertex_count()), idx(m.indices.size());
      const size_t n = weld(pos.data(), remap.data(), idx.data(), span, m.indices.data(), m.indices.size(), tolerance);
      ASSERT_EQ(n, w.vertex_count()) << m.name;
      EXPECT_TRUE(same_bytes(pos.data(), w.positions.data(), 3 * n)) << m.name;
      EXPECT_TRUE(same_bytes(remap.data(), w.remap.data(), remap.size())) << m.name;
      EXPECT_TRUE(same_bytes(idx.data(), w.indices.data(), idx.size())) << m.name;
      for (size_t i = 3 * bound; i < pos.size(); ++i) ASSERT_EQ(pos[i], 123.0f) << m.name;
      // In place: the output indices may be the input's.
      std::vector<uint32_t> in_place = m.indices;
      weld(pos.data(), remap.data(), in_place.data(), span, in_place.data(), in_place.size(), tolerance);
      EXPECT_EQ(in_place, w.indices) << m.name;
    }
  }
}

TEST(CoreApi, AdjacencyFillsExactlyItsBound) {
  for (const Mesh& m : corpus()) {
    const Stages s = stages(m);
    const size_t tc = s.triangles(), bound = adjacency_bound(tc);
    std::vector<uint32_t> a(bound + 3, 0xdeadbeefu), b(bound + 3, 0xdeadbeefu);
    ASSERT_TRUE(build_adjacency(a.data(), s.weld.indices.data(), tc, s.topology));
    ASSERT_TRUE(build_adjacency(b.data(), s.weld.indices.data(), tc, s.weld.vertex_count()));
    EXPECT_EQ(a, b) << m.name;
    for (size_t i = 0; i < bound; ++i) ASSERT_LT(a[i], s.weld.vertex_count()) << m.name;  // every slot written
    for (size_t i = bound; i < a.size(); ++i) ASSERT_EQ(a[i], 0xdeadbeefu) << m.name;     // nothing past it
  }
}

TEST(CoreApi, EsmQuadsStayWithinTheirBoundAndIntoCallerMemoryIsByteIdentical) {
  EsmOptions keep;  // the most quads: concave edges kept, every edge under 179 degrees bevelled
  keep.keep_concave = true;
  keep.bevel_below_degrees = 179;
  size_t most = 0;  // the largest quads / bound seen: the bound is not loose by a factor
  for (const Mesh& m : corpus()) {
    const Stages s = stages(m);
    const size_t tc = s.triangles();
    for (bool kept : {false, true}) {
      const EsmOptions opts = kept ? keep : EsmOptions();
      const EsmQuads v = build_esm_quads(s.welded(), s.weld.indices.data(), tc, s.topology, s.planes, opts);
      ASSERT_LE(v.quads.size(), esm_quads_bound(tc)) << m.name;
      if (tc) most = std::max(most, 1000 * v.quads.size() / esm_quads_bound(tc));
      std::vector<EsmQuad> out(esm_quads_bound(tc) + 1);
      std::memset(out.data(), 0xab, out.size() * sizeof(EsmQuad));
      const EsmQuads c = build_esm_quads(out.data(), s.welded(), s.weld.indices.data(), tc, s.topology, s.planes, opts);
      EXPECT_TRUE(c.quads.empty());
      ASSERT_EQ(c.stats.quads, v.quads.size()) << m.name;
      EXPECT_TRUE(same_bytes(out.data(), v.quads.data(), v.quads.size())) << m.name;
      EXPECT_EQ(c.planes, v.planes) << m.name;
      EXPECT_EQ(std::memcmp(c.origin, v.origin, sizeof c.origin), 0);
      EXPECT_EQ(std::memcmp(&c.stats, &v.stats, sizeof c.stats), 0) << m.name;
      const unsigned char* guard = reinterpret_cast<const unsigned char*>(out.data() + v.quads.size());
      for (size_t i = 0; i < (out.size() - v.quads.size()) * sizeof(EsmQuad); ++i) ASSERT_EQ(guard[i], 0xab) << m.name;
    }
  }
  EXPECT_GE(most, 500u);  // some mesh fills half of 6 quads per triangle or more (a book, a bevelled sheet)
}

TEST(CoreApi, ShadowVolumeStaysWithinItsBoundsAndIntoCallerMemoryIsByteIdentical) {
  size_t most_sides = 0;
  for (const Mesh& m : corpus()) {
    const Stages s = stages(m);
    const size_t tc = s.triangles();
    for (bool one_sided : {false, true}) {
      ShadowVolumeOptions o;
      o.one_sided_closed = one_sided;
      const ShadowVolume v = build_shadow_volume(s.welded(), s.weld.indices.data(), tc, s.topology, s.planes, o);
      ASSERT_LE(v.sides.size(), shadow_volume_sides_bound(tc)) << m.name;
      ASSERT_LE(v.caps.size(), shadow_volume_caps_bound(tc)) << m.name;
      if (tc) most_sides = std::max(most_sides, 1000 * v.sides.size() / shadow_volume_sides_bound(tc));
      std::vector<SvSide> sides(shadow_volume_sides_bound(tc));
      std::vector<SvCap> caps(shadow_volume_caps_bound(tc));
      const ShadowVolume c = build_shadow_volume(sides.data(), caps.data(), s.welded(), s.weld.indices.data(), tc,
                                                 s.topology, s.planes, o);
      EXPECT_TRUE(c.sides.empty() && c.caps.empty());
      ASSERT_EQ(c.stats.sides, v.sides.size()) << m.name;
      ASSERT_EQ(c.stats.caps, v.caps.size()) << m.name;
      EXPECT_TRUE(same_bytes(sides.data(), v.sides.data(), v.sides.size())) << m.name;
      EXPECT_TRUE(same_bytes(caps.data(), v.caps.data(), v.caps.size())) << m.name;
      EXPECT_EQ(c.planes, v.planes) << m.name;
      EXPECT_EQ(std::memcmp(&c.stats, &v.stats, sizeof c.stats), 0) << m.name;
    }
  }
  EXPECT_GE(most_sides, 500u);
}

// Untrusted soups: each kind of damage comes back as its code, with a message
// naming the triangle and the vertex, never as a crash; undamaged ones pass.
TEST(CoreApi, ValidateTrianglesNamesEachKindOfDamage) {
  const Mesh box = fixtures::box(0, 0, 0, 1, 1, 1);
  const PositionSpan span = positions_of(box.positions.data(), box.vertex_count());
  Status ok = validate_triangles(span, box.indices.data(), box.indices.size(), "box");
  EXPECT_TRUE(ok.ok);
  EXPECT_EQ(ok.code, ErrorCode::None);
  EXPECT_EQ(ok.error, "");

  Status s = validate_triangles(span, box.indices.data(), 35, "box");
  EXPECT_EQ(s.code, ErrorCode::IndexCount);
  EXPECT_EQ(s.error, "box: 35 indices, not a multiple of 3 (3 per triangle)");
  EXPECT_FALSE(s.ok);

  s = validate_triangles(span, nullptr, 3, "box");
  EXPECT_EQ(s.code, ErrorCode::Malformed);
  s = validate_triangles(PositionSpan(), box.indices.data(), 3, "box");  // no vertex: every index is out of range
  EXPECT_EQ(s.code, ErrorCode::IndexOutOfRange);
  EXPECT_EQ(s.error, "box: triangle 0 uses vertex 0, out of range (0 vertices)");
  EXPECT_TRUE(validate_triangles(PositionSpan(), nullptr, 0).ok);  // the empty mesh

  // Counts the core cannot address: refused before a single index is read.
  s = validate_triangles(span, box.indices.data(), 3 * (kMaxTriangles + 1), "huge");
  EXPECT_EQ(s.code, ErrorCode::TooLarge);
  s = validate_triangles(PositionSpan(box.positions.data(), kMaxVertices + 1, 0), box.indices.data(), 3, "huge");
  EXPECT_EQ(s.code, ErrorCode::TooLarge);
  s = validate_triangles(PositionSpan(box.positions.data(), 8, std::numeric_limits<size_t>::max() / 4),
                         box.indices.data(), 3, "huge");
  EXPECT_EQ(s.code, ErrorCode::TooLarge);
  EXPECT_NE(s.error.find("overflows"), std::string::npos) << s.error;

  // Random damage: one index out of range, or one used vertex non-finite.
  std::mt19937 rng(11);
  for (int round = 0; round < 400; ++round) {
    Mesh m = random_soup(rng, 4 + rng() % 20, 1 + rng() % 30);
    const size_t corner = rng() % m.indices.size();
    const PositionSpan p = positions_of(m.positions.data(), m.vertex_count());
    if (round % 3 == 0) {
      m.indices[corner] = uint32_t(m.vertex_count() + rng() % 5);
      if (round % 2) m.indices[corner] = 0xffffffffu;
      s = validate_triangles(p, m.indices.data(), m.indices.size(), "soup");
      ASSERT_EQ(s.code, ErrorCode::IndexOutOfRange);
      ASSERT_EQ(s.error, "soup: triangle " + std::to_string(corner / 3) + " uses vertex " +
                             std::to_string(m.indices[corner]) + ", out of range (" + std::to_string(m.vertex_count()) +
                             " vertices)");
    } else {
      const float bad[] = {NAN, INFINITY, -INFINITY};
      const uint32_t v = m.indices[corner];
      m.positions[3 * v + rng() % 3] = bad[rng() % 3];
      s = validate_triangles(p, m.indices.data(), m.indices.size(), "soup");
      ASSERT_EQ(s.code, ErrorCode::NonFinite);
      size_t first = 0;
      while (m.indices[first] != v) ++first;
      ASSERT_EQ(s.error, "soup: triangle " + std::to_string(first / 3) + " uses vertex " + std::to_string(v) +
                             " with a non-finite coordinate");
    }
  }
  // A non-finite vertex no triangle uses is no error.
  Mesh unused = box;
  unused.add(NAN, 0, INFINITY);
  EXPECT_TRUE(validate_triangles(positions_of(unused.positions.data(), unused.vertex_count()), unused.indices.data(),
                                 unused.indices.size())
                  .ok);
}

TEST(CoreApi, CheckedPipelineReturnsCodesAndOtherwiseTheSameBuffers) {
  std::mt19937 rng(5);
  for (int round = 0; round < 60; ++round) {
    Mesh m = random_soup(rng, 4 + rng() % 30, 1 + rng() % 60);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction[0] = 0.3, sun.direction[1] = -1, sun.direction[2] = 0.2;
    const PositionSpan p = positions_of(m.positions.data(), m.vertex_count());
    const PipelineResult r = run_pipeline_checked("soup", p, m.indices.data(), m.indices.size(), {sun});
    ASSERT_TRUE(r.ok) << r.error;
    const Pipeline direct = run_pipeline(p, m.indices.data(), m.triangle_count(), {sun});
    ASSERT_EQ(r.run.esm.quads.size(), direct.esm.quads.size());
    EXPECT_TRUE(same_bytes(r.run.esm.quads.data(), direct.esm.quads.data(), direct.esm.quads.size()));
    ASSERT_EQ(r.run.lights.size(), 1u);
    EXPECT_EQ(r.run.lights[0].volume.sides.size(), direct.lights[0].volume.sides.size());
    EXPECT_EQ(r.run.adjacency, direct.adjacency);

    m.indices.push_back(0);
    PipelineResult bad = run_pipeline_checked("soup", p, m.indices.data(), m.indices.size());
    EXPECT_EQ(bad.code, ErrorCode::IndexCount);
    EXPECT_TRUE(bad.run.weld.positions.empty());
    m.indices.pop_back();
    m.indices[rng() % m.indices.size()] = uint32_t(m.vertex_count());
    bad = run_pipeline_checked("soup", p, m.indices.data(), m.indices.size());
    EXPECT_EQ(bad.code, ErrorCode::IndexOutOfRange);
  }
  const Mesh box = fixtures::box(0, 0, 0, 1, 1, 1);
  Light nowhere;
  nowhere.name = "nowhere";
  nowhere.position[0] = NAN;
  const PipelineResult r = run_pipeline_checked("box", positions_of(box.positions.data(), box.vertex_count()),
                                                box.indices.data(), box.indices.size(), {nowhere});
  EXPECT_EQ(r.code, ErrorCode::NonFinite);
  EXPECT_EQ(r.error, "box: light 'nowhere' is not a usable (x, y, z, w): non-finite or all zero");
}

TEST(CoreApi, ErrorCodesHaveDistinctNames) {
  std::set<std::string> names;
  for (ErrorCode c : {ErrorCode::None, ErrorCode::Malformed, ErrorCode::IndexCount, ErrorCode::IndexOutOfRange,
                      ErrorCode::NonFinite, ErrorCode::TooLarge, ErrorCode::OutOfMemory, ErrorCode::Io})
    names.insert(error_code_name(c));
  EXPECT_EQ(names.size(), 8u);
  EXPECT_STREQ(error_code_name(ErrorCode::IndexOutOfRange), "index_out_of_range");
}

#if GEOM_PRECONDITIONS
// Broken preconditions of the trusted fast paths: the process stops with the
// function's name, the expected and the actual value in the message.
TEST(CoreApiDeathTest, PreconditionsNameTheFunction) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const Mesh box = fixtures::box(0, 0, 0, 1, 1, 1);
  const PositionSpan span = positions_of(box.positions.data(), box.vertex_count());
  std::vector<uint32_t> bad = box.indices;
  bad[13] = 8;
  EXPECT_DEATH(weld(span, bad.data(), bad.size()),
               "geom::weld: indices\\[13\\] = 8, expected < 8 \\(the vertex count\\)");
  std::vector<float> pos(24);
  std::vector<uint32_t> remap(8), idx(36);
  EXPECT_DEATH(weld(pos.data(), remap.data(), idx.data(), span, bad.data(), bad.size()),
               "geom::weld: indices\\[13\\] = 8, expected < 8");
  EXPECT_DEATH(build_topology(span, bad.data(), 12), "geom::build_topology: indices\\[13\\] = 8, expected < 8");
  std::vector<uint32_t> adj(adjacency_bound(12));
  EXPECT_DEATH(build_adjacency(adj.data(), bad.data(), 12, 8), "geom::build_adjacency: indices\\[13\\] = 8");
  EXPECT_DEATH(build_adjacency(nullptr, box.indices.data(), 12, 8), "geom::build_adjacency: null output for 12");

  const Stages s = stages(box);
  const Stages half = stages(fixtures::open_box());  // another mesh's topology and planes
  EXPECT_DEATH(build_adjacency(adj.data(), box.indices.data(), 12, half.topology),
               "geom::build_adjacency: 30 face edges in the topology, expected 36");
  EXPECT_DEATH(compute_face_planes(span, box.indices.data(), 12, half.topology),
               "geom::compute_face_planes: a topology of 10 triangles, expected 12");
  EXPECT_DEATH(build_esm_quads(span, box.indices.data(), 12, s.topology, half.planes),
               "geom::build_esm_quads: 10 face planes, expected 12");
  EXPECT_DEATH(build_shadow_volume(span, box.indices.data(), 12, s.topology, half.planes),
               "geom::build_shadow_volume: 10 face planes, expected 12");
  EXPECT_DEATH(build_esm_quads(nullptr, span, box.indices.data(), 12, s.topology, s.planes),
               "geom::build_esm_quads: null output for 12 triangles");
  std::vector<SvCap> caps(12);
  EXPECT_DEATH(build_shadow_volume(nullptr, caps.data(), span, box.indices.data(), 12, s.topology, s.planes),
               "geom::build_shadow_volume: null output for 12 triangles");
}
#endif
