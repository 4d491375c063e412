// silhouette_edges.cpp: edsm's silhouette edges, found once per frame for the
// frame's light (shaders/edsm_silhouettes.comp: the silhouette test of Bujnak
// 2004, Sect. 3.1 on every baked candidate edge, then a stable compaction),
// and drawn from that list by every face and edge pass (edge_pass.h): an edge
// pass then costs 6 vertices per silhouette edge, not per candidate edge nor
// per triangle (Kenzel 2013's geometry shader, edsm-gs).
#include <algorithm>

#include "edge_pass.h"

namespace render {
namespace {

constexpr GLuint kGroup = 256;        // the compute shader's local size
constexpr GLuint kMaxGroups = 65535;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT's least value
constexpr int kPlanesUnit = 3;        // edsm.cpp's unit of the records' planes
constexpr GLbitfield kStorage = GL_SHADER_STORAGE_BARRIER_BIT;

// A mutable storage buffer of at least `bytes`, grown when needed.
void ensure(Buffer& buffer, size_t& size, size_t bytes, const char* name) {
  if (size >= bytes && buffer) return;
  buffer = Buffer();
  glCreateBuffers(1, &buffer.id);
  glNamedBufferData(buffer, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
  label(GL_BUFFER, buffer, name);
  size = bytes;
}

GLuint groups(const Caster& c) { return (GLuint(c.esm_count) + kGroup - 1) / kGroup; }

// Whether a caster's records are compacted: from kCompactFrom records on (three
// dispatches per caster cost more than testing a few records in the vertex
// shader of each pass: llvmpipe, jenga's 1,485 casters of 12 records, 512: 1,265
// ms compacted, 475 ms tested per pass), up to 65535 x 256 records (drawn whole beyond).
constexpr GLsizei kCompactFrom = 2048;
bool compacted(const Caster& c) { return c.esm_count >= kCompactFrom && groups(c) <= kMaxGroups; }

}  // namespace

bool find_silhouettes(Frame& f) {
  State& s = f.s;
  GLuint p = program(s.programs, {"edsm_silhouettes.comp"}, f.error);
  if (!p) return false;
  size_t list = 0, most_groups = 1;
  for (const Caster& c : s.casters) list += size_t(c.esm_count), most_groups = std::max<size_t>(most_groups, groups(c));
  ensure(s.silhouette_lists, s.silhouette_list_size, 4 * std::max<size_t>(list, 1), "silhouette edges");
  ensure(s.silhouette_groups, s.silhouette_group_size, 4 * most_groups, "silhouette workgroup sums");
  ensure(s.silhouette_commands, s.silhouette_command_size, 16 * std::max<size_t>(s.casters.size(), 1),
         "silhouette draws");
  f.timer.begin("silhouette edges");
  const std::vector<GLuint> empty(4 * s.casters.size(), 0);  // 0 vertices until counted
  if (!empty.empty()) glNamedBufferSubData(s.silhouette_commands, 0, GLsizeiptr(4 * empty.size()), empty.data());
  glUseProgram(p);
  set(p, "u_planes", kPlanesUnit);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s.silhouette_commands);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s.silhouette_lists);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s.silhouette_groups);
  GLuint first = 0;
  for (size_t k = 0; k < s.casters.size(); ++k) {
    const Caster& c = s.casters[k];
    if (!compacted(c)) {
      first += GLuint(c.esm_count);
      continue;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, c.esm_records);
    glBindTextureUnit(kPlanesUnit, c.esm_planes);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_count"), GLuint(c.esm_count));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_groups"), groups(c));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_command"), GLuint(k));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_list_first"), first);
    set(p, "u_light", local_light(c, glm::dvec4(f.light.position)));
    for (int step = 0; step < 3; ++step) {
      set(p, "u_step", step);
      glDispatchCompute(step == 1 ? 1 : groups(c), 1, 1);
      glMemoryBarrier(kStorage);
    }
    first += GLuint(c.esm_count);
  }
  glMemoryBarrier(kStorage | GL_COMMAND_BARRIER_BIT);
  for (GLuint b = 0; b < 4; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
  glBindTextureUnit(kPlanesUnit, 0);
  f.timer.end();
  return true;
}

void draw_silhouette_quads(Frame& f, GLuint p, const glm::mat4& light_clip) {
  const State& s = f.s;
  set(p, "u_planes", kPlanesUnit);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s.silhouette_lists);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, s.silhouette_commands);
  GLuint first = 0;
  for (size_t k = 0; k < s.casters.size(); ++k) {
    const Caster& c = s.casters[k];
    set(p, "u_light_view_proj", at(glm::dmat4(light_clip), c.origin));
    set(p, "u_light", local_light(c, glm::dvec4(f.light.position)));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_list_first"), first);
    set(p, "u_compact", compacted(c) ? 1 : 0);
    glBindTextureUnit(kPlanesUnit, c.esm_planes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, c.esm_records);
    glBindVertexArray(c.esm_vao);  // no attribute read: the records come from the storage buffers
    if (compacted(c))
      glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(16 * k));
    else
      glDrawArrays(GL_TRIANGLES, 0, 6 * c.esm_count);
    first += GLuint(c.esm_count);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, 0);
}

}  // namespace render
