// The bake (geom/bake.h): Scene -> the pipeline (geom/pipeline.h) -> sections.
// This file only chooses, converts and lays out.
#include "geom/bake.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>
#include <new>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "geom/adjacency.h"
#include "json_write.h"

namespace geom {
namespace {

using baked::Format;
using baked::SectionType;

// Per triangle of [t0, t1), its stored plane in input coordinates, d = d_local - n . origin
// ((0, 0, 0, 0) for none), 4 floats each at `out`.
void world_face_planes(const FacePlanes& fp, size_t t0, size_t t1, float* out) {
  for (size_t t = t0; t < t1; ++t, out += 4) {
    uint32_t i = fp.face_plane[t];
    if (i == FacePlanes::kNone) {
      out[0] = out[1] = out[2] = out[3] = 0.0f;
      continue;
    }
    const float* p = &fp.planes[4 * size_t(i)];
    double d = double(p[3]) - (double(p[0]) * fp.origin[0] + double(p[1]) * fp.origin[1] + double(p[2]) * fp.origin[2]);
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
    out[3] = float(d);
  }
}

std::vector<float> world_face_planes(const FacePlanes& fp) {
  std::vector<float> out(fp.face_plane.size() * 4);
  world_face_planes(fp, 0, fp.face_plane.size(), out.data());
  return out;
}

// The face planes section written to `out` in pieces (no whole buffer); `meta` gets its description.
bool put_face_planes(BakedFileWriter& out, const FacePlanes& fp, BakedSection& meta) {
  constexpr size_t kPiece = 1 << 16;  // triangles
  const size_t n = fp.face_plane.size();
  meta.type = SectionType::FacePlanes;
  meta.format = Format::F32x4;
  meta.stride = 16;
  meta.name = "face_planes";
  meta.count = n;
  if (!out.begin(meta, uint64_t(n) * 16)) return false;
  std::vector<float> piece(4 * std::min(n, kPiece));
  for (size_t t0 = 0; t0 < n; t0 += kPiece) {
    const size_t t1 = std::min(n, t0 + kPiece);
    world_face_planes(fp, t0, t1, piece.data());
    if (!out.write(piece.data(), (t1 - t0) * 16)) return false;
  }
  return out.end();
}

template <class T>
void free_vector(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

// A section that views `values` (no copy) inside the stage result `keep` holds.
template <class T>
BakedSection view_section(SectionType type, Format format, uint32_t stride, const char* name,
                          const std::vector<T>& values, std::shared_ptr<const void> keep, uint32_t item = 0) {
  BakedSection s;
  s.type = type;
  s.format = format;
  s.stride = stride;
  s.item = item;
  s.name = name;
  s.view = reinterpret_cast<const unsigned char*>(values.data());
  s.view_size = values.size() * sizeof(T);
  s.count = s.view_size / stride;
  if (s.view) s.keep = std::move(keep);
  return s;
}

template <class Record>
BakedSection record_section(SectionType type, const char* name, const std::vector<Record>& records,
                            std::shared_ptr<const void> keep, uint32_t item = 0) {
  return view_section(type, Format::Record, uint32_t(sizeof(Record)), name, records, std::move(keep), item);
}

struct WriteFailed {};

// A section of records that a stage streams as it makes them (its options'
// *_out): begun with the first piece, or empty at close(), which ends it and
// returns its description (no bytes).
class RecordStream {
 public:
  RecordStream(BakedFileWriter* out, SectionType type, const char* name, uint32_t stride) : out_(out) {
    meta_.type = type, meta_.format = Format::Record, meta_.stride = stride, meta_.name = name;
  }
  void write(const void* records, size_t n) {
    begin();
    if (!out_->write(records, n * meta_.stride)) throw WriteFailed();
    meta_.count += n;
  }
  BakedSection close() {
    if (!closed_) {
      begin();
      if (!out_->end()) throw WriteFailed();
      closed_ = true;
      meta_.view_size = size_t(meta_.count * meta_.stride);
    }
    return meta_;
  }

 private:
  void begin() {
    if (begun_) return;
    if (!out_->begin_records(meta_)) throw WriteFailed();
    begun_ = true;
  }
  BakedFileWriter* out_;
  BakedSection meta_;
  bool begun_ = false, closed_ = false;
};

std::string esm_json(const EsmStats& s) {
  return "{\"edges\":" + json::count(s.edges) + ",\"candidate_edges\":" + json::count(s.candidate_edges) +
         ",\"emitted_edges\":" + json::count(s.emitted_edges) +
         ",\"skipped_coplanar\":" + json::count(s.skipped_coplanar) +
         ",\"skipped_concave\":" + json::count(s.skipped_concave) + ",\"quads\":" + json::count(s.quads) +
         ",\"bevel_edges\":" + json::count(s.bevel_edges) + ",\"bytes\":" + json::count(s.bytes) +
         ",\"naive_bytes\":" + json::count(s.naive_bytes) + "}";
}

std::string volume_json(const ShadowVolumeStats& s) {
  return "{\"edges\":" + json::count(s.edges) + ",\"pair_edges\":" + json::count(s.pair_edges) +
         ",\"single_records\":" + json::count(s.single_records) +
         ",\"skipped_coplanar\":" + json::count(s.skipped_coplanar) +
         ",\"one_sided_faces\":" + json::count(s.one_sided_faces) +
         ",\"double_sided_faces\":" + json::count(s.double_sided_faces) +
         ",\"degenerate_faces\":" + json::count(s.degenerate_faces) + ",\"sides\":" + json::count(s.sides) +
         ",\"caps\":" + json::count(s.caps) + ",\"bytes\":" + json::count(s.bytes) +
         ",\"naive_sides\":" + json::count(s.naive_sides) + ",\"naive_bytes\":" + json::count(s.naive_bytes) + "}";
}

bool finite4(const double v[4]) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

}  // namespace

bool keep_memory_across_bakes() {
#if defined(__GLIBC__)
  // No mmap'd chunks (they are unmapped on free; glibc caps the mmap threshold
  // at 32 MiB, below a large mesh's buffers), no trimming of the heap's top,
  // and one arena for every thread: a worker thread's own arena lives in 64 MiB
  // heaps, so its large buffers were mmap'd anyway (whatever M_MMAP_MAX) and
  // unmapped on free, and emptied heaps were deleted: a bake on a worker
  // faulted in 85,000 fresh pages where the main heap needs 63,000 (the
  // dragon-sized mesh). Small allocations stay in each thread's cache.
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1 && mallopt(M_ARENA_MAX, 1) == 1;
#else
  return false;
#endif
}

namespace {

// `release` (may be null): the scene's triangles, freed once welded. `out`
// (may be null): each section written to it as soon as its stage has run, and
// its buffer freed; the result's sections then describe them without bytes.
BakeResult bake(const Scene& scene, Scene* release, const std::string& name, const BakeOptions& options,
                BakedFileWriter* out) {
  BakeResult r;
  try {
    // The static lights: the scene's, then the caller's; as the lights section holds them.
    std::vector<Light> lights;
    if (options.scene_lights) lights = scene.lights;
    for (size_t i = 0; i < options.lights.size(); ++i) {
      lights.push_back(options.lights[i]);
      if (lights.back().name.empty()) lights.back().name = "--light " + std::to_string(i + 1);
    }
    std::vector<double> table(4 * lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
      double* h = &table[4 * i];
      light_homogeneous(lights[i], h);
      if (!finite4(h) || (h[0] == 0 && h[1] == 0 && h[2] == 0 && h[3] == 0)) {
        r.error = name + ": light '" + lights[i].name + "' is not a usable (x, y, z, w): non-finite or all zero";
        return r;
      }
    }

    const PipelineOptions& asked = options.pipeline;
    PipelineOptions po = asked;
    po.halfedge = true;  // the report's
    po.release_early = true;
    po.timing = false;
    if (out) {
      // Streamed, the adjacency is built after the volume, when the volume's
      // buffers are written and freed, from the edge table the volume read
      // last; this bake frees each stage's tables itself as the pipeline
      // would (release_early), the per-face edges kept for the adjacency.
      po.adjacency = false;
      po.release_early = false;
    }
    const bool more = asked.esm || asked.volume || asked.adjacency || !lights.empty();  // past the topology
    const bool framed = asked.esm || asked.volume || !lights.empty();                   // buffers in the local frame
    if (out) {
      const size_t n = size_t(options.positions) + options.indices + options.weld_remap + asked.face_planes +
                       options.topology_report +
                       (more ? size_t(framed) + 2 * asked.esm + 3 * asked.volume + asked.adjacency + !lights.empty() +
                                   3 * lights.size() + 1
                             : 0);
      if (!out->expect(n)) throw WriteFailed();
    }
    // Streamed, the ESM quads and (without lights: no light volume reads the
    // generic one) the volume's side records and caps go to the file as their
    // stage makes them, a piece at a time: they are most of the file, and
    // were the bake's peak.
    const bool stream_esm = out && asked.esm, stream_volume = out && asked.volume && lights.empty();
    RecordStream quads(out, SectionType::EsmQuads, "esm_quads", sizeof(EsmQuad));
    RecordStream sides(out, SectionType::VolumeSides, "volume_sides", sizeof(SvSide));
    RecordStream caps(out, SectionType::VolumeCaps, "volume_caps", sizeof(SvCap));
    if (stream_esm) po.esm_options.quads_out = [&](const EsmQuad* p, size_t n) { quads.write(p, n); };
    // The volume's component ids are read by the light volumes only: none here.
    if (lights.empty()) po.volume_options.component_ids = false;
    if (stream_volume) {
      po.volume_options.sides_out = [&](const SvSide* p, size_t n) { sides.write(p, n); };
      po.volume_options.caps_out = [&](const SvCap* p, size_t n) {
        sides.close();
        caps.write(p, n);
      };
    }
    // Sections view the buffers (no copy) inside the run `kept` holds; with
    // `out` they are written (and their buffers freed) as they are made.
    const auto kept = std::make_shared<Pipeline>();
    auto& s = r.sections;
    const auto emit = [&](BakedSection&& x) {
      if (out) {
        if (!out->put(x)) throw WriteFailed();
        x.view_size = x.size();
        x.view = nullptr, x.keep.reset(), free_vector(x.bytes);
      }
      s.push_back(std::move(x));
    };
    // The sections in file order, in groups; each group is emitted once the
    // stages it needs have run (without `out`: after the whole run).
    std::vector<std::string> ran;
    int next = 0;
    std::string js = "{";
    const auto flush = [&](Pipeline& p, bool all) {
      const auto has = [&](const char* stage) { return all || std::find(ran.begin(), ran.end(), stage) != ran.end(); };
      const WeldResult& w = p.weld;
      for (;; ++next) switch (next) {
          case 0:
            if (!has("weld")) return;
            if (options.positions)
              emit(view_section(SectionType::Positions, Format::F32x3, 12, "positions", w.positions, kept));
            if (options.indices) emit(view_section(SectionType::Indices, Format::U32, 4, "indices", w.indices, kept));
            if (options.weld_remap)
              emit(view_section(SectionType::WeldRemap, Format::U32, 4, "weld_remap", w.remap, kept));
            if (out) free_vector(p.weld.remap);  // no stage reads it
            break;
          case 1:
            if (!has("halfedge") || ((asked.face_planes || framed) && !has("planes"))) return;
            if (asked.face_planes) {
              if (out) {
                BakedSection meta;
                if (!put_face_planes(*out, p.planes, meta)) throw WriteFailed();
                s.push_back(std::move(meta));
              } else {
                emit(make_baked_section(SectionType::FacePlanes, Format::F32x4, 16, "face_planes",
                                        world_face_planes(p.planes)));
              }
            }
            if (!out) {  // no later section reads them (with `out` the volume still does)
              free_vector(p.planes.planes);
              free_vector(p.planes.face_plane);
            }
            if (out) free_vector(p.topology.face_component), free_vector(p.topology.face_flags);  // no stage reads them
            report_of(scene, p, r.report);
            r.report.file = name;
            if (options.topology_report) {
              std::string json = report_json(r.report);
              emit(make_baked_section(SectionType::TopologyReport, Format::Utf8, 1, "topology",
                                      std::vector<char>(json.begin(), json.end())));
            }
            if (!more) {
              next = 99;
              return;
            }
            if (framed) {
              std::vector<double> origin(p.planes.origin, p.planes.origin + 3);
              emit(make_baked_section(SectionType::Frame, Format::F64x3, 24, "frame", origin));
              js += "\"frame\":[" + json::number(origin[0]) + "," + json::number(origin[1]) + "," +
                    json::number(origin[2]) + "],";
            }
            break;
          case 2:
            if (out && (!asked.esm || has("esm"))) free_vector(p.planes.normals);  // only the ESM quads read them
            if (!asked.esm) break;
            if (!has("esm")) return;
            if (stream_esm)
              s.push_back(quads.close());
            else
              emit(record_section(SectionType::EsmQuads, "esm_quads", p.esm.quads, kept));
            emit(view_section(SectionType::EsmPlanes, Format::F32x4, 16, "esm_planes", p.esm.planes, kept));
            js += "\"esm\":" + esm_json(p.esm.stats) + ",";
            r.esm = p.esm.stats;
            if (out) free_vector(p.esm.quads), free_vector(p.esm.planes);
            break;
          case 3:
            if (asked.volume || !lights.empty()) {
              if (!has("volume")) return;
              if (out) free_vector(p.planes.planes), free_vector(p.planes.face_plane);  // read by the volume last
            }
            if (!asked.volume) break;
            if (stream_volume) {  // written as they came: the sections end here
              s.push_back(sides.close());
              s.push_back(caps.close());
            } else {
              emit(record_section(SectionType::VolumeSides, "volume_sides", p.volume.sides, kept));
              emit(record_section(SectionType::VolumeCaps, "volume_caps", p.volume.caps, kept));
            }
            emit(view_section(SectionType::VolumePlanes, Format::F32x4, 16, "volume_planes", p.volume.planes, kept));
            js += "\"volume\":" + volume_json(p.volume.stats) + ",";
            r.volume = p.volume.stats;
            if (out && lights.empty()) p.volume = ShadowVolume();  // else the light volumes' source
            break;
          case 4:
            if (out) {  // every stage that reads the edge table has run
              if (asked.adjacency) {
                p.adjacency.resize(adjacency_index_count(p.weld.indices.size() / 3));
                build_adjacency(p.adjacency.data(), p.weld.indices.data(), p.weld.indices.size() / 3, p.topology);
              }
              free_vector(p.topology.face_edges), free_vector(p.topology.edges), free_vector(p.topology.edge_faces);
            }
            if (!asked.adjacency) break;
            if (!out && !has("adjacency")) return;
            js += "\"adjacency\":{\"indices\":" + json::count(p.adjacency.size()) + "},";
            emit(view_section(SectionType::AdjacencyIndices, Format::U32, 4, "adjacency", p.adjacency, kept));
            if (out) free_vector(p.adjacency);
            break;
          case 5:
            if (!lights.empty()) emit(make_baked_section(SectionType::Lights, Format::F64x4, 32, "lights", table));
            break;
          case 6:
            if (!lights.empty() && !has("lights")) return;
            if (!asked.volume) p.volume = ShadowVolume();  // the light volumes' source, emitted by none
            js += "\"lights\":[";
            for (size_t i = 0; i < p.lights.size(); ++i) {
              ShadowVolume& lv = p.lights[i].volume;
              const uint32_t item = uint32_t(i);
              const double* h = &table[4 * i];
              emit(record_section(SectionType::LightSides, "light_sides", lv.sides, kept, item));
              emit(record_section(SectionType::LightCaps, "light_caps", lv.caps, kept, item));
              emit(view_section(SectionType::LightPlanes, Format::F32x4, 16, "light_planes", lv.planes, kept, item));
              js += std::string(i ? "," : "") + "{\"name\":" + json::quote(lights[i].name) + ",\"light\":[" +
                    json::number(h[0]) + "," + json::number(h[1]) + "," + json::number(h[2]) + "," +
                    json::number(h[3]) + "],\"sides\":" + json::count(lv.sides.size()) +
                    ",\"caps\":" + json::count(lv.caps.size()) + ",\"bytes\":" + json::count(lv.stats.bytes) + "}";
              if (out) lv.sides = {}, lv.caps = {}, free_vector(lv.planes);
            }
            js += "]}";
            if (out) p.volume = ShadowVolume();
            break;
          case 7:
            if (!all) return;
            r.silhouette = js;
            emit(make_baked_section(SectionType::SilhouetteReport, Format::Utf8, 1, "silhouette",
                                    std::vector<char>(js.begin(), js.end())));
            break;
          default:
            return;
        }
    };
    const auto after_stage = [&](const char* stage, Pipeline& p) {
      if (release && std::string(stage) == "weld") {
        free_vector(release->positions);
        free_vector(release->indices);
        free_vector(release->sources);
      }
      ran.push_back(stage);
      if (out) flush(p, false);
    };
    *kept = run_pipeline(positions_of(scene.positions.data(), scene.vertex_count()), scene.indices.data(),
                         scene.triangle_count(), lights, po, after_stage);
    flush(*kept, true);
  } catch (const WriteFailed&) {
    r = BakeResult();
    r.error = name + ": cannot write the output: " + out->error();
    return r;
  } catch (const std::bad_alloc&) {
    r = BakeResult();
    r.error = name + ": out of memory while baking";
    return r;
  } catch (const std::exception& e) {
    r = BakeResult();
    r.error = name + ": " + e.what();
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace

BakeResult bake_scene(const Scene& scene, const std::string& name, const BakeOptions& options) {
  return bake(scene, nullptr, name, options, nullptr);
}

BakeResult bake_scene(Scene&& scene, const std::string& name, const BakeOptions& options) {
  return bake(scene, &scene, name, options, nullptr);
}

BakeResult bake_scene(Scene&& scene, const std::string& name, const BakeOptions& options, BakedFileWriter& out) {
  return bake(scene, &scene, name, options, &out);
}

BakeResult bake_file(const std::string& input, const std::string& output, const BakeOptions& options,
                     const ImportOptions& import_options) {
  ImportResult imported = import_file(input, import_options);
  if (!imported.ok) {
    BakeResult r;
    r.error = imported.error;
    return r;
  }
  BakeResult r = bake_scene(std::move(imported.scene), input, options);
  imported = ImportResult();
  if (!r.ok) return r;
  std::string error;
  if (!write_baked(output, r.sections, error)) {
    r.ok = false;
    r.error = input + ": cannot write " + output + ": " + error;
  }
  return r;
}

}  // namespace geom
