// The bake (geom/bake.h): Scene -> the pipeline (geom/pipeline.h) -> sections.
// This file only chooses, converts and lays out.
#include "geom/bake.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "geom/adjacency.h"
#include "json_write.h"

namespace geom {
namespace {

using baked::Format;
using baked::SectionType;

// A light as the light_params section holds it (geom/baked_records.h): the
// fields its type has, the others zero; its name at `name_offset` of light_names.
LightRecord light_record(const Light& l, uint32_t name_offset) {
  LightRecord r{};
  r.type = l.type == LightType::Directional ? LightRecord::kDirectional
           : l.type == LightType::Point     ? LightRecord::kPoint
                                            : LightRecord::kSpot;
  r.name_offset = name_offset;
  r.name_size = uint32_t(l.name.size());
  for (int k = 0; k < 3; ++k) {
    r.position[k] = l.type == LightType::Directional ? 0 : l.position[k];
    r.direction[k] = l.type == LightType::Point ? 0 : l.direction[k];
    r.color[k] = l.color[k];
  }
  r.range = l.type == LightType::Directional ? 0 : l.range;
  r.inner_cone_angle = l.type == LightType::Spot ? l.inner_cone : 0;
  r.outer_cone_angle = l.type == LightType::Spot ? l.outer_cone : 0;
  r.intensity = l.intensity;
  return r;
}

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

// The pipeline's stages, as run_pipeline names them (StageTiming::stage).
enum class Stage : unsigned { Weld, Topology, Halfedge, Planes, Adjacency, Esm, Volume, Lights, Count };

Stage stage_of(const char* name) {
  static const char* const kNames[] = {"weld",      "topology", "halfedge", "planes",
                                       "adjacency", "esm",      "volume",   "lights"};
  for (unsigned i = 0; i < unsigned(Stage::Count); ++i)
    if (std::strcmp(name, kNames[i]) == 0) return Stage(i);
  return Stage::Count;  // a stage no section waits for
}

// The sections in file order, in groups (geom/bake.h's table); each group is
// emitted once the stages it needs have run (without a writer: after the whole run).
enum class Group : unsigned { Mesh, Topology, Esm, Volume, Adjacency, LightTable, LightVolumes, Silhouette, Done };
// What a group says: wait for more stages, go on to the next group, or stop (no section follows).
enum class Step { Wait, Next, Stop };

// One bake. `release` (may be null): the scene's triangles, freed once welded.
// `out` (may be null): each section written to it as soon as its stage has
// run, and its buffer freed; the result's sections then describe them without bytes.
class Baker {
 public:
  Baker(const Scene& scene, Scene* release, const std::string& name, const BakeOptions& options, BakedFileWriter* out)
      : scene_(scene),
        release_(release),
        name_(name),
        options_(options),
        asked_(options.pipeline),
        out_(out),
        quads_(out, SectionType::EsmQuads, "esm_quads", sizeof(EsmQuad)),
        sides_(out, SectionType::VolumeSides, "volume_sides", sizeof(SvSide)),
        caps_(out, SectionType::VolumeCaps, "volume_caps", sizeof(SvCap)) {}

  BakeResult run() {
    try {
      if (!gather_lights()) return std::move(r_);
      const PipelineOptions po = pipeline_options();
      if (out_) expect_sections();
      // Sections view the buffers (no copy) inside the run `kept_` holds; with
      // `out_` they are written (and their buffers freed) as they are made.
      *kept_ = run_pipeline(positions_of(scene_.positions.data(), scene_.vertex_count()), scene_.indices.data(),
                            scene_.triangle_count(), lights_, po,
                            [this](const char* stage, Pipeline& p) { after_stage(stage, p); });
      flush(*kept_, true);
    } catch (const WriteFailed&) {
      return failure(ErrorCode::Io, "cannot write the output: " + out_->error());
    } catch (const std::bad_alloc&) {
      return failure(ErrorCode::OutOfMemory, "out of memory while baking");
    } catch (const std::exception& e) {
      return failure(ErrorCode::Malformed, e.what());
    }
    r_.ok = true;
    return std::move(r_);
  }

