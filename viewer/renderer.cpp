// geomview's renderer: the state struct, the passes of every technique, and the
// shared shading pass. References for each pass are in the shaders' headers:
//   shadow map + slope-scaled bias, PCF ........ shaders/lookup_shadow_map.frag
//   omnidirectional cube map (003, 12.3-12.4) .. shaders/cube_distance.*, lookup_cube.frag
//   edge distance shadow map (001) ............. shaders/edsm_edges.*, lookup_edsm.frag
//   extended shadow map (000) .................. shaders/esm_quad.vert, esm_edges.frag, lookup_esm.frag
//   stencil shadow volumes (004, 001 Sect. 5) .. shaders/shadow_volume.vert, volume.frag
//   perspective (002), light-space perspective and uniform focused shadow maps:
//   the light matrix of geom/focus.h (per frame), then the simple map's passes
// The silhouette buffers come from geom/silhouette.h, baked once per caster
// (the triangles of one glTF mesh instance, or of the whole file when it has
// no such notion), so that shadow volumes choose depth-pass or depth-fail per
// caster as an engine does.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "geom/focus.h"
#include "geom/baked_reader.h"
#include "geom/extrude.h"
#include "geom/silhouette.h"
#include "geom/topology.h"

namespace viewer {
namespace {

const char* const kTechniqueNames[] = {"ssm", "pcf", "esm", "edsm", "sv", "sv-zpass", "sv-zfail",
                                       "cube", "psm", "lispsm", "uniform"};

bool technique_available(Technique t) {
  switch (t) {
    case Technique::Ssm:
    case Technique::Pcf:
    case Technique::Cube:
    case Technique::Esm:
    case Technique::Edsm:
    case Technique::Sv:
    case Technique::SvZPass:
    case Technique::SvZFail:
    case Technique::Psm:
    case Technique::Lispsm:
    case Technique::Uniform:
      return true;
  }
  return false;
}

// A GL name that deletes itself (one deleter per object kind).
template <void (*Delete)(GLuint)>
struct GlName {
  GLuint id = 0;
  GlName() = default;
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GlName(GlName&& o) noexcept : id(o.id) { o.id = 0; }
  GlName& operator=(GlName&& o) noexcept {
    std::swap(id, o.id);
    return *this;
  }
  ~GlName() {
    if (id) Delete(id);
  }
  operator GLuint() const { return id; }
};
void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_query(GLuint id) { glDeleteQueries(1, &id); }
using Buffer = GlName<delete_buffer>;
using Texture = GlName<delete_texture>;
using Framebuffer = GlName<delete_framebuffer>;
using Renderbuffer = GlName<delete_renderbuffer>;
using VertexArray = GlName<delete_vertex_array>;
using Program = GlName<delete_program>;
using Query = GlName<delete_query>;

void label(GLenum kind, GLuint id, const std::string& name) { glObjectLabel(kind, id, -1, name.c_str()); }

// A render target: colour texture (optional), depth(-stencil) texture (optional).
struct Target {
  Framebuffer fbo;
  Texture color, depth;
  int width = 0, height = 0;
};

struct PassTimer {
  bool gpu = false;
  std::vector<std::pair<std::string, Query>> queries;
  std::vector<PassTime>* out = nullptr;
  std::chrono::steady_clock::time_point start;
  std::string current;
  void begin(const std::string& name) {
    current = name;
    if (gpu) {
      queries.emplace_back(name, Query());
      glCreateQueries(GL_TIME_ELAPSED, 1, &queries.back().second.id);
      glBeginQuery(GL_TIME_ELAPSED, queries.back().second);
    } else {
      glFinish();
      start = std::chrono::steady_clock::now();
    }
  }
  void end() {
    if (gpu) {
      glEndQuery(GL_TIME_ELAPSED);
    } else {
      glFinish();
      out->push_back({current, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
    }
  }
  void collect() {
    for (auto& q : queries) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(q.second, GL_QUERY_RESULT, &ns);
      out->push_back({q.first, ns * 1e-6});
    }
    queries.clear();
  }
};

// The static buffers of one caster (geom/silhouette.h), in its local frame.
struct Caster {
  glm::vec3 lo{0}, hi{0};  // world bounding box
  glm::dvec3 origin{0};    // local frame origin (geom/face_planes.h)
  // Edge distance shadow map: welded positions (world) + GL_TRIANGLES_ADJACENCY indices.
  Buffer welded, adjacency;
  VertexArray adjacency_vao;
  GLsizei adjacency_count = 0;
  // Extended shadow map quads and their planes (texture buffer).
  Buffer esm_records, esm_plane_buffer;
  Texture esm_planes;
  VertexArray esm_vao;
  GLsizei esm_count = 0;
  // Shadow volume sides, caps and planes.
  Buffer sv_sides, sv_caps, sv_plane_buffer;
  Texture sv_planes;
  VertexArray sides_vao, caps_vao;
  GLsizei side_count = 0, cap_count = 0;
  // Exact volumes of the static lights (geom/shadow_volume.h build_light_volume):
  // used instead of the generic one when the frame's light is one of them.
  struct LightVolume {
    glm::dvec4 light{0};  // input coordinates
    Buffer sides, caps, plane_buffer;
    Texture planes;
    VertexArray sides_vao, caps_vao;
    GLsizei side_count = 0, cap_count = 0;
  };
  std::vector<LightVolume> light_volumes;
  // Inspection lines (world): boundary, non-manifold, inconsistent edges, then degenerate faces' edges.
  Buffer lines;
  VertexArray lines_vao;
  GLsizei line_first[4] = {0, 0, 0, 0}, line_count[4] = {0, 0, 0, 0};
};

}  // namespace

struct State {
  std::string shader_dir;
  bool gpu_timers = false;
  std::string renderer;
  // Scene: non-indexed triangles, position + face normal per vertex (world space).
  Buffer scene_vbo;
  VertexArray scene_vao;
  GLsizei scene_vertices = 0;
  glm::vec4 bounds{0, 0, 0, 1};
  glm::vec3 scene_lo{-1}, scene_hi{1};  // bounding box
  glm::dvec3 origin{0};  // the scene buffer's local frame (its box centre): far coordinates keep float precision
  // Render targets, re-created when their size changes.
  Target camera, shadow_map, cube, edge_map;
  GLuint depth_sampler = 0;  // reads a depth texture without comparison
  std::map<std::string, Program> programs;
  // Silhouette buffers per caster, baked on first use.
  geom::Scene scene;  // positions, indices, sources: the casters are baked from it
  bool casters_built = false;
  std::vector<Caster> casters;
  // A baked file's casters come with it; the buffers it lacks are named here.
  bool baked = false, baked_esm = true, baked_volume = true, baked_adjacency = true;
  ~State() {
    if (depth_sampler) glDeleteSamplers(1, &depth_sampler);
  }
};

void StateDeleter::operator()(State* s) const { delete s; }

std::vector<Technique> available_techniques() {
  std::vector<Technique> out;
  for (int i = 0; i <= int(Technique::Uniform); ++i)
    if (technique_available(Technique(i))) out.push_back(Technique(i));
  return out;
}

const char* technique_name(Technique t) { return kTechniqueNames[int(t)]; }

bool parse_technique(const std::string& name, Technique& out) {
  for (int i = 0; i <= int(Technique::Uniform); ++i)
    if (name == kTechniqueNames[i] && technique_available(Technique(i))) {
      out = Technique(i);
      return true;
    }
  return false;
}

namespace {

bool read_text(const std::string& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  text = ss.str();
  return true;
}

// Links the program made of the named shader files (stage from the extension:
// .vert .geom .frag; several files of one stage are linked together), cached by name.
GLuint program(State& s, const std::vector<std::string>& files, std::string& error) {
  std::string key;
  for (auto& f : files) key += f + "+";
  auto it = s.programs.find(key);
  if (it != s.programs.end()) return it->second;
  Program prog;
  prog.id = glCreateProgram();
  std::vector<GLuint> shaders;
  bool ok = true;
  for (auto& f : files) {
    std::string text;
    if (!read_text(s.shader_dir + "/" + f, text)) {
      error = s.shader_dir + "/" + f + ": cannot read the shader";
      ok = false;
      break;
    }
    const std::string ext = f.substr(f.rfind('.') + 1);
    GLenum stage = ext == "vert" ? GL_VERTEX_SHADER : ext == "geom" ? GL_GEOMETRY_SHADER : GL_FRAGMENT_SHADER;
    GLuint sh = glCreateShader(stage);
    label(GL_SHADER, sh, f);
    const char* src = text.c_str();
    glShaderSource(sh, 1, &src, nullptr);
    glCompileShader(sh);
    GLint status = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &status);
    if (!status) {
      char log[4096] = {};
      glGetShaderInfoLog(sh, sizeof log, nullptr, log);
      error = s.shader_dir + "/" + f + ": compile error: " + log;
      glDeleteShader(sh);
      ok = false;
      break;
    }
    glAttachShader(prog, sh);
    shaders.push_back(sh);
  }
  if (ok) {
    glLinkProgram(prog);
    GLint status = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &status);
    if (!status) {
      char log[4096] = {};
      glGetProgramInfoLog(prog, sizeof log, nullptr, log);
      error = "link error (" + key + "): " + log;
      ok = false;
    }
  }
  for (GLuint sh : shaders) glDeleteShader(sh);
  if (!ok) return 0;
  label(GL_PROGRAM, prog, key);
  GLuint id = prog;
  s.programs.emplace(key, std::move(prog));
  return id;
}

void set(GLuint p, const char* name, const glm::mat4& m) {
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, name), 1, GL_FALSE, glm::value_ptr(m));
}
void set(GLuint p, const char* name, const glm::vec4& v) { glProgramUniform4fv(p, glGetUniformLocation(p, name), 1, glm::value_ptr(v)); }
void set(GLuint p, const char* name, const glm::vec3& v) { glProgramUniform3fv(p, glGetUniformLocation(p, name), 1, glm::value_ptr(v)); }
void set(GLuint p, const char* name, float v) { glProgramUniform1f(p, glGetUniformLocation(p, name), v); }
void set(GLuint p, const char* name, int v) { glProgramUniform1i(p, glGetUniformLocation(p, name), v); }

