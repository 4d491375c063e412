// Import dispatcher: reads the file (or an archive member), picks the format
// by extension, and validates what the format importer produced so that every
// later stage can trust it: indices in range, finite positions, one source
// per triangle, limits respected.
#include "geom/import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <iterator>

#include "file_read.h"
#include "importers.h"
#include "uri.h"

namespace geom {

namespace {

// The formats, by extension: the one list (geom/import.h supported_extensions).
using Importer = bool (*)(const detail::ImportInput&, Scene&, std::string&);
struct Format {
  const char* extension;
  Importer importer;
};
const Format kFormats[] = {{".gltf", detail::import_gltf}, {".glb", detail::import_gltf}, {".obj", detail::import_obj},
                           {".ply", detail::import_ply},   {".off", detail::import_off},  {".stl", detail::import_stl},
                           {".bsp", detail::import_bsp},   {".md3", detail::import_md3}};

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
  return slash == std::string::npos ? std::string("./") : path.substr(0, slash + 1);  // "" would mean no folder
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
  bool all_finite = true;  // then no triangle uses a non-finite vertex: one pass over the vertices, not the corners
  for (size_t i = 0; i < s.positions.size(); i += 3)
    all_finite &= std::isfinite(s.positions[i]) & std::isfinite(s.positions[i + 1]) & std::isfinite(s.positions[i + 2]);
  for (size_t t = 0; !all_finite && t < s.indices.size(); ++t) {
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

const std::vector<std::string>& supported_extensions() {
  static const std::vector<std::string> list = [] {
    std::vector<std::string> out;
    for (const Format& f : kFormats) out.push_back(f.extension);
    return out;
  }();
  return list;
}

bool is_supported_name(const std::string& name) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const Format& f : kFormats) {
    const size_t k = std::strlen(f.extension);
    if (n.size() >= k && n.compare(n.size() - k, k, f.extension) == 0) return true;
  }
  return false;
}

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
  Importer importer = nullptr;
  for (const Format& f : kFormats)
    if (ext == f.extension + 1) importer = f.importer;
  if (!importer) {
    std::string expected;
    for (size_t i = 0; i < std::size(kFormats); ++i)
      expected += std::string(i == 0 ? "" : i + 1 == std::size(kFormats) ? " or " : ", ") + kFormats[i].extension;
    result.error = name + ": unknown file type '." + ext + "' (expected " + expected + ")";
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
  const std::string ext = lower_extension(path);
  if (colon == std::string::npos && (ext == "pk3" || ext == "zip")) {  // an archive, no member named
    std::vector<std::string> names;
    if (!list_archive_members(path, ".bsp", names, error))
      result.error = path + ": " + error;
    else
      result.error = path + (names.empty() ? ": no .bsp map inside the archive"
                                           : ": an archive: name a member (" + path + ":" + names[0] + ")");
    return result;
  }
  if (colon != std::string::npos) {
    std::string archive = path.substr(0, colon + 4);
    std::string member = path.substr(colon + 5);
    if (!read_archive_member(archive, member, bytes, options.max_bytes, error)) {
      result.error = path + ": " + error;
      return result;
    }
    return import_memory(path, bytes.data(), bytes.size(), options, "");
  }
  detail::FileBytes file;  // its own mapping when large: no hole left in the heap
  if (!detail::read_whole_file(path, file, options.max_bytes, error)) {
    result.error = path + ": " + error;
    return result;
  }
  return import_memory(path, file.data(), file.size(), options, directory_of(path));
}

std::vector<std::string> input_dependencies(const std::string& input) {
  std::vector<std::string> deps = {input};
  for (const char* ext : {".pk3:", ".zip:"}) {
    const size_t at = input.find(ext);
    if (at != std::string::npos) {
      deps[0] = input.substr(0, at + 4);
      return deps;
    }
  }
  const size_t dot = input.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : input.substr(dot);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  std::vector<unsigned char> bytes;
  std::string error;
  if (ext != ".gltf" || !detail::read_whole_file(input, bytes, 0, error)) return deps;
  const size_t slash = input.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : input.substr(0, slash + 1);
  for (const std::string& uri : detail::gltf_buffer_uris(bytes.data(), bytes.size())) {
    const std::string path = dir + detail::percent_decode(uri);  // as the importer reads it (uri.h)
    if (std::find(deps.begin(), deps.end(), path) == deps.end()) deps.push_back(path);
  }
  return deps;
}

}  // namespace geom
