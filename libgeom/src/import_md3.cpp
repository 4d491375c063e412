// Quake 3 MD3 model import (IDP3 version 15, as in Debian's openarena-081-players).
//
// Arneson n.d. (Real-Time Shadows), Sect. 2.5: a model is several triangle
// surfaces, each stored once per animation frame. Imported: every surface at
// frame ImportOptions::md3_frame (default 0, the first), vertex positions
// int16 times the format's fixed-point scale 1/64 (MD3_XYZ_SCALE), in model
// units, Z up as in the file. Tags (attachment points), normals, texture
// coordinates and skins are ignored.
//
// Layout: a 108-byte header (ident, version, name[64], flags, frame, tag,
// surface and skin counts, frame/tag/surface/end offsets); surfaces chained
// from the header's surface offset, each with its own 108-byte header whose
// offsets are relative to the surface start: triangles (3 x int32), vertices
// (frames x vertices x {int16 x, y, z, packed normal}), and the next surface
// at the end offset.
//
// Output: triangles reversed to counter-clockwise-front (MD3 stores them
// clockwise, like BSP files: the closed surfaces of OpenArena's players have
// negative signed volume as stored); TriangleSource::mesh = surface index.
// Every offset, count and index is checked against the bytes before use.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "file_read.h"
#include "importers.h"