// The camera target: RGBA8 colour + depth/stencil texture.
void ensure_camera_target(State& s, int w, int h) {
  Target& t = s.camera;
  if (t.width == w && t.height == h) return;
  t = Target();
  t.width = w, t.height = h;
  glCreateTextures(GL_TEXTURE_2D, 1, &t.color.id);
  glTextureStorage2D(t.color, 1, GL_RGBA8, w, h);
  label(GL_TEXTURE, t.color, "camera colour");
  glCreateTextures(GL_TEXTURE_2D, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH24_STENCIL8, w, h);
  label(GL_TEXTURE, t.depth, "camera depth-stencil");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.color, 0);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_STENCIL_ATTACHMENT, t.depth, 0);
  label(GL_FRAMEBUFFER, t.fbo, "camera");
}

// The 2D shadow map: a DEPTH_COMPONENT32F texture with comparison (sampler2DShadow).
void ensure_shadow_map(State& s, int n) {
  Target& t = s.shadow_map;
  if (t.width == n) return;
  t = Target();
  t.width = t.height = n;
  glCreateTextures(GL_TEXTURE_2D, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, n, n);
  glTextureParameteri(t.depth, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(t.depth, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTextureParameteri(t.depth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.depth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  label(GL_TEXTURE, t.depth, "shadow map depth");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  glNamedFramebufferDrawBuffer(t.fbo, GL_NONE);
  label(GL_FRAMEBUFFER, t.fbo, "shadow map");
}

// The omnidirectional map (003): R32F cube of squared distances + a cube depth
// buffer for the z-test, all six faces rendered in one layered pass.
void ensure_cube(State& s, int n) {
  Target& t = s.cube;
  if (t.width == n) return;
  t = Target();
  t.width = t.height = n;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &t.color.id);
  glTextureStorage2D(t.color, 1, GL_R32F, n, n);
  glTextureParameteri(t.color, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.color, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  label(GL_TEXTURE, t.color, "cube squared distance");
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, n, n);
  label(GL_TEXTURE, t.depth, "cube depth");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.color, 0);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  label(GL_FRAMEBUFFER, t.fbo, "cube map");
}

// A world matrix applied to points of a local frame at `origin`, composed in
// double so that large translations cancel before the result is rounded.
glm::mat4 at(const glm::dmat4& m, const glm::dvec3& origin) { return glm::mat4(m * glm::translate(glm::dmat4(1), origin)); }

glm::vec3 any_perpendicular(glm::vec3 d) {
  return std::fabs(d.y) < 0.9f * glm::length(d) ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

// The single shadow map's light frame, covering the scene's bounding sphere:
// orthographic for a directional light, perspective for a point light (aimed
// at the sphere) and for a spot light (aimed along its axis, the cone's full
// angle as field of view).
struct LightFrame {
  glm::mat4 proj{1}, view{1};
  glm::mat4 clip() const { return proj * view; }
};

LightFrame light_frame(const State& s, const LightSetup& light) {
  const glm::vec3 c(s.bounds), L(light.position);
  const float r = std::max(s.bounds.w, 1e-6f);
  LightFrame f;
  if (light.position.w == 0) {
    const glm::vec3 dir = glm::normalize(L);
    f.view = glm::lookAt(c + dir * (2 * r), c, any_perpendicular(dir));
    f.proj = glm::ortho(-r, r, -r, r, r * 0.5f, r * 3.5f);
    return f;
  }
  const float d = glm::length(c - L);
  const float near_plane = std::max(d - r, r * 1e-3f), far_plane = d + r;
  glm::vec3 axis = d > 1e-6f * r ? (c - L) / d : glm::vec3(0, -1, 0);
  float fov = d > r ? std::min(2 * std::asin(r / d) * 1.02f, glm::radians(170.0f)) : glm::radians(170.0f);
  if (light.spot) {
    axis = glm::normalize(light.spot_direction);
    fov = std::min(2 * glm::radians(light.spot_angle_deg) * 1.02f, glm::radians(170.0f));
  }
  f.view = glm::lookAt(L, L + axis, any_perpendicular(axis));
  f.proj = glm::perspective(fov, 1.0f, near_plane, far_plane);
  return f;
}

void draw_scene(const State& s) {
  glBindVertexArray(s.scene_vao);
  glDrawArrays(GL_TRIANGLES, 0, s.scene_vertices);
}


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

void upload(Buffer& buffer, const void* data, size_t bytes, const char* name) {
  glCreateBuffers(1, &buffer.id);
  glNamedBufferStorage(buffer, GLsizeiptr(std::max<size_t>(bytes, 16)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (bytes) glNamedBufferSubData(buffer, 0, GLsizeiptr(bytes), data);
  label(GL_BUFFER, buffer, name);
}

void plane_texture(Texture& texture, Buffer& buffer, const float* planes, size_t plane_count, const char* name) {
  upload(buffer, planes, plane_count * 4 * sizeof(float), name);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &texture.id);
  glTextureBuffer(texture, GL_RGBA32F, buffer);
  label(GL_TEXTURE, texture, name);
}

void attribute(GLuint vao, GLuint location, GLint size, GLenum type, GLuint offset, bool integer, bool normalized = false) {
  glEnableVertexArrayAttrib(vao, location);
  if (integer) glVertexArrayAttribIFormat(vao, location, size, type, offset);
  else glVertexArrayAttribFormat(vao, location, size, type, normalized ? GL_TRUE : GL_FALSE, offset);
  glVertexArrayAttribBinding(vao, location, 0);
}

// The silhouette buffers of one caster, as baked in process (geom/silhouette.h)
// or read from a baked container (geom/baked_reader.h): borrowed arrays.
struct CasterSource {
  glm::dvec3 origin{0};
  const float* welded = nullptr;  // xyz per welded vertex (input coordinates)
  size_t welded_count = 0;
  const uint32_t* adjacency = nullptr;  // 6 per triangle, into welded
  size_t adjacency_count = 0;
  const geom::EsmQuad* esm = nullptr;
  size_t esm_count = 0;
  const float* esm_planes = nullptr;
  size_t esm_plane_count = 0;
  const geom::SvSide* sides = nullptr;
  size_t side_count = 0;
  const geom::SvCap* caps = nullptr;
  size_t cap_count = 0;
  const float* volume_planes = nullptr;
  size_t volume_plane_count = 0;
  const uint32_t* indices = nullptr;  // 3 per triangle, into welded (for the inspection lines)
  size_t triangle_count = 0;
  struct LightVolume {
    glm::dvec4 light{0};
    const geom::SvSide* sides = nullptr;
    size_t side_count = 0;
    const geom::SvCap* caps = nullptr;
    size_t cap_count = 0;
    const float* planes = nullptr;
    size_t plane_count = 0;
  };
  std::vector<LightVolume> light_volumes;
};

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
bool planes_in_range(const Record* records, size_t count, size_t planes, uint32_t Record::*first, uint32_t Record::*second) {
  for (size_t i = 0; i < count; ++i) {
    if (((records[i].*first) & 0x7fffffffu) >= planes) return false;
    if (second && ((records[i].*second) & 0x7fffffffu) >= planes) return false;
  }
  return true;
}

// Uploads one caster; checks every index against its array first (a baked file
// is untrusted input).
bool upload_caster(State& s, const CasterSource& src, std::string& error) {
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
  c.origin = src.origin;
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
  for (const CasterSource::LightVolume& lv : src.light_volumes) {
    if (!planes_in_range(lv.sides, lv.side_count, lv.plane_count, &geom::SvSide::plane_a, &geom::SvSide::plane_b) ||
        !planes_in_range<geom::SvCap>(lv.caps, lv.cap_count, lv.plane_count, &geom::SvCap::plane, nullptr)) {
      error = "a light volume record refers to a plane out of range";
      return false;
    }
    Caster::LightVolume v;
    v.light = lv.light;
    upload(v.sides, lv.sides, lv.side_count * sizeof(geom::SvSide), "light volume sides");
    upload(v.caps, lv.caps, lv.cap_count * sizeof(geom::SvCap), "light volume caps");
    plane_texture(v.planes, v.plane_buffer, lv.planes, lv.plane_count, "light volume planes");
    v.side_count = GLsizei(lv.side_count), v.cap_count = GLsizei(lv.cap_count);
    volume_arrays(v.sides_vao, v.caps_vao, v.sides, v.caps);
    c.light_volumes.push_back(std::move(v));
  }
  // Inspection lines: boundary, non-manifold and inconsistent edges; degenerate faces.
  const geom::Topology topology =
      geom::build_topology(geom::positions_of(src.welded, src.welded_count), src.indices, src.triangle_count);
  std::vector<float> lines[4];
  auto vertex = [&](std::vector<float>& out, uint32_t v) { out.insert(out.end(), src.welded + 3 * size_t(v), src.welded + 3 * size_t(v) + 3); };
  for (const geom::Edge& e : topology.edges) {
    const int kind = e.kind == geom::EdgeKind::Boundary      ? 0
                     : e.kind == geom::EdgeKind::NonManifold ? 1
                     : e.kind == geom::EdgeKind::Inconsistent ? 2
                                                              : -1;
    if (kind >= 0) vertex(lines[kind], e.v0), vertex(lines[kind], e.v1);
  }
  for (size_t t = 0; t < topology.face_flags.size() && t < src.triangle_count; ++t)
    if (topology.face_flags[t] & (geom::kFaceCollapsed | geom::kFaceZeroArea))
      for (int k = 0; k < 3; ++k) vertex(lines[3], src.indices[3 * t + k]), vertex(lines[3], src.indices[3 * t + (k + 1) % 3]);
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
  s.casters.push_back(std::move(c));
  return true;
}

// Bakes (geom/silhouette.h) and uploads the silhouette buffers of every caster, once.
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
          positions.insert(positions.end(), scene.positions.begin() + 3 * size_t(v), scene.positions.begin() + 3 * size_t(v) + 3);
        indices.push_back(it->second);
      }
    const geom::SilhouetteBuffers b = geom::bake_silhouettes(geom::positions_of(positions.data(), positions.size() / 3),
                                                             indices.data(), tris.size(), geom::scene_lights(scene));
    if (b.adjacency.size() != 6 * tris.size() || b.weld.indices.size() != 3 * tris.size()) {
      error = "the silhouette bake failed";
      return false;
    }
    CasterSource src;
    src.origin = glm::dvec3(b.planes.origin[0], b.planes.origin[1], b.planes.origin[2]);
    src.welded = b.weld.positions.data(), src.welded_count = b.weld.vertex_count();
    src.adjacency = b.adjacency.data(), src.adjacency_count = b.adjacency.size();
    src.esm = b.esm.quads.data(), src.esm_count = b.esm.quads.size();
    src.esm_planes = b.esm.planes.data(), src.esm_plane_count = b.esm.planes.size() / 4;
    src.sides = b.volume.sides.data(), src.side_count = b.volume.sides.size();
    src.caps = b.volume.caps.data(), src.cap_count = b.volume.caps.size();
    src.volume_planes = b.volume.planes.data(), src.volume_plane_count = b.volume.planes.size() / 4;
    src.indices = b.weld.indices.data(), src.triangle_count = tris.size();
    for (const geom::LightVolume& lv : b.lights)
      if (lv.volume.per_light)
        src.light_volumes.push_back({glm::dvec4(lv.light[0], lv.light[1], lv.light[2], lv.light[3]),
                                     lv.volume.sides.data(), lv.volume.sides.size(), lv.volume.caps.data(),
                                     lv.volume.caps.size(), lv.volume.planes.data(), lv.volume.planes.size() / 4});
    if (!upload_caster(s, src, error)) return false;
  }
  s.casters_built = true;
  return true;
}

