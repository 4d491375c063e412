// geomview's renderer: the state struct, the passes of every technique, and the
// shared shading pass. References for each pass are in the shaders' headers:
//   shadow map + slope-scaled bias, PCF ........ shaders/lookup_shadow_map.frag
//   omnidirectional cube map (003, 12.3-12.4) .. shaders/cube_distance.*, lookup_cube.frag
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

namespace viewer {
namespace {

const char* const kTechniqueNames[] = {"ssm", "pcf", "esm", "edsm", "sv", "sv-zpass", "sv-zfail",
                                       "cube", "psm", "lispsm", "uniform"};

bool technique_available(Technique t) {
  switch (t) {
    case Technique::Ssm:
    case Technique::Pcf:
    case Technique::Cube:
      return true;
    default:
      return false;
  }
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
  // Render targets, re-created when their size changes.
  Target camera, shadow_map, cube;
  std::map<std::string, Program> programs;
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

glm::vec3 any_perpendicular(glm::vec3 d) {
  return std::fabs(d.y) < 0.9f * glm::length(d) ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

// World -> light clip matrix of a single shadow map covering the scene's bounding
// sphere: orthographic for a directional light, perspective for a point light
// (aimed at the sphere) and for a spot light (aimed along its axis, the cone's
// full angle as field of view).
glm::mat4 light_matrix(const State& s, const LightSetup& light) {
  const glm::vec3 c(s.bounds), L(light.position);
  const float r = std::max(s.bounds.w, 1e-6f);
  if (light.position.w == 0) {
    const glm::vec3 dir = glm::normalize(L);
    const glm::mat4 view = glm::lookAt(c + dir * (2 * r), c, any_perpendicular(dir));
    return glm::ortho(-r, r, -r, r, r * 0.5f, r * 3.5f) * view;
  }
  const float d = glm::length(c - L);
  const float near_plane = std::max(d - r, r * 1e-3f), far_plane = d + r;
  if (light.spot) {
    const glm::vec3 axis = glm::normalize(light.spot_direction);
    const float fov = std::min(2 * glm::radians(light.spot_angle_deg) * 1.02f, glm::radians(170.0f));
    return glm::perspective(fov, 1.0f, near_plane, far_plane) * glm::lookAt(L, L + axis, any_perpendicular(axis));
  }
  const glm::vec3 axis = d > 1e-6f * r ? (c - L) / d : glm::vec3(0, -1, 0);
  const float fov = d > r ? std::min(2 * std::asin(r / d) * 1.02f, glm::radians(170.0f)) : glm::radians(170.0f);
  return glm::perspective(fov, 1.0f, near_plane, far_plane) * glm::lookAt(L, L + axis, any_perpendicular(axis));
}

void draw_scene(const State& s) {
  glBindVertexArray(s.scene_vao);
  glDrawArrays(GL_TRIANGLES, 0, s.scene_vertices);
}

// The shared shading pass: scene.vert + shade.frag + the technique's lookup shader.
GLuint shading_program(State& s, const std::string& lookup, const View& view, const glm::mat4& view_proj,
                       const LightSetup& light, Output output, std::string& error) {
  GLuint p = program(s, {"scene.vert", "shade.frag", lookup}, error);
  if (!p) return 0;
  set(p, "u_view_proj", view_proj);
  set(p, "u_view", glm::lookAt(view.eye, view.target, view.up));
  set(p, "u_far", view.far_plane);
  set(p, "u_light", light.position);
  set(p, "u_spot_direction", glm::normalize(light.spot_direction));
  set(p, "u_spot_cos", light.spot && light.position.w != 0 ? std::cos(glm::radians(light.spot_angle_deg)) : -2.0f);
  set(p, "u_output", output == Output::Mask ? 1 : 0);
  set(p, "u_ambient_only", 0);
  return p;
}

// Draws one frame into the framebuffer `fbo` of w x h.
bool draw_frame(State& s, const View& view, const LightSetup& light, const FrameSettings& fs, GLuint fbo, int w,
                int h, PassTimer& timer, std::string& error) {
  const int n = std::clamp(fs.shadow_map_size, 16, 16384);
  const glm::mat4 camera_proj =
      glm::infinitePerspective(glm::radians(view.fovy_deg), float(w) / float(h), view.near_plane);
  const glm::mat4 view_proj = camera_proj * glm::lookAt(view.eye, view.target, view.up);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

  std::string lookup;
  GLuint shadow_texture = 0;
  glm::mat4 light_clip(1);
  switch (fs.technique) {
    case Technique::Ssm:
    case Technique::Pcf: {
      ensure_shadow_map(s, n);
      light_clip = light_matrix(s, light);
      GLuint p = program(s, {"depth.vert", "depth.frag"}, error);
      if (!p) return false;
      set(p, "u_matrix", light_clip);
      timer.begin("shadow map");
      glBindFramebuffer(GL_FRAMEBUFFER, s.shadow_map.fbo);
      glViewport(0, 0, n, n);
      glClear(GL_DEPTH_BUFFER_BIT);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1.5f, 4.0f);  // slope-scaled depth bias (001, Sect. 1.2; 004, glPolygonOffset)
      glUseProgram(p);
      draw_scene(s);
      glDisable(GL_POLYGON_OFFSET_FILL);
      timer.end();
      const GLint filter = fs.technique == Technique::Pcf ? GL_LINEAR : GL_NEAREST;
      glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MIN_FILTER, filter);
      glTextureParameteri(s.shadow_map.depth, GL_TEXTURE_MAG_FILTER, filter);
      shadow_texture = s.shadow_map.depth;
      lookup = "lookup_shadow_map.frag";
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
      const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, near_plane, far_plane);
      // GL cube face order +X -X +Y -Y +Z -Z, with the face orientations of the GL spec.
      const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
      GLuint p = program(s, {"cube_distance.vert", "cube_distance.geom", "cube_distance.frag"}, error);
      if (!p) return false;
      for (int f = 0; f < 6; ++f) {
        const std::string name = "u_face[" + std::to_string(f) + "]";
        set(p, name.c_str(), proj * glm::lookAt(L, L + dirs[f], ups[f]));
      }
      set(p, "u_light_position", L);
      timer.begin("cube map");
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
    default:
      error = std::string("technique ") + technique_name(fs.technique) + " is not available in this build";
      return false;
  }

  GLuint p = shading_program(s, lookup, view, view_proj, light, fs.output, error);
  if (!p) return false;
  set(p, "u_light_matrix", light_clip);
  set(p, "u_shadow_map", 0);
  set(p, "u_pcf", fs.technique == Technique::Pcf ? 1 : 0);
  set(p, "u_cube_bias", 0.97f);                             // 003, 12.3.7: fDistSquared * DepthBias
  set(p, "u_cube_filter", 1.0f / float(n));                 // 003, 12.4: tap offsets of about one texel
  glBindTextureUnit(0, shadow_texture);
  timer.begin("shading");
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, w, h);
  const float background[4] = {0.5f, 0.5f, 0.5f, 1.0f};  // mask: 128 where no geometry is
  const float sky[4] = {0.18f, 0.2f, 0.24f, 1.0f};
  glClearColor(fs.output == Output::Mask ? background[0] : sky[0], fs.output == Output::Mask ? background[1] : sky[1],
               fs.output == Output::Mask ? background[2] : sky[2], 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glUseProgram(p);
  draw_scene(s);
  timer.end();
  glBindTextureUnit(0, 0);
  return true;
}

}  // namespace

StatePtr create_state(const geom::Scene& scene, const std::string& shader_dir, std::string& error) {
  StatePtr s(new State);
  s->shader_dir = shader_dir;
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
      vertices.insert(vertices.end(), {p[k].x, p[k].y, p[k].z, n.x, n.y, n.z});
      lo = glm::min(lo, p[k]), hi = glm::max(hi, p[k]);
    }
  }
  if (tris) s->bounds = glm::vec4((lo + hi) * 0.5f, std::max(glm::length(hi - lo) * 0.5f, 1e-3f));
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

}  // namespace viewer
