// The shadow volume's bookkeeping (geom/shadow_volume.h): the component ids
// build_light_volume reads, against components found independently (a flood
// over each edge's non-degenerate faces); ShadowVolumeOptions::component_ids
// off changes no record, cap or plane; the FacePlanes&& overload gives the
// same volume and takes the plane table; the volume streamed (sides_out,
// caps_out) is the kept one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "geom/shadow_volume.h"
#include "silhouette_fixtures.h"

namespace {

using fixtures::Mesh;

std::vector<Mesh> meshes() {
  return {fixtures::box(-1, -1, -1, 1, 1, 1), fixtures::sphere(12, 7), fixtures::torus(12, 8),
          fixtures::sheet(6, 0.3),           fixtures::open_box(),    fixtures::book(4),
          fixtures::bowtie(),                fixtures::flipped_box(), fixtures::degenerate_box(),
          fixtures::stack(),                 fixtures::sliver_box()};
}

geom::ShadowVolume volume(const fixtures::Baked& b, const geom::ShadowVolumeOptions& o = {}) {
  return geom::build_shadow_volume(geom::positions_of(b.weld.positions.data(), b.weld.vertex_count()),
                                   b.weld.indices.data(), b.weld.indices.size() / 3, b.topology, b.planes, o);
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Per face: its component, numbered in face order (kNone: degenerate), by a
// flood over the edges' faces that have a plane; and per component whether
// every edge has exactly two such faces running it in opposite directions.
struct Components {
  std::vector<uint32_t> of_face;
  std::vector<uint8_t> closed;
};

Components flood(const fixtures::Baked& b) {
  const geom::Topology& t = b.topology;
  const size_t n = b.weld.indices.size() / 3;
  const auto live = [&](uint32_t f) { return b.planes.face_plane[f] != geom::FacePlanes::kNone; };
  std::vector<std::vector<uint32_t>> edges_of(n);
  for (uint32_t e = 0; e < t.edges.size(); ++e)
    for (uint32_t i = 0; i < t.edges[e].face_count; ++i) edges_of[t.edge_faces[t.edges[e].first + i] >> 1].push_back(e);
  Components c;
  c.of_face.assign(n, geom::Topology::kNone);
  for (uint32_t seed = 0; seed < n; ++seed) {
    if (!live(seed) || c.of_face[seed] != geom::Topology::kNone) continue;
    const uint32_t id = uint32_t(c.closed.size());
    c.closed.push_back(1);
    std::vector<uint32_t> todo = {seed};
    c.of_face[seed] = id;
    while (!todo.empty()) {
      const uint32_t f = todo.back();
      todo.pop_back();
      for (uint32_t e : edges_of[f]) {
        std::vector<uint32_t> faces;
        for (uint32_t i = 0; i < t.edges[e].face_count; ++i)
          if (live(t.edge_faces[t.edges[e].first + i] >> 1)) faces.push_back(t.edge_faces[t.edges[e].first + i]);
        if (!(faces.size() == 2 && ((faces[0] ^ faces[1]) & 1))) c.closed[id] = 0;
        for (uint32_t ef : faces)
          if (c.of_face[ef >> 1] == geom::Topology::kNone) c.of_face[ef >> 1] = id, todo.push_back(ef >> 1);
      }
    }
  }
  return c;
}

TEST(ShadowVolumeOptions, ComponentIdsMatchAFlood) {
  for (const Mesh& m : meshes()) {
    for (bool one_sided : {false, true}) {
      geom::ShadowVolumeOptions o;
      o.one_sided_closed = one_sided;
      const fixtures::Baked b = fixtures::bake(m, o);
      const geom::ShadowVolume& sv = b.volume;
      const Components c = flood(b);
      ASSERT_EQ(sv.component_closed, c.closed) << m.name;
      EXPECT_EQ(sv.stats.components, c.closed.size()) << m.name;
      ASSERT_EQ(sv.cap_component.size(), sv.caps.size()) << m.name;
      ASSERT_EQ(sv.side_component.size(), sv.sides.size()) << m.name;
      // Caps are the live faces in face order.
      size_t cap = 0;
      for (size_t f = 0; f < c.of_face.size(); ++f) {
        if (c.of_face[f] == geom::Topology::kNone) continue;
        ASSERT_LT(cap, sv.caps.size()) << m.name;
        EXPECT_EQ(sv.cap_component[cap], c.of_face[f]) << m.name << " face " << f;
        EXPECT_EQ(bool(sv.caps[cap].plane & geom::SvCap::kDoubleSided), !one_sided || !c.closed[c.of_face[f]])
            << m.name << " face " << f;
        ++cap;
      }
      EXPECT_EQ(cap, sv.caps.size()) << m.name;
      // A record's component holds a face whose stored plane the record names.
      for (size_t i = 0; i < sv.sides.size(); ++i) {
        const uint32_t plane = sv.sides[i].plane_a & 0x7fffffffu, id = sv.side_component[i];
        bool found = false;
        for (size_t f = 0; f < c.of_face.size() && !found; ++f)
          found = c.of_face[f] == id && b.planes.face_plane[f] == plane;
        EXPECT_TRUE(found) << m.name << " record " << i;
        if (one_sided && c.closed[id]) EXPECT_FALSE(sv.sides[i].plane_a & geom::SvSide::kSecond) << m.name;
      }
    }
  }
}

TEST(ShadowVolumeOptions, WithoutComponentIdsTheSameRecords) {
  for (const Mesh& m : meshes()) {
    const fixtures::Baked b = fixtures::bake(m);
    geom::ShadowVolumeOptions off;
    off.component_ids = false;
    const geom::ShadowVolume with = volume(b), without = volume(b, off);
    EXPECT_TRUE(same_bytes(with.sides, without.sides)) << m.name;
    EXPECT_TRUE(same_bytes(with.caps, without.caps)) << m.name;
    EXPECT_TRUE(same_bytes(with.planes, without.planes)) << m.name;
    EXPECT_TRUE(same_bytes(with.sides, b.volume.sides)) << m.name;
    EXPECT_FALSE(with.side_component.empty()) << m.name;
    EXPECT_TRUE(without.side_component.empty() && without.cap_component.empty() && without.component_closed.empty())
        << m.name;
    EXPECT_EQ(with.stats.bytes, without.stats.bytes) << m.name;
    EXPECT_EQ(with.stats.pair_edges, without.stats.pair_edges) << m.name;
    EXPECT_EQ(with.stats.skipped_coplanar_records, without.stats.skipped_coplanar_records) << m.name;
    EXPECT_EQ(with.stats.double_sided_faces, without.stats.double_sided_faces) << m.name;
    // one_sided_closed needs the components: it computes them whatever the option says.
    geom::ShadowVolumeOptions one = off;
    one.one_sided_closed = true;
    const geom::ShadowVolume one_sided = volume(b, one);
    EXPECT_EQ(one_sided.cap_component.size(), one_sided.caps.size()) << m.name;
    // And a light volume from an id-less volume stays double-sided: correct, never smaller.
    const float light[4] = {3.0f, 4.0f, 5.0f, 1.0f};
    const geom::ShadowVolume lw = geom::build_light_volume(with, light), lo = geom::build_light_volume(without, light);
    EXPECT_EQ(lo.stats.light_one_sided, 0u) << m.name;
    EXPECT_GE(lo.sides.size() + lo.caps.size(), lw.sides.size() + lw.caps.size()) << m.name;
  }
}

TEST(ShadowVolumeOptions, MovedPlanesTheSameVolume) {
  for (const Mesh& m : meshes()) {
    fixtures::Baked b = fixtures::bake(m);
    const geom::ShadowVolume copied = volume(b);
    const std::vector<float> planes = b.planes.planes;
    const geom::ShadowVolume moved =
        geom::build_shadow_volume(geom::positions_of(b.weld.positions.data(), b.weld.vertex_count()),
                                  b.weld.indices.data(), b.weld.indices.size() / 3, b.topology, std::move(b.planes));
    EXPECT_TRUE(b.planes.planes.empty()) << m.name;
    EXPECT_FALSE(b.planes.face_plane.empty()) << m.name;
    EXPECT_TRUE(same_bytes(moved.planes, planes)) << m.name;
    EXPECT_TRUE(same_bytes(moved.sides, copied.sides)) << m.name;
    EXPECT_TRUE(same_bytes(moved.caps, copied.caps)) << m.name;
    EXPECT_EQ(moved.stats.bytes, copied.stats.bytes) << m.name;
    EXPECT_EQ(moved.side_component, copied.side_component) << m.name;
  }
}

}  // namespace

// The volume streamed (ShadowVolumeOptions::sides_out / caps_out) is the kept
// one, record for record and in order, in pieces of at most 4096, with the
// same stats; nothing of it is kept. Every fixture (open, non-manifold,
// degenerate ones included), one- and double-sided, and a sphere of more than
// 4096 records of each kind, so the pieces split.
TEST(ShadowVolume, StreamedRecordsAreTheKeptOnes) {
  std::vector<Mesh> all = meshes();
  all.push_back(fixtures::sphere(80, 40));
  for (const Mesh& m : all)
    for (bool one_sided : {false, true}) {
      geom::ShadowVolumeOptions kept;
      kept.one_sided_closed = one_sided;
      const fixtures::Baked b = fixtures::bake(m, kept);
      std::vector<geom::SvSide> sides;
      std::vector<geom::SvCap> caps;
      size_t most = 0, calls = 0;
      geom::ShadowVolumeOptions streamed = kept;
      streamed.sides_out = [&](const geom::SvSide* p, size_t n) {
        EXPECT_TRUE(caps.empty()) << "a side after a cap";
        sides.insert(sides.end(), p, p + n), most = std::max(most, n), ++calls;
      };
      streamed.caps_out = [&](const geom::SvCap* p, size_t n) {
        caps.insert(caps.end(), p, p + n), most = std::max(most, n), ++calls;
      };
      const geom::ShadowVolume v = volume(b, streamed);
      const std::string what = m.name + (one_sided ? " one-sided" : "");
      ASSERT_EQ(sides.size(), b.volume.sides.size()) << what;
      ASSERT_EQ(caps.size(), b.volume.caps.size()) << what;
      EXPECT_TRUE(same_bytes(sides, b.volume.sides)) << what;
      EXPECT_TRUE(same_bytes(caps, b.volume.caps)) << what;
      EXPECT_LE(most, 4096u) << what;
      EXPECT_TRUE(v.sides.empty() && v.caps.empty() && v.side_component.empty() && v.cap_component.empty()) << what;
      EXPECT_EQ(v.stats.sides, b.volume.stats.sides) << what;
      EXPECT_EQ(v.stats.caps, b.volume.stats.caps) << what;
      EXPECT_EQ(v.stats.bytes, b.volume.stats.bytes) << what;
      EXPECT_EQ(v.planes, b.volume.planes) << what;
      if (m.name == "sphere" && b.volume.caps.size() > 4096) EXPECT_GT(calls, 3u) << what;
    }
}
