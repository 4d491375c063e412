// engine_sample: what an engine does with a .gbake, in plain OpenGL 4.5 and
// geom::reader alone (geom/baked_reader.h, geom/baked_records.h: standard
// library only). It loads the file, uploads its sections as they lie, and draws
// one light's shadows with the shipped shaders, in the GL state their headers
// state: depth-fail stencil shadow volumes (shadow_volume.vert, volume.frag) or
// a shadow map (depth.vert, depth.frag, lookup_shadow_map.frag); the scene is
// shaded by scene.vert and shade.frag. Headless through EGL; in a GLFW window
// too with --window where a display exists. --mask FILE.pgm writes the shadow
// mask (255 lit, 0 shadowed, 128 no geometry; tests/test_gl_engine_sample.cpp
// compares it with the ray-cast reference).
//   engine_sample FILE.gbake SHADER_DIR [--mask OUT.pgm] [--map] [--no-offset] [--window]
//     [--size W,H] [--eye X,Y,Z] [--target X,Y,Z] [--fov DEG] [--near N] [--light X,Y,Z,W]
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#ifdef SAMPLE_GLFW
#include <GLFW/glfw3.h>
#endif
#include <geom/baked_reader.h>
#include <geom/baked_records.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {
using geom::baked::SectionType;
struct M4 {
  double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};  // column-major
M4 mul(const M4& a, const M4& b) {
  M4 r;
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) {
      double s = 0;
      for (int j = 0; j < 4; ++j) s += a.m[j * 4 + k] * b.m[c * 4 + j];
      r.m[c * 4 + k] = s;
    }
  return r;
}
void norm(double v[3]) {
  double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int k = 0; k < 3; ++k) v[k] /= l;
}
void cross(const double a[3], const double b[3], double o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
M4 look_at(const double eye[3], const double at[3], const double up_hint[3]) {
  double f[3] = {at[0] - eye[0], at[1] - eye[1], at[2] - eye[2]}, s[3], u[3];
  norm(f), cross(f, up_hint, s), norm(s), cross(s, f, u);
  M4 r;
  for (int k = 0; k < 3; ++k) r.m[k * 4] = s[k], r.m[k * 4 + 1] = u[k], r.m[k * 4 + 2] = -f[k];
  for (int k = 0; k < 3; ++k) r.m[12 + k] = -(r.m[k] * eye[0] + r.m[4 + k] * eye[1] + r.m[8 + k] * eye[2]);
  return r;
}
M4 perspective(double fovy_deg, double aspect, double n, double f) {  // f = INFINITY: infinite far plane
  const double t = 1 / std::tan(fovy_deg * M_PI / 360);
  M4 r;
  r.m[0] = t / aspect, r.m[5] = t, r.m[11] = -1, r.m[15] = 0;
  r.m[10] = std::isinf(f) ? -1 : -(f + n) / (f - n), r.m[14] = std::isinf(f) ? -2 * n : -2 * f * n / (f - n);
  return r;
}
void set_matrix(GLuint p, const char* name, const M4& a) {
  float f[16];
  for (int i = 0; i < 16; ++i) f[i] = float(a.m[i]);
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, name), 1, GL_FALSE, f);
}
GLuint shader(GLenum kind, const std::string& path) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const char* src = text.c_str();
  GLuint s = glCreateShader(kind);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  return s;
}
GLuint program(const std::string& dir, std::vector<std::pair<GLenum, const char*>> parts) {
  GLuint p = glCreateProgram();
  for (auto& [kind, name] : parts) glAttachShader(p, shader(kind, dir + "/" + name));
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    std::fprintf(stderr, "Error: %s: the shaders do not link: %s\n", dir.c_str(), log);
    std::exit(1);
  }
  return p;
}
// A vertex array over one buffer of records, one instance each: {location, components, offset, integer}.
GLuint record_vao(const geom::baked::Section& s, std::vector<std::vector<int>> attributes) {
  GLuint vao, buffer;
  glCreateVertexArrays(1, &vao), glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, GLsizeiptr(s.size ? s.size : 1), s.data, 0);
  glVertexArrayVertexBuffer(vao, 0, buffer, 0, GLsizei(s.stride));
  glVertexArrayBindingDivisor(vao, 0, 1);
  for (const auto& a : attributes) {
    glEnableVertexArrayAttrib(vao, a[0]), glVertexArrayAttribBinding(vao, a[0], 0);
    if (a[3])
      glVertexArrayAttribIFormat(vao, a[0], a[1], GL_UNSIGNED_INT, a[2]);
    else
      glVertexArrayAttribFormat(vao, a[0], a[1], GL_FLOAT, GL_FALSE, a[2]);
  }
  return vao;
}
bool numbers(int argc, char** argv, int& i, const char* flag, double* out, int n) {
  if (std::strcmp(argv[i], flag) != 0 || i + 1 >= argc) return false;
  const char* p = argv[++i];
  for (int k = 0; k < n; ++k, ++p) out[k] = std::strtod(p, const_cast<char**>(&p));
  return true;
}

