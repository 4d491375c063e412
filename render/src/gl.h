// gl.h (private to render/): the GL helpers every technique file uses: names
// that delete themselves, a label on every object, render targets, programs
// linked from shaders/ files and cached by file list, uniforms, pass timing.
#pragma once
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <chrono>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/render.h"

namespace render {

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
void delete_buffer(GLuint id);
void delete_texture(GLuint id);
void delete_framebuffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_program(GLuint id);
void delete_query(GLuint id);
void delete_sampler(GLuint id);
using Buffer = GlName<delete_buffer>;
using Texture = GlName<delete_texture>;
using Framebuffer = GlName<delete_framebuffer>;
using VertexArray = GlName<delete_vertex_array>;
using Program = GlName<delete_program>;
using Query = GlName<delete_query>;
using Sampler = GlName<delete_sampler>;

void label(GLenum kind, GLuint id, const std::string& name);

// A render target: colour texture (optional), depth(-stencil) texture (optional).
struct Target {
  Framebuffer fbo;
  Texture color, depth;
  int width = 0, height = 0;
};

// The time of each pass: GPU timer queries, or wall time around glFinish; and
// its pipeline statistics where the context has them (pass_counters.h).
struct CounterQueries;
struct PassTimer {
  bool gpu = false;
  int counters = -1;  // pipeline statistics: -1 not yet asked, 0 none, 1 queried per pass
  struct Pending {
    PassTime time;
    Query elapsed;
    std::shared_ptr<CounterQueries> stats;
  };
  std::vector<Pending> pending;
  std::vector<PassTime>* out = nullptr;
  std::chrono::steady_clock::time_point start;
  void begin(const std::string& name);
  void end();
  void collect();  // appends every pass, in order, to *out
};

// Programs made of shaders/ files (stage from the extension: .vert .geom
// .frag .comp; several files of one stage are linked together), cached by name.
struct Programs {
  std::string shader_dir;
  std::map<std::string, Program> cache;
};
GLuint program(Programs& programs, const std::vector<std::string>& files, std::string& error);

void set(GLuint p, const char* name, const glm::mat4& m);
void set(GLuint p, const char* name, const glm::vec4& v);
void set(GLuint p, const char* name, const glm::vec3& v);
void set(GLuint p, const char* name, const glm::vec2& v);
void set(GLuint p, const char* name, float v);
void set(GLuint p, const char* name, int v);

// An immutable buffer of `bytes` (at least 16), filled from `data`.
void upload(Buffer& buffer, const void* data, size_t bytes, const char* name);
// A texture buffer of RGBA32F planes over its own buffer.
void plane_texture(Texture& texture, Buffer& buffer, const float* planes, size_t plane_count, const char* name);
// Vertex attribute `location` of binding 0.
void attribute(GLuint vao, GLuint location, GLint size, GLenum type, GLuint offset, bool integer,
               bool normalized = false);

// A world matrix applied to points of a local frame at `origin`, composed in
// double so that large translations cancel before the result is rounded.
glm::mat4 at(const glm::dmat4& m, const glm::dvec3& origin);

}  // namespace render
