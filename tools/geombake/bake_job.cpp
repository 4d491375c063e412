// One input of `geombake bake` (bake_job.h).
#include "geombake/bake_job.h"

#include <algorithm>
#include <cctype>
#include <chrono>

#include "geombake/bake_output.h"

namespace geombake {
namespace {

// What baking one triangle costs at the peak, beyond the imported scene: the
// weld, the topology's edge table, the planes, the ESM quads, the volume, the
// adjacency, their sections and the serialized file. Measured (peak RSS of
// `geombake bake -j 1` less the 12 MB of an empty run, over the triangles, the
// import included): 2CylinderEngine.glb (121,496 triangles) 550 B, OpenArena's
// oa_ctf2 (19,193) 370 B; rounded up with a margin. The process's own ~12 MB
// is not counted.
constexpr uint64_t kBakeBytesPerTriangle = 1024;
// And per triangle per exact light volume (--light, KHR_lights_punctual): at
// most a side quad per edge and two caps per triangle, 16-byte vertices, as a
// lower bound (the budget of fault.h counts the real allocations).
constexpr uint64_t kBakeBytesPerTrianglePerLight = 256;
// And per vertex when the bake stores the casters' hull (BakeOptions::caster_hull,
// on unless --no-caster-hull): the hull runs over its own copies of every
// welded position (in double, then as CGAL's points, 24 bytes each) and
// CGAL's working structures, beside the pipeline's buffers. Measured (peak RSS
// with the hull less without, 400,000 random vertices and 2 triangles): 78 B
// per vertex; rounded up. The scene's vertex count bounds the welded one.
constexpr uint64_t kHullBytesPerVertex = 96;

// `crc`: the section's CRC-32C as the writer computed it (never a second time);
// the section's bytes are gone (written as made), its count x stride is its size.
SectionInfo info_of(const geom::BakedSection& s, uint32_t crc) {
  return {s.name, s.type, s.format, s.stride, s.item, s.count, s.count * s.stride, crc};
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  if (from.empty() || from == to) return;
  for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
}

// The memory estimate (--max-memory): "" if the bake may fit, else the error.
std::string over_estimate(const Job& job, const geom::Scene& scene, const geom::BakeOptions& options,
                          uint64_t max_memory) {
  const uint64_t tris = scene.triangle_count();
  const uint64_t lights = options.lights.size() + (options.scene_lights ? scene.lights.size() : 0);
  const uint64_t hull_vertices = options.caster_hull ? scene.vertex_count() : 0;
  const uint64_t need = tris * kBakeBytesPerTriangle + lights * tris * kBakeBytesPerTrianglePerLight +
                        hull_vertices * kHullBytesPerVertex;
  if (need <= max_memory) return "";
  return job.input + ": baking " + std::to_string(tris) + " triangles" +
         (lights ? " with " + std::to_string(lights) + " exact light volumes" : std::string()) +
         (hull_vertices ? " and the hull of " + std::to_string(hull_vertices) + " vertices" : std::string()) +
         " needs about " + std::to_string(need) + " bytes, over the limit of " + std::to_string(max_memory) +
         " (--max-memory)";
}

// A plain mesh format (.obj .off .ply .stl), whose file without a face holds
// nothing at all; a glTF without a mesh may still be a valid scene (cameras,
// lights), and is baked to a container without geometry.
bool is_plain_mesh_name(const std::string& path) {
  std::string ext = path.substr(std::min(path.size(), path.find_last_of('.')));
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl";
}

Outcome fail(std::string error, ErrorKind kind) {
  Outcome o;
  o.error = std::move(error);
  o.kind = kind;
  return o;
}

// The write, once the bake is done: only if the watchdog has not given up on
// the job (kRunning -> kWriting) and the time limit still holds.
void finish_write(Job& job, geom::BakedFileWriter& writer, double timeout, Outcome& o) {
  int expected = kRunning;
  if (timeout > 0 && double(now_ns() - job.started_ns.load()) * 1e-9 > timeout) return;  // the caller times it out
  if (!job.state.compare_exchange_strong(expected, kWriting)) return;                    // given up on: write nothing
  std::vector<uint32_t> crcs;
  bool unchanged = false;
  if (writer.finish(unchanged, &crcs)) {
    o.written = unchanged ? Written::Unchanged : Written::New;
  } else {
    o.result.ok = false;
    o.error = job.input + ": cannot write " + job.output + ": " + writer.error();
    o.kind = ErrorKind::WriteFailed;
  }
  crcs.resize(o.result.sections.size(), 0);
  for (size_t i = 0; i < o.result.sections.size(); ++i) o.sections.push_back(info_of(o.result.sections[i], crcs[i]));
  std::vector<geom::BakedSection>().swap(o.result.sections);
}

Outcome bake_unguarded(Job& job, const geom::BakeOptions& options, const geom::ImportOptions& import_options,
                       const JobLimits& limits, const WriteOptions& write) {
  geom::ImportResult imported = geom::import_file(job.input, import_options);
  if (!imported.ok) return fail(imported.error, classify_import_error(job.input, imported.error));
  if (imported.scene.triangle_count() == 0 && is_plain_mesh_name(job.input))  // an OBJ as an empty OFF, PLY or STL
    return fail(job.input + ": no face: nothing to bake (the file holds no triangle)", ErrorKind::Malformed);
  if (limits.max_memory) {  // the estimate refuses at once what cannot fit; the budget (fault.h) bounds the rest
    std::string over = over_estimate(job, imported.scene, options, limits.max_memory);
    if (!over.empty()) return fail(over, ErrorKind::LimitMemory);
  }
  Outcome o;
  // The output holds the stored name, never the path as typed (hermetic bytes):
  // the importer's warnings are stored with it too, and shown with the path.
  o.warnings = imported.scene.warnings;
  for (std::string& w : imported.scene.warnings) replace_all(w, job.input, job.name);
  std::string error;
  if (write.make_parents && !make_parent_directories(job.output, error))
    return fail(job.input + ": cannot write " + job.output + ": " + error, ErrorKind::WriteFailed);
  // Each section goes to the output (a temporary file until finished) as soon
  // as it is made, its buffer freed: the bake's peak holds no finished section.
  geom::BakedFileWriter writer;
  writer.open(job.output, !write.force);  // an output there: compared as it comes, left untouched if the same
  o.result = geom::bake_scene(std::move(imported.scene), job.name, options, writer);  // its triangles freed once welded
  imported = geom::ImportResult();
  if (!o.result.ok) {
    o.error = o.result.error;
    o.kind = ErrorKind::Malformed;
    if (!writer.error().empty()) {
      o.error = job.input + ": cannot write " + job.output + ": " + writer.error();
      o.kind = ErrorKind::WriteFailed;
    } else if (o.error.rfind(job.name + ":", 0) == 0) {
      o.error = job.input + o.error.substr(job.name.size());
    }
    return o;
  }
  finish_write(job, writer, limits.timeout, o);
  return o;
}

}  // namespace

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

Outcome bake_one(Job& job, const geom::BakeOptions& options, const geom::ImportOptions& import_options,
                 const JobLimits& limits, const WriteOptions& write) {
  Outcome o;
  job.budget.limit = limits.max_memory;
  std::string error = guarded(job.input, job.budget, [&] {
    o = bake_unguarded(job, options, import_options, limits, write);
    return o.error;
  });
  if (!error.empty() && error != o.error) {
    o = Outcome();
    o.error = error;
    o.kind = job.budget.exceeded || error.find("out of memory") != std::string::npos ? ErrorKind::LimitMemory
                                                                                     : ErrorKind::Malformed;
  }
  return o;
}

}  // namespace geombake
