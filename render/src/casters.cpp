// casters.cpp: the casters' silhouette buffers on the GPU. An in-process bake
// (geom/pipeline.h, one caster per glTF mesh instance) and a baked container
// (geom/baked_reader.h, one caster) both become a BakedView, and every
// BakedView is uploaded by upload_caster, after its indices are checked (a
// baked file is untrusted input).
#include <map>
#include <tuple>

#include "geom/extrude.h"
#include "geom/topology.h"
#include "state.h"

namespace render {

BakedView baked_view(const geom::Pipeline& b) {
  BakedView v;
  for (int k = 0; k < 3; ++k) v.origin[k] = b.planes.origin[k];
  v.welded = b.weld.positions.data(), v.welded_count = b.weld.vertex_count();
  v.adjacency = b.adjacency.data(), v.adjacency_count = b.adjacency.size();
  v.esm = b.esm.quads.data(), v.esm_count = b.esm.quads.size();
  v.esm_planes = b.esm.planes.data(), v.esm_plane_count = b.esm.planes.size() / 4;
  v.sides = b.volume.sides.data(), v.side_count = b.volume.sides.size();
  v.caps = b.volume.caps.data(), v.cap_count = b.volume.caps.size();
  v.volume_planes = b.volume.planes.data(), v.volume_plane_count = b.volume.planes.size() / 4;
  v.indices = b.weld.indices.data(), v.triangle_count = b.weld.indices.size() / 3;
  for (const geom::LightVolume& lv : b.lights)
    if (lv.volume.per_light) {
      BakedView::LightVolume l{{},
                               lv.volume.sides.data(),
                               lv.volume.sides.size(),
                               lv.volume.caps.data(),
                               lv.volume.caps.size(),
                               lv.volume.planes.data(),
                               lv.volume.planes.size() / 4};
      geom::light_homogeneous(lv.light, l.light);
      v.light_volumes.push_back(l);
    }
  return v;
}

bool baked_view(const geom::baked::Reader& reader, BakedView& v, std::string& error) {
  namespace gb = geom::baked;
  v = BakedView();
  const gb::Section* positions = reader.find(gb::SectionType::Positions);
  const gb::Section* indices = reader.find(gb::SectionType::Indices);
  if (!positions || !indices || !positions->as<float[3]>() || !indices->as<uint32_t>() || indices->count % 3) {
    error = "no usable positions and indices sections (bake with both)";
    return false;
  }
  v.welded = positions->as<float[3]>()[0], v.welded_count = positions->count;
  v.indices = indices->as<uint32_t>(), v.triangle_count = indices->count / 3;
  if (const gb::Section* frame = reader.find(gb::SectionType::Frame);
      frame && frame->as<double[3]>() && frame->count == 1)
    for (int k = 0; k < 3; ++k) v.origin[k] = frame->as<double[3]>()[0][k];
  const gb::Section* adjacency = reader.find(gb::SectionType::AdjacencyIndices);
  v.has_adjacency = adjacency && adjacency->as<uint32_t>() && adjacency->count == 2 * indices->count;
  if (v.has_adjacency) v.adjacency = adjacency->as<uint32_t>(), v.adjacency_count = adjacency->count;
  const gb::Section* esm = reader.find(gb::SectionType::EsmQuads);
  const gb::Section* esm_planes = reader.find(gb::SectionType::EsmPlanes);
  v.has_esm = esm && esm_planes && esm->as<geom::EsmQuad>() && esm_planes->as<float[4]>();
  if (v.has_esm) {
    v.esm = esm->as<geom::EsmQuad>(), v.esm_count = esm->count;
    v.esm_planes = esm_planes->as<float[4]>()[0], v.esm_plane_count = esm_planes->count;
  }
  const gb::Section* sides = reader.find(gb::SectionType::VolumeSides);
  const gb::Section* caps = reader.find(gb::SectionType::VolumeCaps);
  const gb::Section* planes = reader.find(gb::SectionType::VolumePlanes);
  v.has_volume =
      sides && caps && planes && sides->as<geom::SvSide>() && caps->as<geom::SvCap>() && planes->as<float[4]>();
  if (v.has_volume) {
    v.sides = sides->as<geom::SvSide>(), v.side_count = sides->count;
    v.caps = caps->as<geom::SvCap>(), v.cap_count = caps->count;
    v.volume_planes = planes->as<float[4]>()[0], v.volume_plane_count = planes->count;
  }
  if (const gb::Section* lights = reader.find(gb::SectionType::Lights); lights && lights->as<double[4]>())
    for (uint32_t i = 0; i < lights->count; ++i) {
      const gb::Section* ls = reader.find(gb::SectionType::LightSides, i);
      const gb::Section* lc = reader.find(gb::SectionType::LightCaps, i);
      const gb::Section* lp = reader.find(gb::SectionType::LightPlanes, i);
      if (!ls || !lc || !lp || !ls->as<geom::SvSide>() || !lc->as<geom::SvCap>() || !lp->as<float[4]>()) continue;
      const double* l = lights->as<double[4]>()[i];
      v.light_volumes.push_back({{l[0], l[1], l[2], l[3]},
                                 ls->as<geom::SvSide>(),
                                 ls->count,
                                 lc->as<geom::SvCap>(),
                                 lc->count,
                                 lp->as<float[4]>()[0],
                                 lp->count});
    }
  return true;
}

namespace {

// Groups the triangles by caster: one glTF mesh instance (file, mesh, node), or
// everything where the format has no such notion.
std::vector<std::vector<uint32_t>> caster_triangles(const geom::Scene& scene) {
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, size_t> group_of;
  std::vector<std::vector<uint32_t>> groups;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    geom::TriangleSource src = t < scene.sources.size() ? scene.sources[t] : geom::TriangleSource();
    auto key = std::make_tuple(src.file, src.mesh, src.node);
    auto it = group_of.emplace(key, groups.size()).first;
    if (it->second == groups.size()) groups.emplace_back();
    groups[it->second].push_back(uint32_t(t));
  }
  return groups;
}

// Vertex arrays of volume sides and caps (geom/shadow_volume.h layout).
void volume_arrays(VertexArray& sides_vao, VertexArray& caps_vao, GLuint sides, GLuint caps) {
  glCreateVertexArrays(1, &sides_vao.id);
  glVertexArrayVertexBuffer(sides_vao, 0, sides, 0, sizeof(geom::SvSide));
  glVertexArrayBindingDivisor(sides_vao, 0, 1);
  attribute(sides_vao, 0, 3, GL_FLOAT, 0, false);
  attribute(sides_vao, 1, 3, GL_FLOAT, 12, false);
  attribute(sides_vao, 3, 1, GL_UNSIGNED_INT, 24, true);
  attribute(sides_vao, 4, 1, GL_UNSIGNED_INT, 28, true);
  label(GL_VERTEX_ARRAY, sides_vao, "volume sides");
  glCreateVertexArrays(1, &caps_vao.id);
  glVertexArrayVertexBuffer(caps_vao, 0, caps, 0, sizeof(geom::SvCap));
  glVertexArrayBindingDivisor(caps_vao, 0, 1);
  attribute(caps_vao, 0, 3, GL_FLOAT, 0, false);
  attribute(caps_vao, 1, 3, GL_FLOAT, 12, false);
  attribute(caps_vao, 2, 3, GL_FLOAT, 24, false);
  attribute(caps_vao, 3, 1, GL_UNSIGNED_INT, 36, true);
  label(GL_VERTEX_ARRAY, caps_vao, "volume caps");
}

template <class Record>
bool planes_in_range(const Record* records, size_t count, size_t planes, uint32_t Record::*first,
                     uint32_t Record::*second) {
  for (size_t i = 0; i < count; ++i) {
    if (((records[i].*first) & 0x7fffffffu) >= planes) return false;
    if (second && ((records[i].*second) & 0x7fffffffu) >= planes) return false;
  }
  return true;
}

// Inspection lines: boundary, non-manifold and inconsistent edges; degenerate faces.
void inspection_lines(Caster& c, const BakedView& src) {
  const geom::Topology topology =
      geom::build_topology(geom::positions_of(src.welded, src.welded_count), src.indices, src.triangle_count);
  std::vector<float> lines[4];
  auto vertex = [&](std::vector<float>& out, uint32_t v) {
    out.insert(out.end(), src.welded + 3 * size_t(v), src.welded + 3 * size_t(v) + 3);
  };
  for (const geom::Edge& e : topology.edges) {
    const int kind = e.kind == geom::EdgeKind::Boundary       ? 0
                     : e.kind == geom::EdgeKind::NonManifold  ? 1
                     : e.kind == geom::EdgeKind::Inconsistent ? 2
                                                              : -1;
    if (kind >= 0) vertex(lines[kind], e.v0), vertex(lines[kind], e.v1);
  }
  for (size_t t = 0; t < topology.face_flags.size() && t < src.triangle_count; ++t)
    if (topology.face_flags[t] & (geom::kFaceCollapsed | geom::kFaceZeroArea))
      for (int k = 0; k < 3; ++k)
        vertex(lines[3], src.indices[3 * t + k]), vertex(lines[3], src.indices[3 * t + (k + 1) % 3]);
  std::vector<float> all;
  for (int k = 0; k < 4; ++k) {
    c.line_first[k] = GLsizei(all.size() / 3);
    c.line_count[k] = GLsizei(lines[k].size() / 3);
    all.insert(all.end(), lines[k].begin(), lines[k].end());
  }
  upload(c.lines, all.data(), all.size() * sizeof(float), "caster inspection lines");
  glCreateVertexArrays(1, &c.lines_vao.id);
  glVertexArrayVertexBuffer(c.lines_vao, 0, c.lines, 0, 3 * sizeof(float));
  attribute(c.lines_vao, 0, 3, GL_FLOAT, 0, false);
  label(GL_VERTEX_ARRAY, c.lines_vao, "caster inspection lines");
}

}  // namespace

