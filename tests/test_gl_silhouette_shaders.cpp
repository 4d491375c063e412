// shaders/shadow_volume.vert and shaders/esm_quad.vert against their CPU
// reference (geom/extrude.h), on the GPU or Mesa llvmpipe through headless
// EGL: every instance drawn as GL_POINTS with transform feedback capturing
// gl_Position, with identity matrices. The shadow-volume corners must match
// bit for bit (the same float operations, `precise` in the shader, and a
// multiply by the identity is exact); the ESM corners within 1e-5 (the
// octahedral decode's normalize may round differently). Also checks that the
// attribute layouts documented in the headers (strides, offsets, integer
// attributes, snorm16) are the ones the shaders read.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "geom/extrude.h"
#include "silhouette_fixtures.h"

namespace {

struct Context {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string error;
  Context() {
    auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_display) display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major, minor;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor) || !eglBindAPI(EGL_OPENGL_API)) {
      error = "no surfaceless EGL display";
      return;
    }
    const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context = eglCreateContext(display, nullptr, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      error = "no OpenGL 4.5 core context";
  }
  ~Context() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A vertex-only program whose gl_Position is captured.
GLuint program(const std::string& file, std::string& log) {
  const std::string text = read_text(std::string(GEOM_SOURCE_DIR) + "/shaders/" + file);
  const char* src = text.c_str();
  GLuint vs = glCreateShader(GL_VERTEX_SHADER);
  glShaderSource(vs, 1, &src, nullptr);
  glCompileShader(vs);
  GLint ok = 0;
  char buf[4096];
  glGetShaderiv(vs, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    glGetShaderInfoLog(vs, sizeof buf, nullptr, buf);
    log = buf;
    return 0;
  }
  GLuint p = glCreateProgram();
  glAttachShader(p, vs);
  const char* varyings[] = {"gl_Position"};
  glTransformFeedbackVaryings(p, 1, varyings, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(p);
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramInfoLog(p, sizeof buf, nullptr, buf);
    log = buf;
    return 0;
  }
  glDeleteShader(vs);
  return p;
}

// Draws `instances` x `per` points from `records` (stride bytes) and returns
// the captured clip positions (4 floats each).
std::vector<float> capture(GLuint prog, const void* records, size_t bytes, GLsizei stride, GLsizei instances,
                           GLsizei per, const std::vector<float>& planes, void (*layout)(GLsizei stride)) {
  GLuint vao, vbo, tbo, tex, out;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), records, GL_STATIC_DRAW);
  layout(stride);
  glGenBuffers(1, &tbo);
  glBindBuffer(GL_TEXTURE_BUFFER, tbo);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(planes.size() * 4), planes.data(), GL_STATIC_DRAW);
  glGenTextures(1, &tex);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, tex);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, tbo);
  glUniform1i(glGetUniformLocation(prog, "u_planes"), 0);
  const size_t n = size_t(instances) * per;
  glGenBuffers(1, &out);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, out);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, GLsizeiptr(n * 16), nullptr, GL_STATIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArraysInstanced(GL_POINTS, 0, per, instances);
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  std::vector<float> result(n * 4);
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, GLsizeiptr(n * 16), result.data());
  glDeleteBuffers(1, &out);
  glDeleteTextures(1, &tex);
  glDeleteBuffers(1, &tbo);
  glDeleteBuffers(1, &vbo);
  glDeleteVertexArrays(1, &vao);
  return result;
}