// The light in a caster's local frame (geom/face_planes.h).
glm::vec4 local_light(const Caster& c, const glm::dvec4& light) {
  const double origin[3] = {c.origin.x, c.origin.y, c.origin.z}, l[4] = {light.x, light.y, light.z, light.w};
  float out[4];
  geom::to_local_light(origin, l, out);
  return glm::vec4(out[0], out[1], out[2], out[3]);
}

// The exact volume of a static light equal to `light` (relative 1e-6), if any.
const Caster::LightVolume* light_volume(const Caster& c, const glm::vec4& light) {
  for (const Caster::LightVolume& v : c.light_volumes) {
    const double scale = std::max(1.0, glm::length(glm::dvec3(v.light)));
    if (v.light.w == double(light.w) && glm::length(glm::dvec3(v.light) - glm::dvec3(light)) <= 1e-6 * scale) return &v;
  }
  return nullptr;
}

// May the camera's near-plane rectangle lie inside this caster's shadow volume?
// Conservative (004, depth-pass vs depth-fail): the volume part that can contain
// the near rectangle lies within `radius` of the segment from the eye to the
// light (or the ray towards a directional light); test that segment against the
// caster's box grown by `radius` (slab test).
bool camera_may_be_in_volume(const Caster& c, const glm::vec3& eye, float radius, const glm::vec4& light) {
  const glm::vec3 lo = c.lo - glm::vec3(radius), hi = c.hi + glm::vec3(radius);
  const glm::vec3 d = light.w != 0 ? glm::vec3(light) / light.w - eye : glm::vec3(light);
  float t0 = 0, t1 = light.w != 0 ? 1.0f : 1e30f;
  for (int k = 0; k < 3; ++k) {
    if (std::fabs(d[k]) < 1e-30f) {
      if (eye[k] < lo[k] || eye[k] > hi[k]) return false;
      continue;
    }
    float a = (lo[k] - eye[k]) / d[k], b = (hi[k] - eye[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

// A depth map from the light with slope-scaled bias: shared by ssm, pcf, esm,
// edsm and the focused maps. `slope` is glPolygonOffset's factor: the depth
// slope of one texel covers a lookup at the texel's own centre; a filter whose
// taps reach k texels away needs about k + 1 of them.
bool depth_map_pass(State& s, const glm::mat4& light_clip, int n, float slope, PassTimer& timer, std::string& error) {
  ensure_shadow_map(s, n);
  GLuint p = program(s, {"depth.vert", "depth.frag"}, error);
  if (!p) return false;
  set(p, "u_matrix", at(glm::dmat4(light_clip), s.origin));
  timer.begin("depth map");
  glBindFramebuffer(GL_FRAMEBUFFER, s.shadow_map.fbo);
  glViewport(0, 0, n, n);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(slope, 4.0f);  // slope-scaled depth bias (001, Sect. 1.2; 004, glPolygonOffset)
  glUseProgram(p);
  draw_scene(s);
  glDisable(GL_POLYGON_OFFSET_FILL);
  timer.end();
  return true;
}

// The edge target of esm / edsm: an N x N float colour texture + its own depth.
void ensure_edge_map(State& s, int n, GLenum format) {
  Target& t = s.edge_map;
  if (t.width == n && t.height == int(format)) return;
  t = Target();
  t.width = n, t.height = int(format);  // height field keeps the format: one target serves both
  glCreateTextures(GL_TEXTURE_2D, 1, &t.color.id);
  glTextureStorage2D(t.color, 1, format, n, n);
  glTextureParameteri(t.color, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.color, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  label(GL_TEXTURE, t.color, "edge map");
  glCreateTextures(GL_TEXTURE_2D, 1, &t.depth.id);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, n, n);
  label(GL_TEXTURE, t.depth, "edge map priority depth");
  glCreateFramebuffers(1, &t.fbo.id);
  glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.color, 0);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  label(GL_FRAMEBUFFER, t.fbo, "edge map");
}

GLuint depth_sampler(State& s) {
  if (!s.depth_sampler) {
    glCreateSamplers(1, &s.depth_sampler);
    glSamplerParameteri(s.depth_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(s.depth_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(s.depth_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    label(GL_SAMPLER, s.depth_sampler, "depth without comparison");
  }
  return s.depth_sampler;
}

// Edge distance shadow map, distance pass (001, Sect. 4.2.1).
bool edsm_pass(State& s, const glm::mat4& light_clip, int n, PassTimer& timer, std::string& error) {
  ensure_edge_map(s, n, GL_RG32F);
  GLuint p = program(s, {"edsm_edges.vert", "edsm_edges.geom", "edsm_edges.frag"}, error);
  if (!p) return false;
  set(p, "u_matrix", light_clip);
  set(p, "u_map_size", float(n));
  set(p, "u_half_width", 2.0f);
  set(p, "u_depth", 1);
  timer.begin("edge distance map");
  glBindFramebuffer(GL_FRAMEBUFFER, s.edge_map.fbo);
  glViewport(0, 0, n, n);
  const float none[4] = {3.0e38f, 0, 0, 0};
  glClearNamedFramebufferfv(s.edge_map.fbo, GL_COLOR, 0, none);
  glClear(GL_DEPTH_BUFFER_BIT);
  glBindTextureUnit(1, s.shadow_map.depth);
  glBindSampler(1, depth_sampler(s));
  glUseProgram(p);
  for (const Caster& c : s.casters) {
    glBindVertexArray(c.adjacency_vao);
    glDrawElements(GL_TRIANGLES_ADJACENCY, c.adjacency_count, GL_UNSIGNED_INT, nullptr);
  }
  glBindSampler(1, 0);
  timer.end();
  return true;
}

// Extended shadow map, silhouette quad pass (000, Sect. 4.1-4.2): edge distance
// and edge depth beside the depth map, MAX blending.
bool esm_pass(State& s, const LightFrame& frame, const LightSetup& light, int n, PassTimer& timer,
              std::string& error) {
  const glm::mat4 light_clip = frame.clip();
  ensure_edge_map(s, n, GL_RGBA32F);
  GLuint p = program(s, {"esm_quad.vert", "esm_edges.frag"}, error);
  if (!p) return false;
  const float texels = 2.5f;  // quad reach beyond the edge, in texels
  set(p, "u_extrude_scale", 2.0f * texels / (float(n) * std::fabs(frame.proj[0][0])));
  set(p, "u_planes", 2);
  set(p, "u_depth", 1);
  set(p, "u_map_size", float(n));
  timer.begin("extended map quads");
  glBindFramebuffer(GL_FRAMEBUFFER, s.edge_map.fbo);
  glViewport(0, 0, n, n);
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(s.edge_map.fbo, GL_COLOR, 0, zero);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_MAX);  // 000 Sect. 4.1: MAX of the inverted distance and of the edge depth
  glBindTextureUnit(1, s.shadow_map.depth);
  glBindSampler(1, depth_sampler(s));
  glUseProgram(p);
  for (const Caster& c : s.casters) {
    set(p, "u_light_view_proj", at(glm::dmat4(light_clip), c.origin));
    set(p, "u_light", local_light(c, light.position));
    glBindTextureUnit(2, c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glBindSampler(1, 0);
  timer.end();
  return true;
}

// The shared shading pass: scene.vert + shade.frag + the technique's lookup shader.
GLuint shading_program(State& s, const std::string& lookup, const View& view, const glm::dmat4& view_proj,
                       const LightSetup& light, Output output, std::string& error) {
  GLuint p = program(s, {"scene.vert", "shade.frag", lookup}, error);
  if (!p) return 0;
  set(p, "u_view_proj", at(view_proj, s.origin));
  set(p, "u_view", at(glm::lookAt(glm::dvec3(view.eye), glm::dvec3(view.target), glm::dvec3(view.up)), s.origin));
  set(p, "u_far", view.far_plane);
  set(p, "u_light", glm::vec4(glm::dvec3(light.position) - s.origin * double(light.position.w), light.position.w));
  set(p, "u_spot_direction", glm::normalize(light.spot_direction));
  set(p, "u_spot_cos", light.spot && light.position.w != 0 ? std::cos(glm::radians(light.spot_angle_deg)) : -2.0f);
  set(p, "u_output", output == Output::Mask ? 1 : 0);
  set(p, "u_ambient_only", 0);
  return p;
}

// Stencil shadow volumes (004; geom/shadow_volume.h): the volume of every caster,
// depth-fail (sides and caps) or depth-pass (sides), per caster.
bool volume_pass(State& s, const View& view, const glm::dmat4& view_proj, const LightSetup& light, Technique t,
                 float near_radius, PassTimer& timer, std::string& error) {
  GLuint p = program(s, {"shadow_volume.vert", "volume.frag"}, error);
  if (!p) return false;
  set(p, "u_planes", 2);
  bool any_exact = false;
  for (const Caster& c : s.casters) any_exact = any_exact || light_volume(c, light.position);
  timer.begin(any_exact ? "stencil volumes (exact for this static light)" : "stencil volumes");
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glStencilMask(0xff);
  glDepthMask(GL_FALSE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_DEPTH_CLAMP);
  glDepthFunc(GL_LESS);
  glUseProgram(p);
  for (const Caster& c : s.casters) {
    const bool zfail = t == Technique::SvZFail ||
                       (t == Technique::Sv && camera_may_be_in_volume(c, view.eye, near_radius, light.position));
    const Caster::LightVolume* exact = light_volume(c, light.position);
    const glm::dvec4 l = exact ? exact->light : glm::dvec4(light.position);
    set(p, "u_view_proj", at(view_proj, c.origin));
    set(p, "u_light", local_light(c, l));
    glBindTextureUnit(2, exact ? GLuint(exact->planes) : GLuint(c.sv_planes));
    if (zfail) {  // back faces increment, front faces decrement where the depth test fails
      glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
      glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
    } else {  // front faces increment, back faces decrement where it passes
      glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
      glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    }
    set(p, "u_caps", 0);
    glBindVertexArray(exact ? GLuint(exact->sides_vao) : GLuint(c.sides_vao));
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, exact ? exact->side_count : c.side_count);
    if (zfail) {
      set(p, "u_caps", 1);
      glBindVertexArray(exact ? GLuint(exact->caps_vao) : GLuint(c.caps_vao));
      glDrawArraysInstanced(GL_TRIANGLES, 0, 6, exact ? exact->cap_count : c.cap_count);
    }
  }
  glDisable(GL_DEPTH_CLAMP);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  timer.end();
  return true;
}

// The focused light matrix of psm / lispsm / uniform (geom/focus.h), and H.
geom::FocusResult focus(const State& s, const View& view, float aspect, const LightSetup& light,
                        geom::FocusMethod method, bool faces = false) {
  const double eye[3] = {view.eye.x, view.eye.y, view.eye.z}, target[3] = {view.target.x, view.target.y, view.target.z},
               up[3] = {view.up.x, view.up.y, view.up.z};
  const geom::FocusCamera camera =
      geom::focus_camera_look_at(eye, target, up, view.fovy_deg, aspect, view.near_plane, view.far_plane);
  geom::FocusLight l;
  const glm::vec3 L(light.position);
  if (light.position.w == 0) {
    l.type = geom::FocusLightType::Directional;
    for (int k = 0; k < 3; ++k) l.direction[k] = -L[k];
  } else {
    l.type = light.spot ? geom::FocusLightType::Spot : geom::FocusLightType::Point;
    for (int k = 0; k < 3; ++k) l.position[k] = L[k], l.direction[k] = light.spot_direction[k];
    l.spot_angle = glm::radians(double(light.spot_angle_deg));
  }
  geom::FocusBox box;
  for (int k = 0; k < 3; ++k) box.min[k] = s.scene_lo[k], box.max[k] = s.scene_hi[k];
  geom::FocusOptions options;
  options.method = method;
  options.faces = faces;  // H's faces only for the inspection wireframe
  geom::FocusResult result;
  geom::compute_focus(camera, l, box, options, result);
  return result;
}

glm::mat4 to_mat4(const double m[16]) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = float(m[c * 4 + r]);
  return out;
}

// Inspection overlay: topology problems of the mesh and the silhouette quads of
// the current light, drawn over the shaded frame.
bool inspection_pass(State& s, const View& view, const glm::dmat4& view_proj, const LightSetup& light,
                     geom::FocusMethod method, int w, int h, PassTimer& timer, std::string& error) {
  GLuint lines = program(s, {"inspect.vert", "inspect.frag"}, error);
  GLuint quads = lines ? program(s, {"esm_quad.vert", "inspect.frag"}, error) : 0;
  if (!quads) return false;
  timer.begin("inspection");
  glDisable(GL_STENCIL_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_POLYGON_OFFSET_LINE);
  glPolygonOffset(-1.0f, -4.0f);
  const glm::vec4 colours[4] = {{1.0f, 0.85f, 0.1f, 1}, {1.0f, 0.1f, 0.1f, 1}, {0.9f, 0.2f, 1.0f, 1}, {0.1f, 0.9f, 1.0f, 1}};
  glUseProgram(lines);
  set(lines, "u_matrix", glm::mat4(view_proj));
  for (const Caster& c : s.casters)
    for (int k = 0; k < 4; ++k) {
      set(lines, "u_colour", colours[k]);
      glBindVertexArray(c.lines_vao);
      glDrawArrays(GL_LINES, c.line_first[k], c.line_count[k]);
    }
  // Silhouette quads of the current light, extruded in the camera's clip space
  // (about 3 pixels wide); only the quads that open for this light have area.
  glUseProgram(quads);
  set(quads, "u_colour", glm::vec4(1.0f, 0.45f, 0.0f, 1));
  set(quads, "u_planes", 2);
  set(quads, "u_extrude_scale", 2.0f * 3.0f / (float(std::max(w, h)) * std::fabs(float(view_proj[1][1])) + 1e-30f));
  for (const Caster& c : s.casters) {
    set(quads, "u_light_view_proj", at(view_proj, c.origin));
    set(quads, "u_light", local_light(c, light.position));
    glBindTextureUnit(2, c.esm_planes);
    glBindVertexArray(c.esm_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, c.esm_count);
  }
  // The focus body H of the focused shadow map (geom/focus.h), as a wireframe
  // drawn over everything.
  const geom::FocusResult f = focus(s, view, float(w) / float(h), light, method, true);
  std::vector<float> edges;
  size_t at = 0;
  for (uint32_t n : f.face_sizes) {
    for (uint32_t k = 0; k < n && at + n <= f.face_indices.size(); ++k)
      for (uint32_t v : {f.face_indices[at + k], f.face_indices[at + (k + 1) % n]})
        if (size_t(v) * 3 + 2 < f.vertices.size())
          edges.insert(edges.end(), {float(f.vertices[3 * size_t(v)]), float(f.vertices[3 * size_t(v) + 1]),
                                     float(f.vertices[3 * size_t(v) + 2])});
    at += n;
  }
  Buffer buffer;
  VertexArray vao;
  upload(buffer, edges.data(), edges.size() * sizeof(float), "focus body H edges");
  glCreateVertexArrays(1, &vao.id);
  glVertexArrayVertexBuffer(vao, 0, buffer, 0, 3 * sizeof(float));
  attribute(vao, 0, 3, GL_FLOAT, 0, false);
  label(GL_VERTEX_ARRAY, vao, "focus body H");
  glDisable(GL_DEPTH_TEST);
  glUseProgram(lines);
  set(lines, "u_colour", glm::vec4(0.3f, 1.0f, 0.3f, 1));
  glBindVertexArray(vao);
  glDrawArrays(GL_LINES, 0, GLsizei(edges.size() / 3));
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_POLYGON_OFFSET_LINE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  timer.end();
  return true;
}

bool needs_casters(const FrameSettings& fs) {
  switch (fs.technique) {
    case Technique::Esm:
    case Technique::Edsm:
    case Technique::Sv:
    case Technique::SvZPass:
    case Technique::SvZFail:
      return true;
    default:
      return fs.inspect;
  }
}

// Draws one frame into the framebuffer `fbo` of w x h.
bool draw_frame(State& s, const View& view, const LightSetup& light, const FrameSettings& fs, GLuint fbo, int w,
                int h, PassTimer& timer, std::string& error) {
  const int n = std::clamp(fs.shadow_map_size, 16, 16384);
  const float aspect = float(w) / float(h);
  const glm::mat4 camera_proj = glm::infinitePerspective(glm::radians(view.fovy_deg), aspect, view.near_plane);
  const glm::dmat4 view_proj =
      glm::dmat4(camera_proj) * glm::lookAt(glm::dvec3(view.eye), glm::dvec3(view.target), glm::dvec3(view.up));
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  if (s.baked) {
    const bool missing = ((fs.technique == Technique::Esm || fs.inspect) && !s.baked_esm) ||
                         (fs.technique == Technique::Edsm && !s.baked_adjacency) ||
                         ((fs.technique == Technique::Sv || fs.technique == Technique::SvZPass || fs.technique == Technique::SvZFail) && !s.baked_volume);
    if (missing) {
      error = std::string("the baked file has no buffers for ") + (fs.inspect ? "inspection" : technique_name(fs.technique)) +
              " (bake it with ESM quads, the shadow volume and adjacency)";
      return false;
    }
  }
  if (needs_casters(fs) && !s.casters_built) {
    timer.begin("silhouette buffers (bake, once)");
    const bool ok = build_casters(s, error);
    timer.end();
    if (!ok) return false;
  }

  std::string lookup = "lookup_none.frag";
  GLuint shadow_texture = 0, second_texture = 0;
  LightFrame frame;
  Technique t = fs.technique;
  // Focused maps: the light matrix of geom/focus.h; a point light among the
  // receivers cannot be covered by one map, and an engine renders a cube map
  // for it instead (FocusResult::needs_cube_map).
  const bool focused = t == Technique::Psm || t == Technique::Lispsm || t == Technique::Uniform;
  geom::FocusResult focus_result;
  if (focused) {
    timer.begin("focus (CPU)");
    focus_result = focus(s, view, aspect, light,
                         t == Technique::Psm      ? geom::FocusMethod::Psm
                         : t == Technique::Lispsm ? geom::FocusMethod::Lispsm
                                                  : geom::FocusMethod::Uniform);
    timer.end();
    if (focus_result.needs_cube_map) t = Technique::Cube;  // the pass is then named "cube map (...)"
  }
  const bool volumes = t == Technique::Sv || t == Technique::SvZPass || t == Technique::SvZFail;
  switch (t) {
    case Technique::Ssm:
    case Technique::Pcf:
    case Technique::Esm:
    case Technique::Edsm:
    case Technique::Psm:
    case Technique::Lispsm:
    case Technique::Uniform: {
      frame = light_frame(s, light);
      if (focused) frame.proj = to_mat4(focus_result.matrix), frame.view = glm::mat4(1);
      const float slope = t == Technique::Pcf ? 3.5f : focused ? 3.0f : 1.5f;  // pcf: taps 1 texel away, bilinear: 2
      if (!depth_map_pass(s, frame.clip(), n, slope, timer, error)) return false;
      if (t == Technique::Edsm && !edsm_pass(s, frame.clip(), n, timer, error)) return false;
      if (t == Technique::Esm && !esm_pass(s, frame, light, n, timer, error)) return false;
      const GLint filter = t == Technique::Ssm ? GL_NEAREST : GL_LINEAR;
      glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MIN_FILTER, filter);
      glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MAG_FILTER, filter);
      shadow_texture = s.shadow_map.depth;
      second_texture = t == Technique::Edsm || t == Technique::Esm ? GLuint(s.edge_map.color) : 0;
      lookup = t == Technique::Edsm ? "lookup_edsm.frag" : t == Technique::Esm ? "lookup_esm.frag" : "lookup_shadow_map.frag";
      break;
    }
    case Technique::Cube: {
      if (light.position.w == 0) {
        error = "technique cube needs a point or spot light (--light X,Y,Z,1)";
        return false;
      }
      ensure_cube(s, n);
      const glm::vec3 L(light.position);
      const float d = glm::length(glm::vec3(s.bounds) - L), r = s.bounds.w;
      const float near_plane = std::max(r * 1e-3f, (d - r) * 0.5f), far_plane = (d + r) * 1.01f;
      // The six faces, GL order +X -X +Y -Y +Z -Z (geom/focus.h, seed 003).
      const double position[3] = {L.x, L.y, L.z};
      double faces[6][16];
      geom::focus_cube_faces(position, near_plane, far_plane, faces);
      GLuint p = program(s, {"cube_distance.vert", "cube_distance.geom", "cube_distance.frag"}, error);
      if (!p) return false;
      for (int f = 0; f < 6; ++f) {
        const std::string name = "u_face[" + std::to_string(f) + "]";
        set(p, name.c_str(), at(glm::make_mat4(faces[f]), s.origin));
      }
      set(p, "u_light_position", glm::vec3(glm::dvec3(L) - s.origin));
      timer.begin(focused ? "cube map (focus: point light among the receivers)" : "cube map");
      glBindFramebuffer(GL_FRAMEBUFFER, s.cube.fbo);
      glViewport(0, 0, n, n);
      const float far_value = 3.0e38f;
      glClearNamedFramebufferfv(s.cube.fbo, GL_COLOR, 0, &far_value);
      glClear(GL_DEPTH_BUFFER_BIT);
      glUseProgram(p);
      draw_scene(s);
      timer.end();
      shadow_texture = s.cube.color;
      lookup = "lookup_cube.frag";
      break;
    }
    case Technique::Sv:
    case Technique::SvZPass:
    case Technique::SvZFail:
      break;
    default:
      error = std::string("technique ") + technique_name(t) + " is not available in this build";
      return false;
  }

  GLuint p = shading_program(s, lookup, view, view_proj, light, fs.output, error);
  if (!p) return false;
  set(p, "u_light_matrix", at(glm::dmat4(frame.clip()), s.origin));
  set(p, "u_shadow_map", 0);
  set(p, "u_distance_map", 1);
  set(p, "u_edge_map", 1);
  set(p, "u_pcf", t == Technique::Pcf ? 1 : 0);
  set(p, "u_cube_bias", 0.97f);             // 003, 12.3.7: fDistSquared * DepthBias
  set(p, "u_cube_filter", 1.0f / float(n));  // 003, 12.4: tap offsets of about one texel
  glBindTextureUnit(0, shadow_texture);
  glBindTextureUnit(1, second_texture);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, w, h);
  const float grey = 0.5f;  // mask: 128 where no geometry is
  if (fs.output == Output::Mask) glClearColor(grey, grey, grey, 1.0f);
  else glClearColor(0.18f, 0.2f, 0.24f, 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glUseProgram(p);
  if (volumes) {
    // 1. depth and the unlit colour. The scene is pulled a little towards the
    //    camera (004: polygon offset) so that volume faces lying on a surface
    //    (the near cap of a lit face, side quads at its edges) count as behind
    //    it: a point is never shadowed by the face it lies on.
    timer.begin("depth + ambient");
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, -8.0f);
    set(p, "u_ambient_only", 1);
    draw_scene(s);
    timer.end();
    // 2. stencil counts.
    const float near_half_h = view.near_plane * std::tan(glm::radians(view.fovy_deg) * 0.5f);
    const float near_radius = near_half_h * std::sqrt(1.0f + aspect * aspect);
    glDisable(GL_POLYGON_OFFSET_FILL);
    if (!volume_pass(s, view, view_proj, light, t, near_radius, timer, error)) return false;
    // 3. lit where the count is zero.
    timer.begin("lit shading");
    glEnable(GL_POLYGON_OFFSET_FILL);  // the same offset as pass 1: GL_EQUAL holds
    glUseProgram(p);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDepthFunc(GL_EQUAL);
    set(p, "u_ambient_only", 0);
    draw_scene(s);
    glDepthFunc(GL_LESS);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    timer.end();
  } else {
    timer.begin("shading");
    draw_scene(s);
    timer.end();
  }
  glBindTextureUnit(0, 0);
  glBindTextureUnit(1, 0);
  const geom::FocusMethod method = t == Technique::Lispsm    ? geom::FocusMethod::Lispsm
                                   : t == Technique::Uniform ? geom::FocusMethod::Uniform
                                                             : geom::FocusMethod::Psm;
  if (fs.inspect && fs.output != Output::Mask && !inspection_pass(s, view, view_proj, light, method, w, h, timer, error)) return false;
  return true;
}

}  // namespace

StatePtr create_state(const geom::Scene& scene, const std::string& shader_dir, std::string& error) {
  StatePtr s(new State);
  s->shader_dir = shader_dir;
  s->scene.positions = scene.positions;
  s->scene.indices = scene.indices;
  s->scene.sources = scene.sources;
  s->scene.lights = scene.lights;
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  s->renderer = renderer ? renderer : "?";
  const bool software = std::strstr(s->renderer.c_str(), "llvmpipe") || std::strstr(s->renderer.c_str(), "softpipe") ||
                        std::strstr(s->renderer.c_str(), "Software");
  s->gpu_timers = !software;
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    error = "OpenGL 4.5 needed, the context has " + std::to_string(major) + "." + std::to_string(minor);
    return nullptr;
  }
  // Non-indexed triangles with their face normal (flat shading, exact per face).
  std::vector<float> vertices;
  const size_t tris = scene.triangle_count(), nv = scene.vertex_count();
  vertices.reserve(tris * 18);
  glm::dvec3 dlo(1e300), dhi(-1e300);
  for (size_t i = 0; i < 3 * tris; ++i) {
    const uint32_t v = scene.indices[i];
    if (v >= nv) continue;
    const glm::dvec3 p(scene.positions[3 * size_t(v)], scene.positions[3 * size_t(v) + 1], scene.positions[3 * size_t(v) + 2]);
    dlo = glm::min(dlo, p), dhi = glm::max(dhi, p);
  }
  if (tris) s->origin = (dlo + dhi) * 0.5;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (size_t t = 0; t < tris; ++t) {
    glm::vec3 p[3];
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = scene.indices[3 * t + k];
      if (i >= nv) ok = false;
      else p[k] = glm::vec3(scene.positions[3 * i], scene.positions[3 * i + 1], scene.positions[3 * i + 2]);
    }
    if (!ok) {
      error = "triangle " + std::to_string(t) + " has an index out of range";
      return nullptr;
    }
    glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const float len = glm::length(n);
    n = len > 0 ? n / len : glm::vec3(0);
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 local(glm::dvec3(p[k]) - s->origin);
      vertices.insert(vertices.end(), {local.x, local.y, local.z, n.x, n.y, n.z});
      lo = glm::min(lo, p[k]), hi = glm::max(hi, p[k]);
    }
  }
  if (tris) {
    s->bounds = glm::vec4((lo + hi) * 0.5f, std::max(glm::length(hi - lo) * 0.5f, 1e-3f));
    s->scene_lo = lo, s->scene_hi = hi;
  }
  s->scene_vertices = GLsizei(tris * 3);
  glCreateBuffers(1, &s->scene_vbo.id);
  glNamedBufferStorage(s->scene_vbo, GLsizeiptr(std::max<size_t>(vertices.size(), 1) * sizeof(float)),
                       vertices.empty() ? nullptr : vertices.data(), 0);
  label(GL_BUFFER, s->scene_vbo, "scene triangles (position, face normal)");
  glCreateVertexArrays(1, &s->scene_vao.id);
  glVertexArrayVertexBuffer(s->scene_vao, 0, s->scene_vbo, 0, 6 * sizeof(float));
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(s->scene_vao, a);
    glVertexArrayAttribFormat(s->scene_vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
    glVertexArrayAttribBinding(s->scene_vao, a, 0);
  }
  label(GL_VERTEX_ARRAY, s->scene_vao, "scene");
  return s;
}

