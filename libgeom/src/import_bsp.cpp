// Quake 3 BSP import (IBSP version 46, as shipped in Debian's openarena-081-maps).
//
// The test bed of Arneson n.d. (Real-Time Shadows, Sect. 2): a map is a list of
// models, model 0 the static world and the others brush models (doors, lifts);
// each model is a range of faces of four types:
//   1 polygon    convex planar polygon, triangulated by the map compiler:
//                triangles are face.vertex + meshvert[face.meshvert + k]
//   2 patch      a grid of size[0] x size[1] control points (face.vertex ...),
//                biquadratic Bezier pieces tessellated at ImportOptions::
//                patch_level segments per piece side (bsp_patch.h: the borders
//                that neighbouring patches share come out bit-identical)
//   3 mesh       a triangle mesh, same encoding as polygons
//   4 billboard  a sprite that turns to the viewer: skipped and counted
//
// Output conventions:
// - Units and axes are Quake's, as in the file: inches-like "units", Z up,
//   right-handed.
// - Winding: Quake 3 stores triangles clockwise seen from the front (checked on
//   OpenArena's maps against the face normals); they are reversed here so that
//   the front is counter-clockwise like every other importer (glTF convention).
// - TriangleSource::mesh = model index (0 = world), primitive = face index.
// - Only vertices that some triangle uses are kept, in order of first use;
//   each patch gets its own tessellated vertices (weld to join patches).
// - Faces whose shader has SURF_NODRAW (0x80) are never drawn by the engine,
//   so they cast no shadow there either: they are skipped (no geometry), counted
//   as "nodraw.faces" and in a warning. Faces with SURF_SKY (0x4) are drawn
//   (the sky box) and kept; they are counted as "sky.faces". Billboards and
//   faces that no model lists are skipped with a warning too.
// - Patch borders are exact where neighbouring patches share control points;
//   some OpenArena maps hold control points meant to coincide that differ in
//   the last bit (oa_dm3: 832 -31.9999924 0 against 832 -32 0), which leaves
//   gaps of that size (under 1e-3 units): weld with a tolerance to close them.
// - Scene::source_counts: ("polygon.faces", n), ("polygon.triangles", n), the
//   same for "mesh" and "patch", ("billboard.faces", n), ("nodraw.faces", n),
//   ("sky.faces", n). The face counts cover every face of the file by type; the
//   triangle counts are the triangles emitted.
//
// Hostile input: every lump must lie inside the file and be a whole number of
// records; every index (texture, vertex range, mesh vertex, model face range)
// is checked before use; patch sizes must be odd and in [3, 65]; a face may
// belong to one model only; the triangle total is computed before anything is
// allocated and refused above ImportOptions::max_triangles, or above
// kDefaultTriangleCap (2^24) when that is 0: mesh-vertex and vertex ranges may
// legally overlap (OpenArena's polygons share them), so a small file can claim
// any number of triangles.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "bsp_patch.h"
#include "importers.h"