void attrib(GLuint loc, GLint size, GLenum type, GLsizei stride, size_t offset, bool integer, bool normalized = false) {
  glEnableVertexAttribArray(loc);
  if (integer)
    glVertexAttribIPointer(loc, size, type, stride, reinterpret_cast<const void*>(offset));
  else
    glVertexAttribPointer(loc, size, type, normalized ? GL_TRUE : GL_FALSE, stride,
                          reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(loc, 1);
}

void side_layout(GLsizei s) {
  attrib(0, 3, GL_FLOAT, s, 0, false);
  attrib(1, 3, GL_FLOAT, s, 12, false);
  attrib(3, 1, GL_UNSIGNED_INT, s, 24, true);
  attrib(4, 1, GL_UNSIGNED_INT, s, 28, true);
}
void cap_layout(GLsizei s) {
  attrib(0, 3, GL_FLOAT, s, 0, false);
  attrib(1, 3, GL_FLOAT, s, 12, false);
  attrib(2, 3, GL_FLOAT, s, 24, false);
  attrib(3, 1, GL_UNSIGNED_INT, s, 36, true);
}
void esm_layout(GLsizei s) {
  attrib(0, 3, GL_FLOAT, s, 0, false);
  attrib(1, 3, GL_FLOAT, s, 12, false);
  attrib(2, 1, GL_UNSIGNED_INT, s, 24, true);
  attrib(3, 1, GL_UNSIGNED_INT, s, 28, true);
  attrib(4, 2, GL_SHORT, s, 32, false, true);
}

const float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

TEST(GlSilhouetteShaders, MatchTheCpuReference) {
  Context ctx;
  ASSERT_TRUE(ctx.error.empty()) << ctx.error;
  std::string log;
  const GLuint sv = program("shadow_volume.vert", log);
  ASSERT_NE(sv, 0u) << log;
  const GLuint esm = program("esm_quad.vert", log);
  ASSERT_NE(esm, 0u) << log;
  // Surfaceless EGL has no default framebuffer: draws need a complete FBO.
  GLuint fbo, rb;
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));

  std::mt19937 rng(17);
  std::normal_distribution<double> g;
  int compared = 0;
  for (const fixtures::Mesh& m : {fixtures::stack(), fixtures::bowtie(), fixtures::degenerate_box()}) {
    const fixtures::Baked b = fixtures::bake(m);
    for (int trial = 0; trial < 10; ++trial) {
      float light[4] = {float(2 * g(rng)), float(2 * g(rng)), float(2 * g(rng)), trial % 2 ? 0.0f : 1.0f};
      if (trial == 6) std::memcpy(light, b.volume.sides[0].p0, 12), light[3] = 1;  // at a vertex
      if (trial >= 8) {  // inside a face (its centroid), on an edge: the faces on the light collapse
        const geom::SvCap& c = b.volume.caps[0];
        const geom::SvSide& e = b.volume.sides[0];
        for (int k = 0; k < 3; ++k)
          light[k] = trial == 8 ? (c.a[k] + c.b[k] + c.c[k]) / 3 : 0.25f * e.p0[k] + 0.75f * e.p1[k];
        light[3] = 1;
      }
      // Shadow volume: sides and caps, generic and per-light.
      const geom::ShadowVolume lv = geom::build_light_volume(b.volume, light);
      for (const geom::ShadowVolume* v : {&b.volume, &lv}) {
        glUseProgram(sv);
        glUniformMatrix4fv(glGetUniformLocation(sv, "u_view_proj"), 1, GL_FALSE, kIdentity);
        glUniform4fv(glGetUniformLocation(sv, "u_light"), 1, light);
        glUniform1i(glGetUniformLocation(sv, "u_caps"), 0);
        std::vector<float> gpu =
            capture(sv, v->sides.data(), v->sides.size() * 32, 32, GLsizei(v->sides.size()), 4, v->planes, side_layout);
        ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
        for (size_t i = 0; i < v->sides.size(); ++i) {
          float c[4][4];
          geom::side_corners(v->sides[i], v->planes.data(), light, c);
          ASSERT_EQ(std::memcmp(c, &gpu[16 * i], 64), 0) << "side " << i;
          ++compared;
        }
        glUniform1i(glGetUniformLocation(sv, "u_caps"), 1);
        gpu = capture(sv, v->caps.data(), v->caps.size() * 40, 40, GLsizei(v->caps.size()), 6, v->planes, cap_layout);
        ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
        for (size_t i = 0; i < v->caps.size(); ++i) {
          float c[6][4];
          geom::cap_corners(v->caps[i], v->planes.data(), light, c);
          ASSERT_EQ(std::memcmp(c, &gpu[24 * i], 96), 0) << "cap " << i;
          ++compared;
        }
      }
      // ESM quads.
      glUseProgram(esm);
      const float scale = 0.05f;
      glUniformMatrix4fv(glGetUniformLocation(esm, "u_light_view_proj"), 1, GL_FALSE, kIdentity);
      glUniform4fv(glGetUniformLocation(esm, "u_light"), 1, light);
      glUniform1f(glGetUniformLocation(esm, "u_extrude_scale"), scale);
      const std::vector<float> gpu = capture(esm, b.esm.quads.data(), b.esm.quads.size() * 36, 36,
                                             GLsizei(b.esm.quads.size()), 4, b.esm.planes, esm_layout);
      ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
      for (size_t i = 0; i < b.esm.quads.size(); ++i) {
        float c[4][4];
        geom::esm_corners(b.esm.quads[i], b.esm.planes.data(), light, kIdentity, scale, c);
        for (int k = 0; k < 4; ++k)
          for (int j = 0; j < 4; ++j) ASSERT_NEAR(c[k][j], gpu[16 * i + 4 * k + j], 1e-5) << "quad " << i;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 1000);
  glDeleteProgram(sv);
  glDeleteProgram(esm);
}

}  // namespace
