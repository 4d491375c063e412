// Private: one function per format, called by import.cpp's dispatcher.
// Each fills `out` (world-space triangles, sources, lights, warnings) or
// returns false with `error` set to "what is wrong" (the dispatcher prefixes
// the file name). They must be safe on hostile input: check every count and
// offset against the bytes before allocating or reading.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geom/import.h"

namespace geom::detail {

struct ImportInput {
  std::string name;  // file name as given (for messages and Scene::files)
  const unsigned char* data = nullptr;
  size_t size = 0;
  std::string base_dir;  // for relative URIs; may be empty
  ImportOptions options;
};

bool import_gltf(const ImportInput& in, Scene& out, std::string& error);
bool import_obj(const ImportInput& in, Scene& out, std::string& error);
bool import_ply(const ImportInput& in, Scene& out, std::string& error);
bool import_off(const ImportInput& in, Scene& out, std::string& error);
bool import_stl(const ImportInput& in, Scene& out, std::string& error);
bool import_bsp(const ImportInput& in, Scene& out, std::string& error);
bool import_md3(const ImportInput& in, Scene& out, std::string& error);

// The URIs of a glTF JSON's buffers that are not data: URIs, as written (none
// if the JSON does not parse): geom/import.h input_dependencies.
std::vector<std::string> gltf_buffer_uris(const unsigned char* data, size_t size);

// draco_guard.cpp: libdraco's texture-coordinate decoders with their orientation
// count bounded. draco_guard_refusal() returns (and clears) why the guard last
// refused on this thread, "" if it did not; draco_guard_checks(i) counts the counts
// checked by instantiation i: 0 portable / 1 deprecated scheme on the position
// corner table, 2 / 3 on an attribute corner table.
std::string draco_guard_refusal();
uint64_t draco_guard_checks(int which);

}  // namespace geom::detail
