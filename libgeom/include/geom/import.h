// geom/import.h: load a mesh file into a Scene.
//
// Formats, chosen by extension (case-insensitive):
//   .gltf .glb  glTF 2.0 (external / data-URI buffers, KHR_draco_mesh_compression,
//               KHR_mesh_quantization, sparse accessors, KHR_lights_punctual)
//   .obj .ply .off .stl
//   .bsp .md3   Quake 3 (also "ARCHIVE.pk3:path/inside.bsp")
// Errors are returned, never thrown, in the library's one style (geom/status.h):
// ImportResult::code says what kind (Malformed, IndexOutOfRange, NonFinite,
// TooLarge, OutOfMemory, Io), ImportResult::error is one line of the form
// "FILE: what is wrong". Non-fatal problems land in Scene::warnings.
// Safe to call on untrusted input: no crash, no unbounded allocation, no hang.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geom/scene.h"
#include "geom/status.h"

namespace geom {

struct ImportOptions {
  int patch_level = 4;              // BSP Bezier patch tessellation (segments per side)
  int md3_frame = 0;                // MD3 frame to import
  uint64_t max_triangles = 0;       // 0 = no limit; larger inputs are refused
  uint64_t max_bytes = 0;           // 0 = no limit on the memory one input may claim
  bool allow_outside_uris = false;  // glTF: read external buffers outside the asset's folder too
};

struct ImportResult : Status {  // ok, code, error: "FILE: what is wrong" when !ok
  Scene scene;
};

ImportResult import_file(const std::string& path, const ImportOptions& options = {});

// The extensions the importers read, lower case with their dot, in the order
// of the list above: ".gltf", ".glb", ".obj", ".ply", ".off", ".stl", ".bsp", ".md3".
const std::vector<std::string>& supported_extensions();
// Whether `name` ends in one of them (case-insensitive): a file import_file
// would try (a tree walk's filter).
bool is_supported_name(const std::string& name);

// The members of a zip (.pk3) archive whose names end with `suffix`
// (case-insensitive, e.g. ".bsp"), sorted: what "ARCHIVE.pk3:member" can name.
// False with `error` set when the archive cannot be opened or read.
bool list_archive_members(const std::string& archive, const std::string& suffix, std::vector<std::string>& names,
                          std::string& error);
// One member of a zip archive, whole, found by its exact name or else
// case-insensitively: what import_file reads for "ARCHIVE.pk3:member". False
// with `error` set when the archive cannot be opened, the member is missing or
// corrupt, or it is larger than max_bytes (0 = no limit) or this machine's memory.
bool read_archive_member(const std::string& archive, const std::string& member, std::vector<unsigned char>& bytes,
                         uint64_t max_bytes, std::string& error);

// The files that `input` (a name as import_file takes it) is made from, for a
// depfile: the file itself, or its archive for "ARCHIVE.pk3:member" (or
// ".zip:"); and for a .gltf the external buffer files its JSON names, each
// percent-decoded and joined to the input's folder as the importer reads them
// (data: URIs are none; images are never read, so they are no dependency). An
// unreadable or malformed .gltf lists itself only.
std::vector<std::string> input_dependencies(const std::string& input);

// Import from bytes already in memory; `name` decides the format (by extension)
// and appears in messages. `base_dir` resolves relative URIs (glTF), may be empty.
ImportResult import_memory(const std::string& name, const void* data, size_t size, const ImportOptions& options = {},
                           const std::string& base_dir = "");

}  // namespace geom
