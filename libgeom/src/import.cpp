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
#include "geom/validate.h"
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
// The scene the importer made, checked as any untrusted soup is
// (geom/validate.h), and against the caller's limit.
Status validate(Scene& s, const std::string& name, const ImportOptions& options) {
  Status st;
  const size_t tc = s.triangle_count();
  if (options.max_triangles && tc > options.max_triangles) {
    st.code = ErrorCode::TooLarge;
    st.error =
        name + ": " + std::to_string(tc) + " triangles, over the limit of " + std::to_string(options.max_triangles);
    return st;
  }
  st = validate_triangles(positions_of(s.positions.data(), s.vertex_count()), s.indices.data(), s.indices.size(), name);
  if (st.ok && s.sources.size() != tc) s.sources.resize(tc);
  return st;
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
    result.code = ErrorCode::Malformed;
    result.error = name + ": unknown file type '." + ext + "' (expected " + expected + ")";
    return result;
  }
  std::string error;
  bool ok = false;
  ErrorCode code = ErrorCode::Malformed;
  try {
    ok = importer(in, result.scene, error);
    if (ok) {
      Status checked = validate(result.scene, name, options);
      if (!checked.ok) {
        result.scene = Scene();
        static_cast<Status&>(result) = std::move(checked);
        return result;
      }
    }
  } catch (const std::bad_alloc&) {
    error = "out of memory (the file claims more data than can be held)";
    code = ErrorCode::OutOfMemory;
    ok = false;
  } catch (const std::exception& e) {
    error = e.what();
    ok = false;
  }
  if (!ok) {
    result.scene = Scene();
    result.code = code;
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
    result.code = ErrorCode::Malformed;
    if (!list_archive_members(path, ".bsp", names, error))
      result.code = ErrorCode::Io, result.error = path + ": " + error;
    else
      result.error = path + (names.empty() ? ": no .bsp map inside the archive"
                                           : ": an archive: name a member (" + path + ":" + names[0] + ")");
    return result;
  }
  if (colon != std::string::npos) {
    std::string archive = path.substr(0, colon + 4);
    std::string member = path.substr(colon + 5);
    if (!read_archive_member(archive, member, bytes, options.max_bytes, error)) {
      result.code = ErrorCode::Io;
      result.error = path + ": " + error;
      return result;
    }
    return import_memory(path, bytes.data(), bytes.size(), options, "");
  }
  detail::FileBytes file;  // its own mapping when large: no hole left in the heap
  if (!detail::read_whole_file(path, file, options.max_bytes, error)) {
    result.code = ErrorCode::Io;
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