 private:
  BakeResult failure(ErrorCode code, const std::string& what) {
    BakeResult r;
    r.code = code;
    r.error = name_ + ": " + what;
    return r;
  }

  // The static lights: the scene's, then the caller's; as the lights section holds them.
  bool gather_lights() {
    if (options_.scene_lights) lights_ = scene_.lights;
    for (size_t i = 0; i < options_.lights.size(); ++i) {
      lights_.push_back(options_.lights[i]);
      if (lights_.back().name.empty()) lights_.back().name = "--light " + std::to_string(i + 1);
    }
    table_.assign(4 * lights_.size(), 0.0);
    for (size_t i = 0; i < lights_.size(); ++i) {
      double* h = &table_[4 * i];
      light_homogeneous(lights_[i], h);
      if (!finite4(h) || (h[0] == 0 && h[1] == 0 && h[2] == 0 && h[3] == 0)) {
        r_.code = ErrorCode::NonFinite;
        r_.error = name_ + ": light '" + lights_[i].name + "' is not a usable (x, y, z, w): non-finite or all zero";
        return false;
      }
    }
    return true;
  }

  PipelineOptions pipeline_options() {
    PipelineOptions po = asked_;
    po.halfedge = true;  // the report's
    po.release_early = true;
    po.timing = false;
    if (out_) {
      // Streamed, the adjacency is built after the volume, when the volume's
      // buffers are written and freed, from the edge table the volume read
      // last; this bake frees each stage's tables itself as the pipeline
      // would (release_early), the per-face edges kept for the adjacency.
      po.adjacency = false;
      po.release_early = false;
    }
    more_ = asked_.esm || asked_.volume || asked_.adjacency || !lights_.empty();  // past the topology
    framed_ = asked_.esm || asked_.volume || !lights_.empty();                    // buffers in the local frame
    // Streamed, the ESM quads and (without lights: no light volume reads the
    // generic one) the volume's side records and caps go to the file as their
    // stage makes them, a piece at a time: they are most of the file, and
    // held whole in memory they would be the bake's peak.
    stream_esm_ = out_ && asked_.esm;
    stream_volume_ = out_ && asked_.volume && lights_.empty();
    if (stream_esm_) po.esm_options.quads_out = [this](const EsmQuad* q, size_t n) { quads_.write(q, n); };
    // The volume's component ids are read by the light volumes only: none here.
    if (lights_.empty()) po.volume_options.component_ids = false;
    if (stream_volume_) {
      po.volume_options.sides_out = [this](const SvSide* q, size_t n) { sides_.write(q, n); };
      po.volume_options.caps_out = [this](const SvCap* q, size_t n) {
        sides_.close();
        caps_.write(q, n);
      };
    }
    return po;
  }

  void expect_sections() {
    const size_t n = size_t(options_.positions) + options_.indices + options_.weld_remap +
                     (options_.caster_hull != nullptr) + asked_.face_planes + options_.topology_report +
                     (more_ ? size_t(framed_) + 2 * asked_.esm + 3 * asked_.volume + asked_.adjacency +
                                  3 * !lights_.empty() + 3 * lights_.size() + 1
                            : 0);
    if (!out_->expect(n)) throw WriteFailed();
  }

  void after_stage(const char* name, Pipeline& p) {
    const Stage stage = stage_of(name);
    if (release_ && stage == Stage::Weld) {
      free_vector(release_->positions);
      free_vector(release_->indices);
      free_vector(release_->sources);
    }
    if (stage != Stage::Count) ran_[unsigned(stage)] = true;
    if (out_) flush(p, false);
  }

  bool has(Stage stage, bool all) const { return all || ran_[unsigned(stage)]; }