bool upload_caster(State& s, const BakedView& src, std::string& error) {
  for (size_t i = 0; i < src.adjacency_count; ++i)
    if (src.adjacency[i] >= src.welded_count) {
      error = "adjacency index " + std::to_string(i) + " out of range";
      return false;
    }
  for (size_t i = 0; i < 3 * src.triangle_count; ++i)
    if (src.indices[i] >= src.welded_count) {
      error = "triangle index " + std::to_string(i) + " out of range";
      return false;
    }
  if (!planes_in_range(src.esm, src.esm_count, src.esm_plane_count, &geom::EsmQuad::plane_a, &geom::EsmQuad::plane_b) ||
      !planes_in_range(src.sides, src.side_count, src.volume_plane_count, &geom::SvSide::plane_a,
                       &geom::SvSide::plane_b) ||
      !planes_in_range<geom::SvCap>(src.caps, src.cap_count, src.volume_plane_count, &geom::SvCap::plane, nullptr)) {
    error = "a silhouette record refers to a plane out of range";
    return false;
  }
  Caster c;
  c.origin = glm::dvec3(src.origin[0], src.origin[1], src.origin[2]);
  c.lo = glm::vec3(1e30f), c.hi = glm::vec3(-1e30f);
  for (size_t v = 0; v < src.welded_count; ++v) {
    const glm::vec3 p(src.welded[3 * v], src.welded[3 * v + 1], src.welded[3 * v + 2]);
    c.lo = glm::min(c.lo, p), c.hi = glm::max(c.hi, p);
  }
  // Edge distance shadow map: welded positions and the adjacency indices.
  upload(c.welded, src.welded, src.welded_count * 3 * sizeof(float), "caster welded positions");
  upload(c.adjacency, src.adjacency, src.adjacency_count * sizeof(uint32_t), "caster adjacency indices");
  c.adjacency_count = GLsizei(src.adjacency_count);
  glCreateVertexArrays(1, &c.adjacency_vao.id);
  glVertexArrayVertexBuffer(c.adjacency_vao, 0, c.welded, 0, 3 * sizeof(float));
  glVertexArrayElementBuffer(c.adjacency_vao, c.adjacency);
  attribute(c.adjacency_vao, 0, 3, GL_FLOAT, 0, false);
  label(GL_VERTEX_ARRAY, c.adjacency_vao, "caster adjacency");
  // Extended shadow map quads (geom/esm_quads.h layout).
  upload(c.esm_records, src.esm, src.esm_count * sizeof(geom::EsmQuad), "caster ESM quads");
  plane_texture(c.esm_planes, c.esm_plane_buffer, src.esm_planes, src.esm_plane_count, "caster ESM planes");
  c.esm_count = GLsizei(src.esm_count);
  glCreateVertexArrays(1, &c.esm_vao.id);
  glVertexArrayVertexBuffer(c.esm_vao, 0, c.esm_records, 0, sizeof(geom::EsmQuad));
  glVertexArrayBindingDivisor(c.esm_vao, 0, 1);
  attribute(c.esm_vao, 0, 3, GL_FLOAT, 0, false);
  attribute(c.esm_vao, 1, 3, GL_FLOAT, 12, false);
  attribute(c.esm_vao, 2, 1, GL_UNSIGNED_INT, 24, true);
  attribute(c.esm_vao, 3, 1, GL_UNSIGNED_INT, 28, true);
  attribute(c.esm_vao, 4, 2, GL_SHORT, 32, false, true);
  label(GL_VERTEX_ARRAY, c.esm_vao, "caster ESM quads");
  // Shadow volume (geom/shadow_volume.h layout).
  upload(c.sv_sides, src.sides, src.side_count * sizeof(geom::SvSide), "caster volume sides");
  upload(c.sv_caps, src.caps, src.cap_count * sizeof(geom::SvCap), "caster volume caps");
  plane_texture(c.sv_planes, c.sv_plane_buffer, src.volume_planes, src.volume_plane_count, "caster volume planes");
  c.side_count = GLsizei(src.side_count), c.cap_count = GLsizei(src.cap_count);
  volume_arrays(c.sides_vao, c.caps_vao, c.sv_sides, c.sv_caps);
  for (const BakedView::LightVolume& lv : src.light_volumes) {
    if (!planes_in_range(lv.sides, lv.side_count, lv.plane_count, &geom::SvSide::plane_a, &geom::SvSide::plane_b) ||
        !planes_in_range<geom::SvCap>(lv.caps, lv.cap_count, lv.plane_count, &geom::SvCap::plane, nullptr)) {
      error = "a light volume record refers to a plane out of range";
      return false;
    }
    Caster::LightVolume v;
    v.light = glm::dvec4(lv.light[0], lv.light[1], lv.light[2], lv.light[3]);
    upload(v.sides, lv.sides, lv.side_count * sizeof(geom::SvSide), "light volume sides");
    upload(v.caps, lv.caps, lv.cap_count * sizeof(geom::SvCap), "light volume caps");
    plane_texture(v.planes, v.plane_buffer, lv.planes, lv.plane_count, "light volume planes");
    v.side_count = GLsizei(lv.side_count), v.cap_count = GLsizei(lv.cap_count);
    volume_arrays(v.sides_vao, v.caps_vao, v.sides, v.caps);
    c.light_volumes.push_back(std::move(v));
  }
  inspection_lines(c, src);
  s.casters.push_back(std::move(c));
  return true;
}

