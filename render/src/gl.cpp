// gl.cpp: the GL helpers of gl.h.
#include "gl.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <sstream>

#include "pass_counters.h"
#include "render/platform.h"

namespace render {

void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_query(GLuint id) { glDeleteQueries(1, &id); }
void delete_sampler(GLuint id) { glDeleteSamplers(1, &id); }

int GlLimits::max_image_width() const { return std::min({max_texture, max_renderbuffer, max_viewport[0]}); }
int GlLimits::max_image_height() const { return std::min({max_texture, max_renderbuffer, max_viewport[1]}); }

GlLimits gl_limits() {
  GlLimits l;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.max_texture);
  glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &l.max_cube_map);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &l.max_renderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, l.max_viewport);
  return l;
}

std::string gl_error_text() {
  std::string text;
  for (int n = 0; n < 16; ++n) {  // a context that lost itself reports errors forever
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    char b[96];
    std::snprintf(b, sizeof b, "%sOpenGL error 0x%x%s", text.empty() ? "" : ", ", e,
                  e == GL_OUT_OF_MEMORY ? " (GL_OUT_OF_MEMORY: out of GPU memory)" : "");
    text += b;
  }
  return text;
}

void label(GLenum kind, GLuint id, const std::string& name) { glObjectLabel(kind, id, -1, name.c_str()); }

void PassTimer::begin(const std::string& name) {
  if (counters < 0) counters = pass_counters_available() ? 1 : 0;
  pending.emplace_back();
  Pending& p = pending.back();
  p.time.pass = name;
  if (counters) {
    p.stats = std::make_shared<CounterQueries>();
    p.stats->begin();
  }
  if (gpu) {
    glCreateQueries(GL_TIME_ELAPSED, 1, &p.elapsed.id);
    glBeginQuery(GL_TIME_ELAPSED, p.elapsed);
  } else {
    glFinish();
    start = std::chrono::steady_clock::now();
  }
}

void PassTimer::end() {
  Pending& p = pending.back();
  if (gpu) {
    glEndQuery(GL_TIME_ELAPSED);
  } else {
    glFinish();
    p.time.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  if (p.stats) p.stats->end();
}

void PassTimer::collect() {
  for (Pending& p : pending) {
    if (gpu) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(p.elapsed, GL_QUERY_RESULT, &ns);
      p.time.ms = ns * 1e-6;
    }
    if (p.stats) p.time.counters = p.stats->read();
    out->push_back(p.time);
  }
  pending.clear();
}

namespace {

// A shader file as geombake opens its inputs: a regular file only (a FIFO, a
// device or a directory is refused before a byte is read, so nothing blocks or
// reads forever), at most kMaxShaderBytes, every read checked.
constexpr uint64_t kMaxShaderBytes = uint64_t(1) << 24;

bool read_text(const std::string& path, std::string& text, std::string& problem) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return problem = std::string("cannot open the shader (") + std::strerror(errno) + ")", false;
  struct stat st {};
  bool ok = ::fstat(fd, &st) == 0;
  if (!ok)
    problem = "cannot read the shader";
  else if (!S_ISREG(st.st_mode))
    ok = false, problem = "not a regular file (a directory, FIFO or device): not read";
  else if (uint64_t(st.st_size) > kMaxShaderBytes)
    ok = false, problem = "the shader is " + std::to_string(st.st_size) + " bytes, over the limit of " +
                          std::to_string(kMaxShaderBytes);
  if (ok) {
    text.assign(size_t(st.st_size), '\0');
    size_t got = 0;
    while (got < text.size()) {
      const ssize_t n = ::read(fd, &text[got], text.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += size_t(n);
    }
    char extra;
    if (got != text.size() || ::read(fd, &extra, 1) != 0)
      ok = false, problem = "cannot read the shader (its size changed)";
  }
  ::close(fd);
  return ok;
}

}  // namespace

GLuint program(Programs& programs, const std::vector<std::string>& files, std::string& error) {
  std::string key;
  for (auto& f : files) key += f + "+";
  auto it = programs.cache.find(key);
  if (it != programs.cache.end()) return it->second;
  const std::string& dir = programs.shader_dir;
  Program prog;
  prog.id = glCreateProgram();
  std::vector<GLuint> shaders;
  bool ok = true;
  for (auto& f : files) {
    std::string text, problem;
    if (!read_text(dir + "/" + f, text, problem)) {
      error = dir + "/" + f + ": " + problem;
      ok = false;
      break;
    }
    const std::string ext = f.substr(f.rfind('.') + 1);
    GLenum stage = ext == "vert"   ? GL_VERTEX_SHADER
                   : ext == "geom" ? GL_GEOMETRY_SHADER
                   : ext == "comp" ? GL_COMPUTE_SHADER
                                   : GL_FRAGMENT_SHADER;
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
      error = dir + "/" + f + ": compile error: " + log;
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
  programs.cache.emplace(key, std::move(prog));
  return id;
}

void set(GLuint p, const char* name, const glm::mat4& m) {
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, name), 1, GL_FALSE, glm::value_ptr(m));
}
void set(GLuint p, const char* name, const glm::vec4& v) {
  glProgramUniform4fv(p, glGetUniformLocation(p, name), 1, glm::value_ptr(v));
}
void set(GLuint p, const char* name, const glm::vec2& v) {
  glProgramUniform2fv(p, glGetUniformLocation(p, name), 1, glm::value_ptr(v));
}
void set(GLuint p, const char* name, const glm::vec3& v) {
  glProgramUniform3fv(p, glGetUniformLocation(p, name), 1, glm::value_ptr(v));
}
void set(GLuint p, const char* name, float v) { glProgramUniform1f(p, glGetUniformLocation(p, name), v); }
void set(GLuint p, const char* name, int v) { glProgramUniform1i(p, glGetUniformLocation(p, name), v); }

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

void attribute(GLuint vao, GLuint location, GLint size, GLenum type, GLuint offset, bool integer, bool normalized) {
  glEnableVertexArrayAttrib(vao, location);
  if (integer)
    glVertexArrayAttribIFormat(vao, location, size, type, offset);
  else
    glVertexArrayAttribFormat(vao, location, size, type, normalized ? GL_TRUE : GL_FALSE, offset);
  glVertexArrayAttribBinding(vao, location, 0);
}

glm::mat4 at(const glm::dmat4& m, const glm::dvec3& origin) {
  return glm::mat4(m * glm::translate(glm::dmat4(1), origin));
}

}  // namespace render