namespace geom::detail {
namespace {

constexpr uint64_t kDefaultTriangleCap = uint64_t(1) << 24;  // 16.7M triangles, ~470 MB of output
constexpr int kLumpCount = 17;
constexpr size_t kHeaderSize = 8 + 8 * kLumpCount;
enum { kTextures = 1, kModels = 7, kVertexes = 10, kMeshVerts = 11, kFaces = 13 };
constexpr size_t kTextureSize = 72, kModelSize = 40, kVertexSize = 44, kFaceSize = 104;
constexpr int32_t kSurfSky = 0x4, kSurfNoDraw = 0x80;
enum FaceType { kPolygon = 1, kPatch = 2, kMesh = 3, kBillboard = 4 };
const char* const kLumpNames[kLumpCount] = {"entities",      "textures",      "planes",  "nodes",   "leafs",
                                            "leaf faces",    "leaf brushes",  "models",  "brushes", "brush sides",
                                            "vertexes",      "mesh vertices", "effects", "faces",   "lightmaps",
                                            "light volumes", "visibility"};

uint32_t u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
int32_t i32(const unsigned char* p) {
  uint32_t u = u32(p);
  int32_t v;
  std::memcpy(&v, &u, 4);
  return v;
}
float f32(const unsigned char* p) {
  uint32_t u = u32(p);
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}

struct Lump {
  const unsigned char* data = nullptr;
  size_t count = 0;
};

struct Face {
  int32_t texture, type, vertex, vertex_count, meshvert, meshvert_count, width, height;
};

std::string face_name(size_t f, const Face& face) {
  static const char* const names[] = {"", "polygon", "patch", "mesh", "billboard"};
  const char* kind = face.type >= 1 && face.type <= 4 ? names[face.type] : "face";
  return "face " + std::to_string(f) + " (" + kind + ")";
}

bool read_lumps(const ImportInput& in, Lump lumps[kLumpCount], std::string& error) {
  static const size_t record[kLumpCount] = {1, kTextureSize, 1, 1, 1,         1, 1, kModelSize, 1,
                                            1, kVertexSize,  4, 1, kFaceSize, 1, 1, 1};
  for (int l = 0; l < kLumpCount; ++l) {
    const int64_t offset = i32(in.data + 8 + 8 * l), length = i32(in.data + 12 + 8 * l);
    if (offset < 0 || length < 0 || uint64_t(offset) + uint64_t(length) > in.size) {
      error = std::string(kLumpNames[l]) + " lump (offset " + std::to_string(offset) + ", length " +
              std::to_string(length) + ") lies outside the file (" + std::to_string(in.size) + " bytes)";
      return false;
    }
    if (length % int64_t(record[l]) != 0) {
      error = std::string(kLumpNames[l]) + " lump length " + std::to_string(length) + " is not a multiple of its " +
              std::to_string(record[l]) + "-byte record";
      return false;
    }
    lumps[l].data = in.data + offset;
    lumps[l].count = size_t(length) / record[l];
  }
  return true;
}

// Checks one face against the lumps; the message names the face and the problem.
bool check_face(size_t f, const Face& face, const Lump lumps[], std::string& error) {
  const std::string name = face_name(f, face);
  if (face.type < kPolygon || face.type > kBillboard) {
    error = name + " has unknown type " + std::to_string(face.type) + " (expected 1 to 4)";
    return false;
  }
  if (face.texture < 0 || size_t(face.texture) >= lumps[kTextures].count) {
    error = name + " uses shader " + std::to_string(face.texture) + ", out of range (" +
            std::to_string(lumps[kTextures].count) + " shaders)";
    return false;
  }
  if (face.type == kBillboard) return true;
  const uint64_t vertices = lumps[kVertexes].count;
  if (face.vertex < 0 || face.vertex_count < 0 || uint64_t(face.vertex) + uint64_t(face.vertex_count) > vertices) {
    error = name + " uses vertices " + std::to_string(face.vertex) + " to " +
            std::to_string(int64_t(face.vertex) + face.vertex_count) + ", out of range (" + std::to_string(vertices) +
            " vertices)";
    return false;
  }
  if (face.type == kPatch) {
    if (!patch_size_valid(face.width, face.height)) {
      error = name + " has " + std::to_string(face.width) + " x " + std::to_string(face.height) +
              " control points (each side must be odd, from 3 to " + std::to_string(kMaxPatchControl) + ")";
      return false;
    }
    if (int64_t(face.width) * face.height != face.vertex_count) {
      error = name + " has " + std::to_string(face.width) + " x " + std::to_string(face.height) +
              " control points but " + std::to_string(face.vertex_count) + " vertices";
      return false;
    }
    return true;
  }
  const uint64_t meshverts = lumps[kMeshVerts].count;
  if (face.meshvert < 0 || face.meshvert_count < 0 ||
      uint64_t(face.meshvert) + uint64_t(face.meshvert_count) > meshverts) {
    error = name + " uses mesh vertices " + std::to_string(face.meshvert) + " to " +
            std::to_string(int64_t(face.meshvert) + face.meshvert_count) + ", out of range (" +
            std::to_string(meshverts) + " mesh vertices)";
    return false;
  }
  if (face.meshvert_count % 3 != 0) {
    error = name + " has " + std::to_string(face.meshvert_count) + " mesh vertices, not a multiple of 3";
    return false;
  }
  for (int32_t k = 0; k < face.meshvert_count; ++k) {
    const int32_t m = i32(lumps[kMeshVerts].data + 4 * (size_t(face.meshvert) + size_t(k)));
    if (m < 0 || m >= face.vertex_count) {
      error = name + " mesh vertex " + std::to_string(face.meshvert + k) + " = " + std::to_string(m) +
              ", out of range (the face has " + std::to_string(face.vertex_count) + " vertices)";
      return false;
    }
  }
  return true;
}

const float* vertex_position(const Lump lumps[], size_t v, float out[3]) {
  const unsigned char* p = lumps[kVertexes].data + kVertexSize * v;
  out[0] = f32(p), out[1] = f32(p + 4), out[2] = f32(p + 8);
  return out;
}

bool finite3(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// What the checks of the lumps give the emission.
struct BspMap {
  Lump lumps[kLumpCount];
  std::vector<int32_t> texture_flags;  // per shader
  std::vector<Face> faces;
  std::vector<uint32_t> face_model;  // per face: its model, or kNone
  uint64_t polygon_faces = 0, mesh_faces = 0, patch_faces = 0, billboard_faces = 0, nodraw_faces = 0, sky_faces = 0;
  uint64_t polygon_triangles = 0, mesh_triangles = 0, patch_triangles = 0, orphans = 0;
};

// The patch level asked for, the header's size, magic and version.
bool check_header(const ImportInput& in, std::string& error) {
  const int level = in.options.patch_level;
  if (level < 1 || level > kMaxPatchLevel) {
    error = "patch level " + std::to_string(level) + " is out of range (1 to " + std::to_string(kMaxPatchLevel) + ")";
    return false;
  }
  if (in.size < kHeaderSize) {
    error = "truncated: " + std::to_string(in.size) + " bytes, shorter than the " + std::to_string(kHeaderSize) +
            "-byte BSP header";
    return false;
  }
  if (std::memcmp(in.data, "IBSP", 4) != 0) {
    error = "not a Quake 3 BSP file (no 'IBSP' magic)";
    return false;
  }
  if (i32(in.data + 4) != 46) {
    error = "BSP version " + std::to_string(i32(in.data + 4)) + " is not supported (expected 46, Quake 3)";
    return false;
  }
  return true;
}

// Every face read and checked, counted by type and shader flag.
bool read_faces(BspMap& map, std::string& error) {
  const Lump* lumps = map.lumps;
  map.texture_flags.resize(lumps[kTextures].count);
  for (size_t t = 0; t < map.texture_flags.size(); ++t)
    map.texture_flags[t] = i32(lumps[kTextures].data + kTextureSize * t + 64);
  map.faces.resize(lumps[kFaces].count);
  for (size_t f = 0; f < map.faces.size(); ++f) {
    const unsigned char* p = lumps[kFaces].data + kFaceSize * f;
    Face& face = map.faces[f];
    face = {i32(p), i32(p + 8), i32(p + 12), i32(p + 16), i32(p + 20), i32(p + 24), i32(p + 96), i32(p + 100)};
    if (!check_face(f, face, lumps, error)) return false;
    map.polygon_faces += face.type == kPolygon, map.patch_faces += face.type == kPatch;
    map.mesh_faces += face.type == kMesh, map.billboard_faces += face.type == kBillboard;
    map.nodraw_faces += (map.texture_flags[size_t(face.texture)] & kSurfNoDraw) != 0;
    map.sky_faces += (map.texture_flags[size_t(face.texture)] & kSurfSky) != 0;
  }
  return true;
}

// Models: face ranges in bounds, each face in at most one model.
bool read_models(BspMap& map, std::string& error) {
  const size_t model_count = map.lumps[kModels].count;
  if (model_count == 0) {
    error = "the models lump is empty (a map has at least the world model)";
    return false;
  }
  map.face_model.assign(map.faces.size(), TriangleSource::kNone);
  for (size_t m = 0; m < model_count; ++m) {
    const unsigned char* p = map.lumps[kModels].data + kModelSize * m;
    const int32_t first = i32(p + 24), count = i32(p + 28);
    if (first < 0 || count < 0 || uint64_t(first) + uint64_t(count) > map.faces.size()) {
      error = "model " + std::to_string(m) + " uses faces " + std::to_string(first) + " to " +
              std::to_string(int64_t(first) + count) + ", out of range (" + std::to_string(map.faces.size()) +
              " faces)";
      return false;
    }
    for (size_t f = size_t(first); f < size_t(first) + size_t(count); ++f) {
      if (map.face_model[f] != TriangleSource::kNone) {
        error = "face " + std::to_string(f) + " belongs to both model " + std::to_string(map.face_model[f]) +
                " and model " + std::to_string(m);
        return false;
      }
      map.face_model[f] = uint32_t(m);
    }
  }
  return true;
}

// Whether face f gives triangles: in a model, not a billboard, its shader drawn.
bool emitted(const BspMap& map, size_t f) {
  const Face& face = map.faces[f];
  return map.face_model[f] != TriangleSource::kNone && face.type != kBillboard &&
         !(map.texture_flags[size_t(face.texture)] & kSurfNoDraw);
}

// The triangle total, before any allocation that depends on it; refused over the cap.
bool count_triangles(const ImportInput& in, BspMap& map, uint64_t& total, std::string& error) {
  const int level = in.options.patch_level;
  for (size_t f = 0; f < map.faces.size(); ++f) {
    map.orphans += map.face_model[f] == TriangleSource::kNone;
    if (!emitted(map, f)) continue;
    const Face& face = map.faces[f];
    if (face.type == kPolygon)
      map.polygon_triangles += uint64_t(face.meshvert_count) / 3;
    else if (face.type == kMesh)
      map.mesh_triangles += uint64_t(face.meshvert_count) / 3;
    else
      map.patch_triangles += patch_triangle_count(face.width, face.height, level);
  }
  total = map.polygon_triangles + map.mesh_triangles + map.patch_triangles;
  const uint64_t cap = in.options.max_triangles ? in.options.max_triangles : kDefaultTriangleCap;
  if (total > cap) {
    error = "would produce " + std::to_string(total) + " triangles (" + std::to_string(map.patch_triangles) +
            " from patches at level " + std::to_string(level) + "), over the limit of " + std::to_string(cap);
    return false;
  }
  return true;
}

// A patch face: its control points checked and tessellated at `level`.
bool emit_patch(const BspMap& map, size_t f, int level, const TriangleSource& source, std::vector<float>& control,
                Scene& out, std::string& error) {
  const Face& face = map.faces[f];
  control.resize(size_t(face.vertex_count) * 3);
  for (size_t k = 0; k < size_t(face.vertex_count); ++k) {
    if (!finite3(vertex_position(map.lumps, size_t(face.vertex) + k, &control[3 * k]))) {
      error = face_name(f, face) + " control point " + std::to_string(k) + " has a non-finite coordinate";
      return false;
    }
  }
  const size_t base = out.vertex_count();
  if (base + patch_columns(face.width, level) * patch_rows(face.height, level) > 0xffffffffu) {
    error = "more than 2^32 vertices";
    return false;
  }
  tessellate_patch(control.data(), 3, face.width, face.height, level, out.positions);
  const size_t before = out.indices.size();
  patch_grid_triangles(uint32_t(patch_columns(face.width, level)), uint32_t(patch_rows(face.height, level)),
                       uint32_t(base), out.indices);
  out.sources.insert(out.sources.end(), (out.indices.size() - before) / 3, source);
  return true;
}

// A polygon or mesh face: its mesh-vertex triangles, each map vertex stored
// once (`remap`), the winding turned from the file's clockwise.
bool emit_mesh_face(const BspMap& map, size_t f, const TriangleSource& source, std::vector<uint32_t>& remap, Scene& out,
                    std::string& error) {
  const Face& face = map.faces[f];
  for (int32_t k = 0; k < face.meshvert_count; k += 3) {
    uint32_t tri[3];
    for (int j = 0; j < 3; ++j) {
      const size_t v =
          size_t(face.vertex) + size_t(i32(map.lumps[kMeshVerts].data + 4 * (size_t(face.meshvert) + k + j)));
      if (remap[v] == TriangleSource::kNone) {
        float p[3];
        if (!finite3(vertex_position(map.lumps, v, p))) {
          error = face_name(f, face) + " uses vertex " + std::to_string(v) + " with a non-finite coordinate";
          return false;
        }
        remap[v] = uint32_t(out.vertex_count());
        out.positions.insert(out.positions.end(), p, p + 3);
      }
      tri[j] = remap[v];
    }
    out.indices.insert(out.indices.end(), {tri[0], tri[2], tri[1]});  // clockwise in the file
    out.sources.push_back(source);
  }
  return true;
}

// Emit, model by model, face by face.
bool emit_models(const ImportInput& in, const BspMap& map, uint64_t total, Scene& out, std::string& error) {
  const uint32_t file = 0;
  const int level = in.options.patch_level;
  std::vector<uint32_t> remap(map.lumps[kVertexes].count, TriangleSource::kNone);
  out.indices.reserve(size_t(total) * 3);
  out.sources.reserve(size_t(total));
  std::vector<float> control;
  for (size_t m = 0; m < map.lumps[kModels].count; ++m) {
    const unsigned char* mp = map.lumps[kModels].data + kModelSize * m;
    const size_t first = size_t(i32(mp + 24)), count = size_t(i32(mp + 28));
    for (size_t f = first; f < first + count; ++f) {
      if (!emitted(map, f)) continue;
      const TriangleSource source{file, uint32_t(m), uint32_t(f), TriangleSource::kNone};
      const bool ok = map.faces[f].type == kPatch ? emit_patch(map, f, level, source, control, out, error)
                                                  : emit_mesh_face(map, f, source, remap, out, error);
      if (!ok) return false;
    }
  }
  return true;
}

}  // namespace

bool import_bsp(const ImportInput& in, Scene& out, std::string& error) {
  if (!check_header(in, error)) return false;
  BspMap map;
  uint64_t total = 0;
  if (!read_lumps(in, map.lumps, error) || !read_faces(map, error) || !read_models(map, error) ||
      !count_triangles(in, map, total, error) || !emit_models(in, map, total, out, error))
    return false;
  out.source_counts = {{"polygon.faces", map.polygon_faces},
                       {"polygon.triangles", map.polygon_triangles},
                       {"mesh.faces", map.mesh_faces},
                       {"mesh.triangles", map.mesh_triangles},
                       {"patch.faces", map.patch_faces},
                       {"patch.triangles", map.patch_triangles},
                       {"billboard.faces", map.billboard_faces},
                       {"nodraw.faces", map.nodraw_faces},
                       {"sky.faces", map.sky_faces}};
  if (map.billboard_faces)
    out.warnings.push_back(in.name + ": " + std::to_string(map.billboard_faces) + " billboard faces skipped");
  if (map.nodraw_faces)
    out.warnings.push_back(in.name + ": " + std::to_string(map.nodraw_faces) +
                           " faces with a never-drawn shader (SURF_NODRAW) skipped");
  if (map.orphans)
    out.warnings.push_back(in.name + ": " + std::to_string(map.orphans) + " faces belong to no model, skipped");
  return true;
}

}  // namespace geom::detail