bool build_casters(State& s, std::string& error) {
  if (s.casters_built) return true;
  const geom::Scene& scene = s.scene;
  for (const std::vector<uint32_t>& tris : caster_triangles(scene)) {
    // The caster's own vertices, compacted.
    std::map<uint32_t, uint32_t> remap;
    std::vector<float> positions;
    std::vector<uint32_t> indices;
    for (uint32_t t : tris)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = scene.indices[3 * size_t(t) + k];
        auto it = remap.emplace(v, uint32_t(positions.size() / 3)).first;
        if (it->second == positions.size() / 3)
          positions.insert(positions.end(), scene.positions.begin() + 3 * size_t(v),
                           scene.positions.begin() + 3 * size_t(v) + 3);
        indices.push_back(it->second);
      }
    geom::PipelineOptions options;
    options.release_early = true;  // the casters read no topology
    const geom::Pipeline b = geom::run_pipeline(geom::positions_of(positions.data(), positions.size() / 3),
                                                indices.data(), tris.size(), scene.lights, options);
    if (b.adjacency.size() != 6 * tris.size() || b.weld.indices.size() != 3 * tris.size()) {
      error = "the silhouette bake failed";
      return false;
    }
    if (!upload_caster(s, baked_view(b), error)) return false;
  }
  s.casters_built = true;
  return true;
}

glm::vec4 local_light(const Caster& c, const glm::dvec4& light) {
  const double origin[3] = {c.origin.x, c.origin.y, c.origin.z}, l[4] = {light.x, light.y, light.z, light.w};
  float out[4];
  geom::to_local_light(origin, l, out);
  return glm::vec4(out[0], out[1], out[2], out[3]);
}

const Caster::LightVolume* light_volume(const Caster& c, const glm::vec4& light) {
  for (const Caster::LightVolume& v : c.light_volumes) {
    const double scale = std::max(1.0, glm::length(glm::dvec3(v.light)));
    if (v.light.w == double(light.w) && glm::length(glm::dvec3(v.light) - glm::dvec3(light)) <= 1e-6 * scale) return &v;
  }
  return nullptr;
}

void draw_scene(const State& s) {
  glBindVertexArray(s.scene_vao);
  glDrawArrays(GL_TRIANGLES, 0, s.scene_vertices);
}

}  // namespace render
