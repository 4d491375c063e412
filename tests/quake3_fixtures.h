// Shared by the Quake 3 tests (test_import_bsp.cpp, libgeom/tests/test_bsp_patch.cpp,
// test_import_md3.cpp, test_shadow_volume_maps.cpp): OpenArena's archives
// (Debian packages openarena-081-maps and openarena-081-players), little-endian
// record access, and the independent parse of a BSP's lumps, which reads them
// with its own code (memcpy of little-endian records), never through the
// importer.
#pragma once
#include <embree3/rtcore.h>
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

#include "geom/extrude.h"
#include "geom/face_planes.h"
#include "geom/import.h"
#include "geom/report.h"
#include "geom/shadow_volume.h"
#include "geom/topology.h"
#include "geom/weld.h"

using namespace geom;

namespace q3test {
using namespace geom;

inline const std::string kBaseoa = "/usr/share/games/openarena/baseoa/";
inline const std::string kMaps = kBaseoa + "pak1-maps.pk3";
inline const std::string kPlayers = kBaseoa + "pak2-players.pk3";

inline std::vector<unsigned char> member(const std::string& archive, const std::string& name) {
  std::vector<unsigned char> bytes;
  std::string error;
  EXPECT_TRUE(read_archive_member(archive, name, bytes, 0, error)) << error;
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

inline uint64_t count_of(const Scene& s, const std::string& key) {
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

inline RawBsp parse_raw(std::vector<unsigned char> bytes) {
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

inline RawBsp raw_map(const std::string& name) { return parse_raw(member(kMaps, "maps/" + name)); }

inline ImportResult import_bytes(const std::string& name, const std::vector<unsigned char>& b, int level = 4) {
  ImportOptions o;
  o.patch_level = level;
  return import_memory(name, b.data(), b.size(), o);
}

// Maps chosen for their mix: brush models and mesh faces (oa_dm1), 9x7 patches
// and sky (oa_ctf2), many patch sizes (oa_dm3, oa_dm5), never-drawn patches
// (delta, oa_spirit3), polygons only (q3dm6ish).
inline const char* const kCountMaps[] = {"oa_dm1.bsp", "oa_ctf2.bsp",    "oa_dm3.bsp",  "oa_dm5.bsp",
                                         "delta.bsp",  "oa_spirit3.bsp", "q3dm6ish.bsp"};

// The importer's refusal of `bytes`: its message (which must name the file
// first, with an empty scene), or "accepted".
inline std::string refusal(const std::vector<unsigned char>& bytes, const std::string& name = "hostile.bsp",
                           ImportOptions options = {}) {
  ImportResult r = import_memory(name, bytes.data(), bytes.size(), options);
  if (r.ok) return "accepted";
  EXPECT_EQ(r.error.rfind(name + ": ", 0), 0u) << r.error;  // names the file first
  EXPECT_TRUE(r.scene.positions.empty() && r.scene.indices.empty());
  return r.error;
}

}  // namespace q3test