  void emit(BakedSection&& x) {
    if (out_) {
      if (!out_->put(x)) throw WriteFailed();
      x.view_size = x.size();
      x.view = nullptr, x.keep.reset(), free_vector(x.bytes);
    }
    r_.sections.push_back(std::move(x));
  }

  // Emits the groups whose stages have run (`all`: every stage has).
  void flush(Pipeline& p, bool all) {
    while (next_ != Group::Done) {
      const Step step = emit_group(next_, p, all);
      if (step == Step::Wait) return;
      next_ = step == Step::Stop ? Group::Done : Group(unsigned(next_) + 1);
    }
  }

  Step emit_group(Group group, Pipeline& p, bool all) {
    switch (group) {
      case Group::Mesh:
        return mesh(p, all);
      case Group::Topology:
        return topology(p, all);
      case Group::Esm:
        return esm(p, all);
      case Group::Volume:
        return volume(p, all);
      case Group::Adjacency:
        return adjacency(p, all);
      case Group::LightTable:
        return light_table();
      case Group::LightVolumes:
        return light_volumes(p, all);
      case Group::Silhouette:
        return silhouette(all);
      case Group::Done:
        break;
    }
    return Step::Stop;
  }

  // positions, indices, weld_remap.
  Step mesh(Pipeline& p, bool all) {
    if (!has(Stage::Weld, all)) return Step::Wait;
    const WeldResult& w = p.weld;
    if (options_.positions)
      emit(view_section(SectionType::Positions, Format::F32x3, 12, "positions", w.positions, kept_));
    if (options_.indices) emit(view_section(SectionType::Indices, Format::U32, 4, "indices", w.indices, kept_));
    if (options_.weld_remap) emit(view_section(SectionType::WeldRemap, Format::U32, 4, "weld_remap", w.remap, kept_));
    if (options_.caster_hull) {  // empty when the positions span no volume
      std::vector<double> planes;
      if (!options_.caster_hull(positions_of(w.positions.data(), w.positions.size() / 3), planes)) planes.clear();
      emit(make_baked_section(SectionType::CasterHull, Format::F64x4, 32, "caster_hull", planes));
    }
    if (out_) free_vector(p.weld.remap);  // no stage reads it
    return Step::Next;
  }

  // face_planes, topology, frame.
  Step topology(Pipeline& p, bool all) {
    if (!has(Stage::Halfedge, all) || ((asked_.face_planes || framed_) && !has(Stage::Planes, all))) return Step::Wait;
    if (asked_.face_planes) {
      if (out_) {
        BakedSection meta;
        if (!put_face_planes(*out_, p.planes, meta)) throw WriteFailed();
        r_.sections.push_back(std::move(meta));
      } else {
        emit(
            make_baked_section(SectionType::FacePlanes, Format::F32x4, 16, "face_planes", world_face_planes(p.planes)));
      }
    }
    if (!out_) {  // no later section reads them (with `out_` the volume still does)
      free_vector(p.planes.planes);
      free_vector(p.planes.face_plane);
    }
    if (out_) free_vector(p.topology.face_component), free_vector(p.topology.face_flags);  // no stage reads them
    report_of(scene_, p, r_.report);
    r_.report.file = name_;
    if (options_.topology_report) {
      const std::string json = report_json(r_.report);
      emit(make_baked_section(SectionType::TopologyReport, Format::Utf8, 1, "topology",
                              std::vector<char>(json.begin(), json.end())));
    }
    if (!more_) return Step::Stop;
    if (framed_) {
      std::vector<double> origin(p.planes.origin, p.planes.origin + 3);
      emit(make_baked_section(SectionType::Frame, Format::F64x3, 24, "frame", origin));
      js_ += "\"frame\":[" + json::number(origin[0]) + "," + json::number(origin[1]) + "," + json::number(origin[2]) +
             "],";
    }
    return Step::Next;
  }

