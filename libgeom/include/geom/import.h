// geom/import.h: load a mesh file into a Scene.
//
// Formats, chosen by extension (case-insensitive):
//   .gltf .glb  glTF 2.0 (external / data-URI buffers, KHR_draco_mesh_compression,
//               KHR_mesh_quantization, sparse accessors, KHR_lights_punctual)
//   .obj .ply .off .stl
//   .bsp .md3   Quake 3 (also "ARCHIVE.pk3:path/inside.bsp")
// Errors are returned, never thrown: ImportResult::error is one line of the form
// "FILE: what is wrong". Non-fatal problems land in Scene::warnings.
// Safe to call on untrusted input: no crash, no unbounded allocation, no hang.
#pragma once
#include <cstdint>
#include <string>

#include "geom/scene.h"

namespace geom {

struct ImportOptions {
  int patch_level = 4;              // BSP Bezier patch tessellation (segments per side)
  int md3_frame = 0;                // MD3 frame to import
  uint64_t max_triangles = 0;       // 0 = no limit; larger inputs are refused
  uint64_t max_bytes = 0;           // 0 = no limit on the memory one input may claim
  bool allow_outside_uris = false;  // glTF: read external buffers outside the asset's folder too
};

struct ImportResult {
  bool ok = false;
  std::string error;  // "FILE: what is wrong" when !ok
  Scene scene;
};

ImportResult import_file(const std::string& path, const ImportOptions& options = {});

// Import from bytes already in memory; `name` decides the format (by extension)
// and appears in messages. `base_dir` resolves relative URIs (glTF), may be empty.
ImportResult import_memory(const std::string& name, const void* data, size_t size, const ImportOptions& options = {},
                           const std::string& base_dir = "");

}  // namespace geom