namespace geom::detail {
namespace {

constexpr size_t kHeaderSize = 108, kSurfaceHeaderSize = 108, kVertexSize = 8;
constexpr float kXyzScale = 1.0f / 64.0f;

int32_t i32(const unsigned char* p) {
  uint32_t u = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  int32_t v;
  std::memcpy(&v, &u, 4);
  return v;
}
int16_t i16(const unsigned char* p) {
  uint16_t u = uint16_t(p[0] | p[1] << 8);
  int16_t v;
  std::memcpy(&v, &u, 2);
  return v;
}

// [offset, offset + count * record) inside [0, limit)?
bool span_inside(int64_t offset, int64_t count, uint64_t record, uint64_t limit) {
  if (offset < 0 || count < 0 || uint64_t(offset) > limit) return false;
  return uint64_t(count) <= (limit - uint64_t(offset)) / record;
}

// The model's header: magic, version, the frame asked for, the surfaces' span.
bool read_header(const ImportInput& in, int32_t& frames, int32_t& surfaces, int32_t& surface_offset,
                 std::string& error) {
  if (in.size < kHeaderSize) {
    error = "truncated: " + std::to_string(in.size) + " bytes, shorter than the 108-byte MD3 header";
    return false;
  }
  if (std::memcmp(in.data, "IDP3", 4) != 0) {
    error = "not an MD3 model (no 'IDP3' magic)";
    return false;
  }
  if (i32(in.data + 4) != 15) {
    error = "MD3 version " + std::to_string(i32(in.data + 4)) + " is not supported (expected 15)";
    return false;
  }
  frames = i32(in.data + 76), surfaces = i32(in.data + 84), surface_offset = i32(in.data + 100);
  const int frame = in.options.md3_frame;
  if (frames <= 0) {
    error = "the model has " + std::to_string(frames) + " frames";
    return false;
  }
  if (frame < 0 || frame >= frames) {
    error = "frame " + std::to_string(frame) + " requested, the model has " + std::to_string(frames) + " (0 to " +
            std::to_string(frames - 1) + ")";
    return false;
  }
  if (surfaces < 0 || !span_inside(surface_offset, surfaces, kSurfaceHeaderSize, in.size)) {
    error = std::to_string(surfaces) + " surfaces at offset " + std::to_string(surface_offset) +
            " do not fit in the file (" + std::to_string(in.size) + " bytes)";
    return false;
  }
  return true;
}

// What the surfaces claim, before anything is allocated: surfaces may share
// their triangle bytes, so a small file can claim millions. Refused over the
// triangle limit or the memory limit; the claimed triangles are reserved.
bool check_claims(const ImportInput& in, int32_t surfaces, int32_t surface_offset, Scene& out, std::string& error) {
  uint64_t claimed_triangles = 0, claimed_vertices = 0;
  for (uint64_t at = uint64_t(surface_offset), s = 0; s < uint64_t(surfaces); ++s) {
    if (!span_inside(int64_t(at), 1, kSurfaceHeaderSize, in.size)) break;  // refused below
    const int32_t vertices = i32(in.data + at + 80), triangles = i32(in.data + at + 84);
    const int32_t tri_offset = i32(in.data + at + 88), end_offset = i32(in.data + at + 104);
    if (!span_inside(tri_offset, triangles, 12, in.size - at)) break;  // refused below, with its own message
    claimed_triangles += uint64_t(std::max(triangles, 0));
    claimed_vertices += uint64_t(std::max(vertices, 0));
    if (end_offset < int32_t(kSurfaceHeaderSize)) break;
    at += uint64_t(end_offset);
  }
  if (in.options.max_triangles && claimed_triangles > in.options.max_triangles) {
    error = "the surfaces claim " + std::to_string(claimed_triangles) + " triangles, over the limit of " +
            std::to_string(in.options.max_triangles);
    return false;
  }
  const uint64_t claimed_bytes =
      claimed_triangles * (3 * sizeof(uint32_t) + sizeof(TriangleSource)) + claimed_vertices * 3 * sizeof(float);
  const uint64_t memory = in.options.max_bytes ? in.options.max_bytes : physical_memory_bytes();
  if (memory && claimed_bytes > memory) {
    error = "the surfaces claim " + std::to_string(claimed_triangles) + " triangles and " +
            std::to_string(claimed_vertices) + " vertices (" + std::to_string(claimed_bytes) +
            " bytes), over the limit of " + std::to_string(memory);
    return false;
  }
  out.indices.reserve(out.indices.size() + 3 * size_t(claimed_triangles));
  out.sources.reserve(out.sources.size() + size_t(claimed_triangles));
  return true;
}

// Surface s at offset `at`: its triangles and the asked-for frame's vertices;
// `at` moves to the next surface.
bool read_surface(const ImportInput& in, int32_t s, int32_t frames, uint64_t& at, Scene& out, std::string& error) {
  const std::string name = "surface " + std::to_string(s);
  if (!span_inside(int64_t(at), 1, kSurfaceHeaderSize, in.size)) {
    error = name + " header at offset " + std::to_string(at) + " lies outside the file";
    return false;
  }
  const unsigned char* sp = in.data + at;
  const uint64_t room = in.size - at;  // bytes from the surface start to the end of the file
  if (std::memcmp(sp, "IDP3", 4) != 0) {
    error = name + " at offset " + std::to_string(at) + " has no 'IDP3' magic";
    return false;
  }
  const int32_t surface_frames = i32(sp + 72), vertices = i32(sp + 80), triangles = i32(sp + 84);
  const int32_t tri_offset = i32(sp + 88), xyz_offset = i32(sp + 100), end_offset = i32(sp + 104);
  if (surface_frames != frames) {
    error = name + " has " + std::to_string(surface_frames) + " frames, the model " + std::to_string(frames);
    return false;
  }
  if (!span_inside(tri_offset, triangles, 12, room)) {
    error = name + ": " + std::to_string(triangles) + " triangles at offset " + std::to_string(tri_offset) +
            " lie outside the file";
    return false;
  }
  if (vertices < 0 || !span_inside(xyz_offset, int64_t(frames) * vertices, kVertexSize, room)) {
    error = name + ": " + std::to_string(frames) + " frames of " + std::to_string(vertices) + " vertices at offset " +
            std::to_string(xyz_offset) + " lie outside the file";
    return false;
  }
  if (end_offset < int32_t(kSurfaceHeaderSize) || uint64_t(end_offset) > room) {
    error = name + " ends at offset " + std::to_string(end_offset) + " (relative), outside [108, " +
            std::to_string(room) + "]";
    return false;
  }
  const size_t base = out.vertex_count();
  if (base + size_t(vertices) > 0xffffffffu) {
    error = "more than 2^32 vertices";
    return false;
  }
  const unsigned char* tp = sp + tri_offset;
  for (int32_t t = 0; t < triangles; ++t) {
    int32_t v[3] = {i32(tp + 12 * size_t(t)), i32(tp + 12 * size_t(t) + 4), i32(tp + 12 * size_t(t) + 8)};
    for (int j = 0; j < 3; ++j) {
      if (v[j] < 0 || v[j] >= vertices) {
        error = name + " triangle " + std::to_string(t) + " uses vertex " + std::to_string(v[j]) + ", out of range (" +
                std::to_string(vertices) + " vertices)";
        return false;
      }
    }
    out.indices.insert(out.indices.end(),
                       {uint32_t(base + size_t(v[0])), uint32_t(base + size_t(v[2])), uint32_t(base + size_t(v[1]))});
    out.sources.push_back({0, uint32_t(s), TriangleSource::kNone, TriangleSource::kNone});
  }
  const unsigned char* vp = sp + xyz_offset + size_t(in.options.md3_frame) * size_t(vertices) * kVertexSize;
  out.positions.reserve(out.positions.size() + size_t(vertices) * 3);
  for (int32_t v = 0; v < vertices; ++v) {
    for (int k = 0; k < 3; ++k) out.positions.push_back(float(i16(vp + kVertexSize * size_t(v) + 2 * k)) * kXyzScale);
  }
  at += uint64_t(end_offset);
  return true;
}

}  // namespace

bool import_md3(const ImportInput& in, Scene& out, std::string& error) {
  int32_t frames = 0, surfaces = 0, surface_offset = 0;
  if (!read_header(in, frames, surfaces, surface_offset, error)) return false;
  if (!check_claims(in, surfaces, surface_offset, out, error)) return false;
  uint64_t at = uint64_t(surface_offset);
  for (int32_t s = 0; s < surfaces; ++s)
    if (!read_surface(in, s, frames, at, out, error)) return false;
  return true;
}

}  // namespace geom::detail