  // esm_quads, esm_planes.
  Step esm(Pipeline& p, bool all) {
    if (out_ && (!asked_.esm || has(Stage::Esm, all))) free_vector(p.planes.normals);  // only the ESM quads read them
    if (!asked_.esm) return Step::Next;
    if (!has(Stage::Esm, all)) return Step::Wait;
    if (stream_esm_)
      r_.sections.push_back(quads_.close());
    else
      emit(record_section(SectionType::EsmQuads, "esm_quads", p.esm.quads, kept_));
    emit(view_section(SectionType::EsmPlanes, Format::F32x4, 16, "esm_planes", p.esm.planes, kept_));
    js_ += "\"esm\":" + esm_json(p.esm.stats) + ",";
    r_.esm = p.esm.stats;
    if (out_) free_vector(p.esm.quads), free_vector(p.esm.planes);
    return Step::Next;
  }

  // volume_sides, volume_caps, volume_planes.
  Step volume(Pipeline& p, bool all) {
    if (asked_.volume || !lights_.empty()) {
      if (!has(Stage::Volume, all)) return Step::Wait;
      if (out_) free_vector(p.planes.planes), free_vector(p.planes.face_plane);  // read by the volume last
    }
    if (!asked_.volume) return Step::Next;
    if (stream_volume_) {  // written as they came: the sections end here
      r_.sections.push_back(sides_.close());
      r_.sections.push_back(caps_.close());
    } else {
      emit(record_section(SectionType::VolumeSides, "volume_sides", p.volume.sides, kept_));
      emit(record_section(SectionType::VolumeCaps, "volume_caps", p.volume.caps, kept_));
    }
    emit(view_section(SectionType::VolumePlanes, Format::F32x4, 16, "volume_planes", p.volume.planes, kept_));
    js_ += "\"volume\":" + volume_json(p.volume.stats) + ",";
    r_.volume = p.volume.stats;
    if (out_ && lights_.empty()) p.volume = ShadowVolume();  // else the light volumes' source
    return Step::Next;
  }

  // adjacency (streamed: built here, once every stage that reads the edge table has run).
  Step adjacency(Pipeline& p, bool all) {
    if (out_) {
      if (asked_.adjacency) {
        p.adjacency.resize(adjacency_index_count(p.weld.indices.size() / 3));
        build_adjacency(p.adjacency.data(), p.weld.indices.data(), p.weld.indices.size() / 3, p.topology);
      }
      free_vector(p.topology.face_edges), free_vector(p.topology.edges), free_vector(p.topology.edge_faces);
    }
    if (!asked_.adjacency) return Step::Next;
    if (!out_ && !has(Stage::Adjacency, all)) return Step::Wait;
    js_ += "\"adjacency\":{\"indices\":" + json::count(p.adjacency.size()) + "},";
    emit(view_section(SectionType::AdjacencyIndices, Format::U32, 4, "adjacency", p.adjacency, kept_));
    if (out_) free_vector(p.adjacency);
    return Step::Next;
  }

  // lights, light_params, light_names.
  Step light_table() {
    if (lights_.empty()) return Step::Next;
    emit(make_baked_section(SectionType::Lights, Format::F64x4, 32, "lights", table_));
    std::vector<LightRecord> records(lights_.size());
    std::vector<char> names;
    for (size_t i = 0; i < lights_.size(); ++i) {
      records[i] = light_record(lights_[i], uint32_t(names.size()));
      names.insert(names.end(), lights_[i].name.begin(), lights_[i].name.end());
      if (names.size() > UINT32_MAX) throw std::length_error("the lights' names are over 4 GiB");
    }
    emit(make_baked_section(SectionType::LightParams, Format::Record, sizeof(LightRecord), "light_params", records));
    emit(make_baked_section(SectionType::LightNames, Format::Utf8, 1, "light_names", names));
    return Step::Next;
  }