struct Options {
  std::string file, dir, mask_path;
  bool use_map = false, offset = true, window = false;
  double size[2] = {640, 480}, eye[3] = {4, 5, 7}, target[3] = {0, 0.7, 0}, fov = 50, near_plane = 0.1,
         light[4] = {-1, 5, -2, 1};
};
// The command line; false (after the message) on an unknown option.
bool parse_options(int argc, char** argv, Options& o) {
  o.file = argv[1], o.dir = argv[2];
  for (int i = 3; i < argc; ++i)
    if (!std::strcmp(argv[i], "--mask") && i + 1 < argc)
      o.mask_path = argv[++i];
    else if (!std::strcmp(argv[i], "--map"))
      o.use_map = true;
    else if (!std::strcmp(argv[i], "--no-offset"))
      o.offset = false;
    else if (!std::strcmp(argv[i], "--window"))
      o.window = true;
    else if (!numbers(argc, argv, i, "--size", o.size, 2) && !numbers(argc, argv, i, "--eye", o.eye, 3) &&
             !numbers(argc, argv, i, "--target", o.target, 3) && !numbers(argc, argv, i, "--fov", &o.fov, 1) &&
             !numbers(argc, argv, i, "--near", &o.near_plane, 1) && !numbers(argc, argv, i, "--light", o.light, 4))
      return std::fprintf(stderr, "Error: unknown option %s\n", argv[i]), false;
  return true;
}

// The sections the sample draws from, borrowed from the reader's bytes.
struct Sections {
  const geom::baked::Section *pos, *idx, *face_planes, *frame, *sides, *caps, *planes;
};
bool find_sections(const geom::baked::Reader& file, Sections& s) {
  s = {file.find(SectionType::Positions),   file.find(SectionType::Indices),     file.find(SectionType::FacePlanes),
       file.find(SectionType::Frame),       file.find(SectionType::VolumeSides), file.find(SectionType::VolumeCaps),
       file.find(SectionType::VolumePlanes)};
  return s.pos && s.idx && s.face_planes && s.frame && s.sides && s.caps && s.planes;
}

// A GL 4.5 core context: a window (*window, with --window where a display
// exists), else EGL without any surface. False when there is none.
bool make_context(const Options& o, int w, int h, void** window) {
  *window = nullptr;
#ifdef SAMPLE_GLFW
  if (o.window && std::getenv("DISPLAY") && glfwInit()) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4), glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    if (GLFWwindow* win = glfwCreateWindow(w, h, "engine_sample", nullptr, nullptr))
      return glfwMakeContextCurrent(win), *window = win, true;
  }
#endif
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay d =
      get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr) : EGL_NO_DISPLAY;
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr))
    eglInitialize(d = eglGetDisplay(EGL_DEFAULT_DISPLAY), nullptr, nullptr);
  const EGLint attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext c = EGL_NO_CONTEXT;
  if (eglBindAPI(EGL_OPENGL_API)) c = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  return c != EGL_NO_CONTEXT && eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c);
}

// The frame drawn into: RGBA8 colour and a depth-stencil buffer.
GLuint make_framebuffer(int w, int h) {
  GLuint fbo, rb[2];
  glCreateFramebuffers(1, &fbo), glCreateRenderbuffers(2, rb);
  glNamedRenderbufferStorage(rb[0], GL_RGBA8, w, h), glNamedRenderbufferStorage(rb[1], GL_DEPTH24_STENCIL8, w, h);
  glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
  glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  return fbo;
}

