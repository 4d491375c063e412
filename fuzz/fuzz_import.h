// Shared body of the importer fuzz targets (fuzz/fuzz_<format>.cpp), also
// used by tests/test_fuzz_regressions.cpp to replay the crashers found.
//
// Each target hands the fuzzer's bytes to geom::import_memory under a file name
// of its format's extension, then checks the importer's contract (geom/import.h)
// on whatever comes back, aborting (a finding) when it is broken:
//   refused  -> the message starts with "NAME: " and the scene is empty;
//   accepted -> 3 indices per triangle, every index below the vertex count,
//               every position finite, one source per triangle.
// Memory and crashes are checked by the sanitizers the fuzz build adds
// (-fsanitize=fuzzer,address,undefined). The limits below keep a legitimately
// huge output (a small file may instance a mesh many times) inside libFuzzer's
// default 2 GB RSS limit; they are options a user has too (--max-triangles,
// --max-memory), so hitting them is an ordinary refusal, not a finding.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "geom/import.h"

namespace geom_fuzz {

inline geom::ImportOptions fuzz_options() {
  geom::ImportOptions options;
  options.max_triangles = uint64_t(1) << 20;
  options.max_bytes = uint64_t(256) << 20;
  return options;
}

// The contract of geom/import.h on one result: "" when kept, else what is broken.
inline std::string broken_contract(const std::string& name, const geom::ImportResult& r) {
  if (!r.ok) {
    if (r.error.rfind(name + ": ", 0) != 0) return "error does not name the file first: " + r.error;
    if (r.error.size() <= name.size() + 2) return "error does not say what is wrong: " + r.error;
    if (!r.scene.positions.empty() || !r.scene.indices.empty()) return "refused scene is not empty: " + r.error;
    return "";
  }
  const geom::Scene& s = r.scene;
  if (s.indices.size() % 3 || s.positions.size() % 3) return "index or position count not a multiple of 3";
  if (s.sources.size() != s.triangle_count()) return "not one source per triangle";
  for (uint32_t i : s.indices) {
    if (i >= s.vertex_count()) return "index " + std::to_string(i) + " out of range";
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.positions[3 * size_t(i) + k])) return "non-finite position " + std::to_string(i);
  }
  return "";
}

// The file name a target's bytes are imported under: the extension picks the importer.
inline std::string name_for(const std::string& target, const uint8_t* data, size_t size) {
  if (target == "gltf") return size >= 4 && std::memcmp(data, "glTF", 4) == 0 ? "fuzz.glb" : "fuzz.gltf";
  if (target == "draco") return "fuzz.glb";
  return "fuzz." + target;
}

// A Draco stream as the BIN chunk of a fixed GLB whose only primitive points its
// KHR_draco_mesh_compression extension at it (POSITION = Draco attribute 0).
inline std::vector<uint8_t> draco_glb(const uint8_t* data, size_t size) {
  auto put_u32 = [](std::vector<uint8_t>& b, uint32_t v) {
    for (int k = 0; k < 4; ++k) b.push_back(uint8_t(v >> (8 * k)));
  };
  const std::string n = std::to_string(size);
  std::string json =
      R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_draco_mesh_compression"],)"
      R"("extensionsRequired":["KHR_draco_mesh_compression"],"buffers":[{"byteLength":)" + n +
      R"(}],"bufferViews":[{"buffer":0,"byteLength":)" + n +
      R"(}],"accessors":[{"componentType":5126,"count":3,"type":"VEC3"},)"
      R"({"componentType":5125,"count":3,"type":"SCALAR"}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},)"
      R"("indices":1,"extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":0}}}}]}],)"
      R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
  while (json.size() % 4) json += ' ';
  const size_t bin = (size + 3) & ~size_t(3);
  std::vector<uint8_t> glb;
  glb.reserve(12 + 8 + json.size() + 8 + bin);
  glb.insert(glb.end(), {'g', 'l', 'T', 'F'});
  put_u32(glb, 2);
  put_u32(glb, uint32_t(12 + 8 + json.size() + 8 + bin));
  put_u32(glb, uint32_t(json.size()));
  glb.insert(glb.end(), {'J', 'S', 'O', 'N'});
  glb.insert(glb.end(), json.begin(), json.end());
  put_u32(glb, uint32_t(bin));
  glb.insert(glb.end(), {'B', 'I', 'N', 0});
  glb.insert(glb.end(), data, data + size);
  glb.resize(glb.size() + bin - size, 0);
  return glb;
}

// One fuzz input of `target` (gltf, draco, obj, ply, off, stl, bsp, md3):
// imported as the fuzz target does; returns the broken contract or "".
inline std::string import_one(const std::string& target, const uint8_t* data, size_t size) {
  const std::string name = name_for(target, data, size);
  if (target == "draco") {
    if (size == 0 || size > (1u << 24)) return "";
    const std::vector<uint8_t> glb = draco_glb(data, size);
    return broken_contract(name, geom::import_memory(name, glb.data(), glb.size(), fuzz_options()));
  }
  return broken_contract(name, geom::import_memory(name, data, size, fuzz_options()));
}

// The body of every importer fuzz target: a broken contract aborts (a finding).
inline int fuzz_import(const std::string& target, const uint8_t* data, size_t size) {
  const std::string broken = import_one(target, data, size);
  if (!broken.empty()) {
    std::fprintf(stderr, "contract broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}

}  // namespace geom_fuzz