StatePtr create_state_baked(const void* bytes, size_t size, const std::string& shader_dir, geom::Scene& scene,
                            std::string& error) {
  namespace gb = geom::baked;
  gb::Reader reader;
  if (!reader.open(bytes, size)) {
    error = reader.error();
    return nullptr;
  }
  const gb::Section* positions = reader.find(gb::SectionType::Positions);
  const gb::Section* indices = reader.find(gb::SectionType::Indices);
  if (!positions || !indices || !positions->as<float[3]>() || !indices->as<uint32_t>() || indices->count % 3) {
    error = "no usable positions and indices sections (bake with both)";
    return nullptr;
  }
  scene = geom::Scene();
  const float* p = positions->as<float[3]>()[0];
  scene.positions.assign(p, p + 3 * positions->count);
  scene.indices.assign(indices->as<uint32_t>(), indices->as<uint32_t>() + indices->count);
  for (uint32_t i : scene.indices)
    if (i >= positions->count) {
      error = "an index of the indices section is out of range";
      return nullptr;
    }
  scene.sources.resize(scene.triangle_count());
  if (const gb::Section* lights = reader.find(gb::SectionType::Lights); lights && lights->as<double[4]>())
    for (uint64_t i = 0; i < lights->count; ++i) {
      const double* l = lights->as<double[4]>()[i];
      geom::Light light;
      light.type = l[3] == 0 ? geom::LightType::Directional : geom::LightType::Point;
      for (int k = 0; k < 3; ++k) {
        light.position[k] = float(l[3] == 0 ? 0 : l[k] / l[3]);
        light.direction[k] = float(l[3] == 0 ? -l[k] : 0);
      }
      scene.lights.push_back(light);
    }
  StatePtr s = create_state(scene, shader_dir, error);
  if (!s) return nullptr;
  // The one caster: the file's buffers as they lie.
  CasterSource src;
  src.welded = p, src.welded_count = positions->count;
  src.indices = scene.indices.data(), src.triangle_count = scene.triangle_count();
  if (const gb::Section* frame = reader.find(gb::SectionType::Frame); frame && frame->as<double[3]>() && frame->count == 1)
    src.origin = glm::dvec3(frame->as<double[3]>()[0][0], frame->as<double[3]>()[0][1], frame->as<double[3]>()[0][2]);
  const gb::Section* adjacency = reader.find(gb::SectionType::AdjacencyIndices);
  s->baked_adjacency = adjacency && adjacency->as<uint32_t>() && adjacency->count == 2 * indices->count;
  if (s->baked_adjacency) src.adjacency = adjacency->as<uint32_t>(), src.adjacency_count = adjacency->count;
  const gb::Section* esm = reader.find(gb::SectionType::EsmQuads);
  const gb::Section* esm_planes = reader.find(gb::SectionType::EsmPlanes);
  s->baked_esm = esm && esm_planes && esm->as<geom::EsmQuad>() && esm_planes->as<float[4]>();
  if (s->baked_esm) {
    src.esm = esm->as<geom::EsmQuad>(), src.esm_count = esm->count;
    src.esm_planes = esm_planes->as<float[4]>()[0], src.esm_plane_count = esm_planes->count;
  }
  const gb::Section* sides = reader.find(gb::SectionType::VolumeSides);
  const gb::Section* caps = reader.find(gb::SectionType::VolumeCaps);
  const gb::Section* planes = reader.find(gb::SectionType::VolumePlanes);
  s->baked_volume = sides && caps && planes && sides->as<geom::SvSide>() && caps->as<geom::SvCap>() && planes->as<float[4]>();
  if (s->baked_volume) {
    src.sides = sides->as<geom::SvSide>(), src.side_count = sides->count;
    src.caps = caps->as<geom::SvCap>(), src.cap_count = caps->count;
    src.volume_planes = planes->as<float[4]>()[0], src.volume_plane_count = planes->count;
  }
  if (const gb::Section* lights = reader.find(gb::SectionType::Lights); lights && lights->as<double[4]>())
    for (uint32_t i = 0; i < lights->count; ++i) {
      const gb::Section* ls = reader.find(gb::SectionType::LightSides, i);
      const gb::Section* lc = reader.find(gb::SectionType::LightCaps, i);
      const gb::Section* lp = reader.find(gb::SectionType::LightPlanes, i);
      if (!ls || !lc || !lp || !ls->as<geom::SvSide>() || !lc->as<geom::SvCap>() || !lp->as<float[4]>()) continue;
      const double* l = lights->as<double[4]>()[i];
      src.light_volumes.push_back({glm::dvec4(l[0], l[1], l[2], l[3]), ls->as<geom::SvSide>(), ls->count,
                                   lc->as<geom::SvCap>(), lc->count, lp->as<float[4]>()[0], lp->count});
    }
  if (!upload_caster(*s, src, error)) return nullptr;
  s->baked = true;
  s->casters_built = true;
  return s;
}