// The scene, in input coordinates: each triangle with its face's normal (scene.vert's inputs).
// The bytes, 64-byte aligned in the file and read into a new'd buffer, are the arrays themselves.
struct Scene {
  GLuint vao = 0;
  GLsizei vertices = 0;
  void draw() const { glBindVertexArray(vao), glDrawArrays(GL_TRIANGLES, 0, vertices); }
};
Scene upload_scene(const Sections& s) {
  const float* p = reinterpret_cast<const float*>(s.pos->data);
  const uint32_t* tri = reinterpret_cast<const uint32_t*>(s.idx->data);
  const float* fp = reinterpret_cast<const float*>(s.face_planes->data);
  std::vector<float> vertices;
  for (uint64_t t = 0; t < s.idx->count / 3; ++t)
    for (int k = 0; k < 3; ++k)
      vertices.insert(vertices.end(), {p[3 * tri[3 * t + k]], p[3 * tri[3 * t + k] + 1], p[3 * tri[3 * t + k] + 2],
                                       fp[4 * t], fp[4 * t + 1], fp[4 * t + 2]});
  Scene scene;
  GLuint buffer;
  glCreateVertexArrays(1, &scene.vao), glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, GLsizeiptr(vertices.size() * 4 + 4), vertices.data(), 0);
  glVertexArrayVertexBuffer(scene.vao, 0, buffer, 0, 24);
  for (int a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(scene.vao, a), glVertexArrayAttribBinding(scene.vao, a, 0);
    glVertexArrayAttribFormat(scene.vao, a, 3, GL_FLOAT, GL_FALSE, a * 12);
  }
  scene.vertices = GLsizei(vertices.size() / 6);
  return scene;
}

// shade.frag with the shadow lookup of the technique, writing the mask (u_output 1).
GLuint shade_program(const Options& o, const M4& view, const M4& view_proj) {
  GLuint shade = program(o.dir, {{GL_VERTEX_SHADER, "scene.vert"},
                                 {GL_FRAGMENT_SHADER, "shade.frag"},
                                 {GL_FRAGMENT_SHADER, o.use_map ? "lookup_shadow_map.frag" : "lookup_none.frag"}});
  set_matrix(shade, "u_view_proj", view_proj), set_matrix(shade, "u_view", view);
  glProgramUniform4f(shade, glGetUniformLocation(shade, "u_light"), float(o.light[0]), float(o.light[1]),
                     float(o.light[2]), float(o.light[3]));
  glProgramUniform1f(shade, glGetUniformLocation(shade, "u_far"), 1e30f);
  glProgramUniform1f(shade, glGetUniformLocation(shade, "u_spot_cos"), -2.0f);
  glProgramUniform1i(shade, glGetUniformLocation(shade, "u_output"), 1);  // the mask
  return shade;
}

