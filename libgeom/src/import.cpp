// Import dispatcher: reads the file (or an archive member), picks the format
// by extension, and validates what the format importer produced so that every
// later stage can trust it: indices in range, finite positions, one source
// per triangle, limits respected.
#include "geom/import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "archive.h"
#include "importers.h"

namespace geom {
namespace {

std::string lower_extension(const std::string& name) {
  size_t dot = name.find_last_of('.');
  size_t slash = name.find_last_of("/\\:");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string directory_of(const std::string& path) {
  size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

bool read_whole_file(const std::string& path, std::vector<unsigned char>& bytes, uint64_t max_bytes,
                     std::string& error) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    error = "cannot open file";
    return false;
  }
  std::fseek(f, 0, SEEK_END);
  long size = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  if (size < 0) {
    std::fclose(f);
    error = "cannot read file (not a regular file?)";
    return false;
  }
  if (max_bytes && uint64_t(size) > max_bytes) {
    std::fclose(f);
    error = "file is " + std::to_string(size) + " bytes, over the limit of " + std::to_string(max_bytes);
    return false;
  }
  bytes.resize(size_t(size));
  size_t got = size ? std::fread(bytes.data(), 1, bytes.size(), f) : 0;
  std::fclose(f);
  if (got != bytes.size()) {
    error = "cannot read file";
    return false;
  }
  return true;
}

// The checks every importer's output must pass before anyone uses it.
bool validate(Scene& s, const ImportOptions& options, std::string& error) {
  if (s.indices.size() % 3 != 0) {
    error = "internal: index count is not a multiple of 3";
    return false;
  }
  size_t vc = s.vertex_count();
  size_t tc = s.triangle_count();
  if (options.max_triangles && tc > options.max_triangles) {
    error = std::to_string(tc) + " triangles, over the limit of " + std::to_string(options.max_triangles);
    return false;
  }
  for (size_t i = 0; i < s.indices.size(); ++i) {
    if (s.indices[i] >= vc) {
      error = "triangle " + std::to_string(i / 3) + " uses vertex " + std::to_string(s.indices[i]) +
              ", out of range (" + std::to_string(vc) + " vertices)";
      return false;
    }
  }
  for (size_t t = 0; t < s.indices.size(); ++t) {
    const float* p = &s.positions[3 * size_t(s.indices[t])];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      error = "triangle " + std::to_string(t / 3) + " uses vertex " + std::to_string(s.indices[t]) +
              " with a non-finite coordinate";
      return false;
    }
  }
  if (s.sources.size() != tc) s.sources.resize(tc);
  return true;
}

}  // namespace

ImportResult import_memory(const std::string& name, const void* data, size_t size, const ImportOptions& options,
                           const std::string& base_dir) {
  ImportResult result;
  detail::ImportInput in;
  in.name = name;
  in.data = static_cast<const unsigned char*>(data);
  in.size = size;
  in.base_dir = base_dir;
  in.options = options;
  result.scene.files.push_back(name);

  const std::string ext = lower_extension(name);
  bool (*importer)(const detail::ImportInput&, Scene&, std::string&) = nullptr;
  if (ext == "gltf" || ext == "glb") importer = detail::import_gltf;
  else if (ext == "obj") importer = detail::import_obj;
  else if (ext == "ply") importer = detail::import_ply;
  else if (ext == "off") importer = detail::import_off;
  else if (ext == "stl") importer = detail::import_stl;
  else if (ext == "bsp") importer = detail::import_bsp;
  else if (ext == "md3") importer = detail::import_md3;
  if (!importer) {
    result.error = name + ": unknown file type '." + ext +
                   "' (expected .gltf, .glb, .obj, .ply, .off, .stl, .bsp or .md3)";
    return result;
  }
  std::string error;
  bool ok = false;
  try {
    ok = importer(in, result.scene, error);
    if (ok) ok = validate(result.scene, options, error);
  } catch (const std::bad_alloc&) {
    error = "out of memory (the file claims more data than can be held)";
    ok = false;
  } catch (const std::exception& e) {
    error = e.what();
    ok = false;
  }
  if (!ok) {
    result.scene = Scene();
    result.error = name + ": " + (error.empty() ? std::string("cannot be imported") : error);
    return result;
  }
  result.ok = true;
  return result;
}

ImportResult import_file(const std::string& path, const ImportOptions& options) {
  ImportResult result;
  std::vector<unsigned char> bytes;
  std::string error;
  // "ARCHIVE.pk3:member/path" reads a member of a zip archive.
  size_t colon = path.find(".pk3:");
  if (colon == std::string::npos) colon = path.find(".zip:");
  if (colon != std::string::npos) {
    std::string archive = path.substr(0, colon + 4);
    std::string member = path.substr(colon + 5);
    if (!detail::read_archive_member(archive, member, bytes, options.max_bytes, error)) {
      result.error = path + ": " + error;
      return result;
    }
    return import_memory(path, bytes.data(), bytes.size(), options, "");
  }
  if (!read_whole_file(path, bytes, options.max_bytes, error)) {
    result.error = path + ": " + error;
    return result;
  }
  return import_memory(path, bytes.data(), bytes.size(), options, directory_of(path));
}

}  // namespace geom