bool render(State& s, const View& view, const LightSetup& light, const FrameSettings& fs, geom::PngImage& image,
            std::vector<PassTime>& times, std::string& error) {
  if (view.width <= 0 || view.height <= 0 || view.width > 16384 || view.height > 16384) {
    error = "image size out of range";
    return false;
  }
  ensure_camera_target(s, view.width, view.height);
  PassTimer timer;
  timer.gpu = s.gpu_timers;
  timer.out = &times;
  if (!draw_frame(s, view, light, fs, s.camera.fbo, view.width, view.height, timer, error)) return false;
  timer.collect();
  std::vector<uint8_t> rgba(size_t(view.width) * view.height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, s.camera.fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, view.width, view.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  const int channels = fs.output == Output::Mask ? 1 : 3;
  image.width = view.width, image.height = view.height, image.channels = channels;
  image.pixels.resize(size_t(view.width) * view.height * channels);
  for (int y = 0; y < view.height; ++y)  // GL's first row is the bottom one
    for (int x = 0; x < view.width; ++x)
      for (int c = 0; c < channels; ++c)
        image.pixels[(size_t(y) * view.width + x) * channels + c] =
            rgba[(size_t(view.height - 1 - y) * view.width + x) * 4 + c];
  GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    error = "OpenGL error 0x" + [&] { std::ostringstream o; o << std::hex << err; return o.str(); }();
    return false;
  }
  return true;
}

bool render_to_window(State& s, const View& view, const LightSetup& light, const FrameSettings& fs, int width,
                      int height, std::vector<PassTime>& times, std::string& error) {
  PassTimer timer;
  timer.gpu = s.gpu_timers;
  timer.out = &times;
  if (!draw_frame(s, view, light, fs, 0, width, height, timer, error)) return false;
  timer.collect();
  return true;
}

std::string renderer_name(State& s) { return s.renderer; }
std::string timing_kind(State& s) {
  return s.gpu_timers ? "GPU timer queries" : "wall time around glFinish (software renderer)";
}
glm::vec4 scene_bounds(const State& s) { return s.bounds; }

View default_view(const State& s, int width, int height) {
  View v;
  v.width = width, v.height = height;
  v.target = glm::vec3(s.bounds) - glm::vec3(0, s.bounds.w * 0.2f, 0);
  v.eye = v.target + glm::normalize(glm::vec3(0.45f, 0.5f, 1.0f)) * (s.bounds.w * 0.9f);
  v.fovy_deg = 50;
  v.near_plane = s.bounds.w * 0.01f;
  v.far_plane = s.bounds.w * 100.0f;
  return v;
}

}  // namespace viewer