// 4a. Depth-fail volumes (shadow_volume.vert's header): depth and ambient with the
//     receivers pulled towards the camera, the stencil count, then lit where it is zero.
void draw_volumes(const Options& o, const Sections& s, const Scene& scene, GLuint shade, const M4& view_proj) {
  const double* light = o.light;
  if (o.offset) glEnable(GL_POLYGON_OFFSET_FILL), glPolygonOffset(0.0f, -8.0f);
  glProgramUniform1i(shade, glGetUniformLocation(shade, "u_ambient_only"), 1);
  glUseProgram(shade), scene.draw();
  glDisable(GL_POLYGON_OFFSET_FILL);
  GLuint volume = program(o.dir, {{GL_VERTEX_SHADER, "shadow_volume.vert"}, {GL_FRAGMENT_SHADER, "volume.frag"}});
  const double* origin = reinterpret_cast<const double*>(s.frame->data);
  M4 to_input;  // local = input - origin
  for (int k = 0; k < 3; ++k) to_input.m[12 + k] = origin[k];
  set_matrix(volume, "u_view_proj", mul(view_proj, to_input));
  glProgramUniform4f(volume, glGetUniformLocation(volume, "u_light"), float(light[0] - light[3] * origin[0]),
                     float(light[1] - light[3] * origin[1]), float(light[2] - light[3] * origin[2]), float(light[3]));
  GLuint plane_buffer, plane_texture;
  glCreateBuffers(1, &plane_buffer),
      glNamedBufferStorage(plane_buffer, GLsizeiptr(s.planes->size + 16), s.planes->data, 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &plane_texture), glTextureBuffer(plane_texture, GL_RGBA32F, plane_buffer);
  glBindTextureUnit(0, plane_texture), glProgramUniform1i(volume, glGetUniformLocation(volume, "u_planes"), 0);
  const GLuint side_vao = record_vao(*s.sides, {{0, 3, 0, 0}, {1, 3, 12, 0}, {3, 1, 24, 1}, {4, 1, 28, 1}});
  const GLuint cap_vao = record_vao(*s.caps, {{0, 3, 0, 0}, {1, 3, 12, 0}, {2, 3, 24, 0}, {3, 1, 36, 1}});
  glEnable(GL_STENCIL_TEST), glStencilFunc(GL_ALWAYS, 0, 0xff), glStencilMask(0xff);
  glDepthMask(GL_FALSE), glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE), glEnable(GL_DEPTH_CLAMP);
  glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
  glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
  glUseProgram(volume);
  glProgramUniform1i(volume, glGetUniformLocation(volume, "u_caps"), 0);
  glBindVertexArray(side_vao), glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(s.sides->count));
  glProgramUniform1i(volume, glGetUniformLocation(volume, "u_caps"), 1);
  glBindVertexArray(cap_vao), glDrawArraysInstanced(GL_TRIANGLES, 0, 6, GLsizei(s.caps->count));
  glDisable(GL_DEPTH_CLAMP), glDepthMask(GL_TRUE), glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  if (o.offset) glEnable(GL_POLYGON_OFFSET_FILL);
  glStencilFunc(GL_EQUAL, 0, 0xff), glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP), glDepthFunc(GL_EQUAL);
  glProgramUniform1i(shade, glGetUniformLocation(shade, "u_ambient_only"), 0);
  glUseProgram(shade), scene.draw();
  glDisable(GL_STENCIL_TEST), glDisable(GL_POLYGON_OFFSET_FILL), glDepthFunc(GL_LESS);
}

