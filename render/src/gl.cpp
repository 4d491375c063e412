// gl.cpp: the GL helpers of gl.h.
#include "gl.h"

#include <algorithm>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <sstream>

namespace render {

void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_query(GLuint id) { glDeleteQueries(1, &id); }
void delete_sampler(GLuint id) { glDeleteSamplers(1, &id); }

void label(GLenum kind, GLuint id, const std::string& name) { glObjectLabel(kind, id, -1, name.c_str()); }

void PassTimer::begin(const std::string& name) {
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

void PassTimer::end() {
  if (gpu) {
    glEndQuery(GL_TIME_ELAPSED);
  } else {
    glFinish();
    out->push_back(
        {current, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
  }
}

void PassTimer::collect() {
  for (auto& q : queries) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(q.second, GL_QUERY_RESULT, &ns);
    out->push_back({q.first, ns * 1e-6});
  }
  queries.clear();
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
    std::string text;
    if (!read_text(dir + "/" + f, text)) {
      error = dir + "/" + f + ": cannot read the shader";
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
