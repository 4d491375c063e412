// silhouette_edges.cpp: edsm's and sssm's silhouette edges, found once per
// frame for the frame's light (shaders/edsm_silhouettes.comp: the silhouette
// test of Bujnak 2004, Sect. 3.1 on every baked candidate edge, then a stable
// compaction), and drawn from that list by every face and edge pass
// (edge_pass.h): an edge pass then costs 6 vertices per silhouette edge, not
// per candidate edge nor per triangle (Kenzel 2013's geometry shader, edsm-gs).
//
// Every caster's records are gathered into one buffer (and their planes into
// one texture buffer) once per set of casters, so the search is three
// dispatches and each edge pass one indirect draw whatever the number of
// casters: on a software rasterizer (Mesa's llvmpipe) a draw per caster costs
// more than its edges on scenes of many small casters (jenga's 1,485 blocks).
// The list holds the records in caster order and record order within a caster:
// the quads are drawn in the order a draw per caster would draw them.
#include <algorithm>
#include <cstring>

#include "edge_pass.h"

namespace render {
namespace {

constexpr GLuint kGroup = 64;                                  // the compute shader's local size
constexpr GLuint kRun = 32;                                    // records per invocation (its kRun)
constexpr GLuint kMaxGroups = 65535;                           // GL_MAX_COMPUTE_WORK_GROUP_COUNT's least value
constexpr size_t kChunk = size_t(kGroup) * kRun * kMaxGroups;  // records per dispatch and per draw
constexpr int kPlanesUnit = 3;                                 // the unit of the gathered planes
constexpr GLbitfield kStorage = GL_SHADER_STORAGE_BARRIER_BIT;
constexpr size_t kRecordBytes = 36;  // geom/esm_quads.h EsmQuad: 9 uints
constexpr size_t kPlaneBytes = 16;   // an RGBA32F plane

// A mutable storage buffer of at least `bytes`, grown when needed.
void ensure(Buffer& buffer, size_t& size, size_t bytes, const char* name) {
  if (size >= bytes && buffer) return;
  buffer = Buffer();
  glCreateBuffers(1, &buffer.id);
  glNamedBufferData(buffer, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
  label(GL_BUFFER, buffer, name);
  size = bytes;
}

// A buffer of `bytes` (at least 4) holding `data` when given.
void make(Buffer& buffer, size_t bytes, const void* data, GLenum usage, const char* name) {
  buffer = Buffer();
  glCreateBuffers(1, &buffer.id);
  glNamedBufferData(buffer, GLsizeiptr(std::max<size_t>(bytes, 4)), data, usage);
  label(GL_BUFFER, buffer, name);
}

size_t chunks(size_t records) { return (records + kChunk - 1) / kChunk; }
size_t runs(size_t records) { return (records + kRun - 1) / kRun; }
GLuint groups(size_t records) { return GLuint((runs(records) + kGroup - 1) / kGroup); }

// The casters' records and planes gathered (s.merged_*), unless the casters
// are the ones gathered last.
void gather(State& s) {
  size_t records = 0;
  for (const Caster& c : s.casters) records += size_t(c.esm_count);
  const size_t key[3] = {s.casters.size(), records, s.casters.empty() ? 0 : size_t(s.casters.front().esm_records.id)};
  if (s.merged_records && std::equal(key, key + 3, s.merged_key)) return;
  std::copy(key, key + 3, s.merged_key);
  s.merged_count = records;
  std::vector<GLint> plane_count(s.casters.size(), 0);
  size_t planes = 0;
  s.caster_plane_first.assign(s.casters.size(), 0);
  std::vector<GLuint> record_caster(records);
  for (size_t k = 0, r = 0; k < s.casters.size(); ++k) {
    const Caster& c = s.casters[k];
    if (c.esm_plane_buffer) glGetNamedBufferParameteriv(c.esm_plane_buffer, GL_BUFFER_SIZE, &plane_count[k]);
    plane_count[k] /= GLint(kPlaneBytes);
    s.caster_plane_first[k] = GLuint(planes);
    planes += size_t(plane_count[k]);
    std::fill_n(record_caster.begin() + std::ptrdiff_t(r), c.esm_count, GLuint(k));
    r += size_t(c.esm_count);
  }
  make(s.merged_records, kRecordBytes * records, nullptr, GL_STATIC_DRAW, "every caster's ESM quads");
  make(s.merged_plane_buffer, kPlaneBytes * planes, nullptr, GL_STATIC_DRAW, "every caster's ESM planes");
  make(s.record_casters, 4 * records, record_caster.data(), GL_STATIC_DRAW, "the caster of each ESM quad");
  for (size_t k = 0, r = 0; k < s.casters.size(); ++k) {
    const Caster& c = s.casters[k];
    if (c.esm_count)
      glCopyNamedBufferSubData(c.esm_records, s.merged_records, 0, GLintptr(kRecordBytes * r),
                               GLsizeiptr(kRecordBytes * size_t(c.esm_count)));
    if (plane_count[k])
      glCopyNamedBufferSubData(c.esm_plane_buffer, s.merged_plane_buffer, 0,
                               GLintptr(kPlaneBytes * s.caster_plane_first[k]),
                               GLsizeiptr(kPlaneBytes * size_t(plane_count[k])));
    r += size_t(c.esm_count);
  }
  s.merged_planes = Texture();
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &s.merged_planes.id);
  glTextureBuffer(s.merged_planes, GL_RGBA32F, s.merged_plane_buffer);
  label(GL_TEXTURE, s.merged_planes, "every caster's ESM planes");
  if (!s.no_attributes) {
    glCreateVertexArrays(1, &s.no_attributes.id);
    label(GL_VERTEX_ARRAY, s.no_attributes, "edge quads (no attribute)");
  }
}

}  // namespace

bool find_silhouettes(Frame& f) {
  State& s = f.s;
  GLuint p = program(s.programs, {"edsm_silhouettes.comp"}, f.error);
  if (!p) return false;
  gather(s);
  const size_t records = s.merged_count, n_chunks = chunks(records);
  ensure(s.silhouette_lists, s.silhouette_list_size, 4 * std::max<size_t>(records, 1), "silhouette edges");
  ensure(s.silhouette_groups, s.silhouette_group_size, 4 * std::max<size_t>(runs(std::min(records, kChunk)), 1),
         "silhouette counts per run");
  ensure(s.silhouette_commands, s.silhouette_command_size, 16 * std::max<size_t>(n_chunks, 1), "silhouette draws");
  f.timer.begin("silhouette edges");
  // Per caster its light in its local frame and its first plane (8 floats, std430).
  std::vector<float> lights(8 * s.casters.size(), 0.0f);
  for (size_t k = 0; k < s.casters.size(); ++k) {
    const glm::vec4 l = local_light(s.casters[k], glm::dvec4(f.light.position));
    std::copy(&l.x, &l.x + 4, &lights[8 * k]);
    const GLuint first = s.caster_plane_first[k];
    std::memcpy(&lights[8 * k + 4], &first, 4);
  }
  make(s.caster_lights, 4 * lights.size(), lights.data(), GL_STREAM_DRAW, "each caster's light");
  const std::vector<GLuint> empty(4 * std::max<size_t>(n_chunks, 1), 0);  // 0 vertices until counted
  glNamedBufferSubData(s.silhouette_commands, 0, GLsizeiptr(4 * empty.size()), empty.data());
  glUseProgram(p);
  set(p, "u_planes", kPlanesUnit);
  glBindTextureUnit(kPlanesUnit, s.merged_planes);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s.merged_records);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s.silhouette_commands);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s.silhouette_lists);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s.silhouette_groups);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, s.record_casters);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, s.caster_lights);
  for (size_t k = 0; k < n_chunks; ++k) {
    const size_t first = k * kChunk, count = std::min(kChunk, records - first);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_first"), GLuint(first));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_count"), GLuint(count));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_command"), GLuint(k));
    for (int step = 0; step < 3; ++step) {
      set(p, "u_step", step);
      glDispatchCompute(step == 1 ? 1 : groups(count), 1, 1);
      glMemoryBarrier(kStorage);
    }
  }
  glMemoryBarrier(kStorage | GL_COMMAND_BARRIER_BIT);
  for (GLuint b = 0; b < 6; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
  glBindTextureUnit(kPlanesUnit, 0);
  f.timer.end();
  return true;
}

void draw_silhouette_quads(Frame& f, GLuint p, const glm::mat4& light_clip) {
  State& s = f.s;
  std::vector<glm::mat4> matrices(std::max<size_t>(s.casters.size(), 1));
  for (size_t k = 0; k < s.casters.size(); ++k) matrices[k] = at(glm::dmat4(light_clip), s.casters[k].origin);
  make(s.caster_matrices, sizeof(glm::mat4) * matrices.size(), matrices.data(), GL_STREAM_DRAW,
       "each caster's light matrix");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s.merged_records);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s.silhouette_lists);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, s.record_casters);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, s.caster_matrices);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s.silhouette_commands);
  glBindVertexArray(s.no_attributes);
  for (size_t k = 0; k < chunks(s.merged_count); ++k) {
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_list_first"), GLuint(k * kChunk));
    glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(16 * k));
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  for (GLuint b : {0u, 2u, 4u, 6u}) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
}

}  // namespace render