// 4b. A 2048^2 shadow map (depth.vert's header) from the light looking at the target.
void draw_with_map(const Options& o, const Scene& scene, GLuint shade, GLuint fbo, int w, int h) {
  const double *light = o.light, *target = o.target;
  const int n = 2048;
  GLuint map, map_fbo;
  glCreateTextures(GL_TEXTURE_2D, 1, &map), glTextureStorage2D(map, 1, GL_DEPTH_COMPONENT32F, n, n);
  glTextureParameteri(map, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(map, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  for (GLenum f : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTextureParameteri(map, f, GL_NEAREST);
  glCreateFramebuffers(1, &map_fbo), glNamedFramebufferTexture(map_fbo, GL_DEPTH_ATTACHMENT, map, 0);
  const double at_light[3] = {light[0] / (light[3] ? light[3] : 1), light[1] / (light[3] ? light[3] : 1),
                              light[2] / (light[3] ? light[3] : 1)};
  const double from[3] = {light[3] ? at_light[0] : target[0] + 20 * at_light[0],
                          light[3] ? at_light[1] : target[1] + 20 * at_light[1],
                          light[3] ? at_light[2] : target[2] + 20 * at_light[2]};
  const double up[3] = {0, 1, 0}, side_up[3] = {1, 0, 0};
  const M4 light_clip =
      mul(perspective(light[3] ? 120 : 30, 1, 0.5, 100),
          look_at(from, target, std::fabs(from[0] - target[0]) + std::fabs(from[2] - target[2]) < 1e-6 ? side_up : up));
  GLuint depth = program(o.dir, {{GL_VERTEX_SHADER, "depth.vert"}, {GL_FRAGMENT_SHADER, "depth.frag"}});
  set_matrix(depth, "u_matrix", light_clip);
  glBindFramebuffer(GL_FRAMEBUFFER, map_fbo), glViewport(0, 0, n, n), glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_CLAMP), glEnable(GL_POLYGON_OFFSET_FILL), glPolygonOffset(1.5f, 4.0f);
  glUseProgram(depth), scene.draw();
  glDisable(GL_POLYGON_OFFSET_FILL), glDisable(GL_DEPTH_CLAMP);
  set_matrix(shade, "u_light_matrix", light_clip);
  glBindTextureUnit(0, map), glProgramUniform1i(shade, glGetUniformLocation(shade, "u_shadow_map"), 0);
  glProgramUniform1i(shade, glGetUniformLocation(shade, "u_pcf"), 0);
  glProgramUniform1i(shade, glGetUniformLocation(shade, "u_ambient_only"), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo), glViewport(0, 0, w, h);
  glUseProgram(shade), scene.draw();
}

// 5. The mask, top row first (255 lit, 0 shadowed, 128 no geometry), as a binary PGM.
bool write_mask(const std::string& path, int w, int h) {
  std::vector<unsigned char> rgba(size_t(w) * h * 4), mask(size_t(w) * h);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char r = rgba[4 * (size_t(h - 1 - y) * w + x)];
      mask[size_t(y) * w + x] = r > 192 ? 255 : r < 64 ? 0 : 128;
    }
  if (path.empty()) return true;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  return f && std::fprintf(f, "P5\n%d %d\n255\n", w, h) >= 0 &&
         std::fwrite(mask.data(), 1, mask.size(), f) == mask.size() && std::fclose(f) == 0;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return std::fprintf(stderr, "usage: engine_sample FILE.gbake SHADER_DIR [options]\n"), 2;
  Options o;
  if (!parse_options(argc, argv, o)) return 2;
  // 1. The file, read and validated in memory; its sections are GL buffers as they lie.
  std::ifstream in(o.file, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  geom::baked::Reader file;
  if (!file.open(bytes.data(), bytes.size()))
    return std::fprintf(stderr, "Error: %s: %s\n", o.file.c_str(), file.error().c_str()), 1;
  Sections s;
  if (!find_sections(file, s))
    return std::fprintf(stderr, "Error: %s: needs positions, indices, face planes and the shadow volume\n",
                        o.file.c_str()),
           1;
  // 2. A GL 4.5 core context and the frame; 3. the scene.
  const int w = int(o.size[0]), h = int(o.size[1]);
  void* win = nullptr;
  if (!make_context(o, w, h, &win)) return std::fprintf(stderr, "Error: no OpenGL 4.5 core context through EGL\n"), 1;
  const GLuint fbo = make_framebuffer(w, h);
  const Scene scene = upload_scene(s);
  const double up[3] = {0, 1, 0};
  const M4 view = look_at(o.eye, o.target, up),
           view_proj = mul(perspective(o.fov, o.size[0] / o.size[1], o.near_plane, INFINITY), view);
  const GLuint shade = shade_program(o, view, view_proj);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo), glViewport(0, 0, w, h);
  glClearColor(0.5f, 0.5f, 0.5f, 1), glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST), glDepthFunc(GL_LESS);
  // 4. The shadows, by one technique.
  if (!o.use_map)
    draw_volumes(o, s, scene, shade, view_proj);
  else
    draw_with_map(o, scene, shade, fbo, w, h);
  if (!write_mask(o.mask_path, w, h))
    return std::fprintf(stderr, "Error: %s: cannot write the mask\n", o.mask_path.c_str()), 1;
#ifdef SAMPLE_GLFW
  for (auto* window = static_cast<GLFWwindow*>(win); window && !glfwWindowShouldClose(window);) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0),  // the frame, shown until the window closes
        glBlitNamedFramebuffer(fbo, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glfwSwapBuffers(window), glfwWaitEvents();
  }
#endif
  (void)win;
  std::printf("engine_sample: %s, %llu triangles, %llu volume sides, %llu caps\n",
              o.use_map ? "shadow map" : "depth-fail volumes", (unsigned long long)(s.idx->count / 3),
              (unsigned long long)s.sides->count, (unsigned long long)s.caps->count);
  return 0;
}