  // light_sides, light_caps, light_planes per light.
  Step light_volumes(Pipeline& p, bool all) {
    if (!lights_.empty() && !has(Stage::Lights, all)) return Step::Wait;
    if (!asked_.volume) p.volume = ShadowVolume();  // the light volumes' source, emitted by none
    js_ += "\"lights\":[";
    for (size_t i = 0; i < p.lights.size(); ++i) {
      ShadowVolume& lv = p.lights[i].volume;
      const uint32_t item = uint32_t(i);
      const double* h = &table_[4 * i];
      emit(record_section(SectionType::LightSides, "light_sides", lv.sides, kept_, item));
      emit(record_section(SectionType::LightCaps, "light_caps", lv.caps, kept_, item));
      emit(view_section(SectionType::LightPlanes, Format::F32x4, 16, "light_planes", lv.planes, kept_, item));
      js_ += std::string(i ? "," : "") + "{\"name\":" + json::quote(lights_[i].name) + ",\"light\":[" +
             json::number(h[0]) + "," + json::number(h[1]) + "," + json::number(h[2]) + "," + json::number(h[3]) +
             "],\"sides\":" + json::count(lv.sides.size()) + ",\"caps\":" + json::count(lv.caps.size()) +
             ",\"bytes\":" + json::count(lv.stats.bytes) + "}";
      if (out_) lv.sides = {}, lv.caps = {}, free_vector(lv.planes);
    }
    js_ += "]}";
    if (out_) p.volume = ShadowVolume();
    return Step::Next;
  }

  // silhouette: last, once the whole run is in.
  Step silhouette(bool all) {
    if (!all) return Step::Wait;
    r_.silhouette = js_;
    emit(make_baked_section(SectionType::SilhouetteReport, Format::Utf8, 1, "silhouette",
                            std::vector<char>(js_.begin(), js_.end())));
    return Step::Next;
  }

  const Scene& scene_;
  Scene* release_;
  const std::string& name_;
  const BakeOptions& options_;
  const PipelineOptions& asked_;
  BakedFileWriter* out_;
  std::vector<Light> lights_;
  std::vector<double> table_;  // (x, y, z, w) per light
  bool more_ = false, framed_ = false, stream_esm_ = false, stream_volume_ = false;
  RecordStream quads_, sides_, caps_;
  const std::shared_ptr<Pipeline> kept_ = std::make_shared<Pipeline>();
  bool ran_[unsigned(Stage::Count)] = {};
  Group next_ = Group::Mesh;
  std::string js_ = "{";  // the silhouette section's JSON
  BakeResult r_;
};

BakeResult bake(const Scene& scene, Scene* release, const std::string& name, const BakeOptions& options,
                BakedFileWriter* out) {
  return Baker(scene, release, name, options, out).run();
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

std::string stored_name(const std::string& input) {
  const auto base = [](const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
  };
  std::string lower = input;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* ext : {".pk3:", ".zip:"}) {
    const size_t at = lower.find(ext);
    if (at != std::string::npos) return base(input.substr(0, at + 4)) + input.substr(at + 4);
  }
  return base(input);
}

namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

}  // namespace

BakeResult bake_file(const std::string& input, const std::string& output, const BakeOptions& options,
                     const ImportOptions& import_options, const std::string& name) {
  ImportResult imported = import_file(input, import_options);
  if (!imported.ok) {
    BakeResult r;
    static_cast<Status&>(r) = std::move(imported);
    return r;
  }
  // The output holds the stored name, never the path as given (hermetic bytes):
  // the importer's warnings are stored with it too.
  const std::string stored = name.empty() ? stored_name(input) : name;
  for (std::string& w : imported.scene.warnings) replace_all(w, input, stored);
  BakeResult r = bake_scene(std::move(imported.scene), stored, options);
  imported = ImportResult();
  if (!r.ok) {
    if (r.error.rfind(stored + ":", 0) == 0) r.error = input + r.error.substr(stored.size());
    return r;
  }
  std::string error;
  if (!write_baked(output, r.sections, error)) {
    r.ok = false;
    r.code = ErrorCode::Io;
    r.error = input + ": cannot write " + output + ": " + error;
  }
  return r;
}

}  // namespace geom
