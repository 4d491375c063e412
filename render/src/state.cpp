// state.cpp: the state's life (the scene upload, a baked file's one caster)
// and the entry points of render/render.h around draw_frame.
#include "state.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace render {

void StateDeleter::operator()(State* s) const { delete s; }

StatePtr create_state(const geom::Scene& scene, const std::string& shader_dir, std::string& error) {
  StatePtr s(new State);
  s->programs.shader_dir = shader_dir;
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
    const glm::dvec3 p(scene.positions[3 * size_t(v)], scene.positions[3 * size_t(v) + 1],
                       scene.positions[3 * size_t(v) + 2]);
    dlo = glm::min(dlo, p), dhi = glm::max(dhi, p);
  }
  if (tris) s->origin = (dlo + dhi) * 0.5;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (size_t t = 0; t < tris; ++t) {
    glm::vec3 p[3];
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = scene.indices[3 * t + k];
      if (i >= nv)
        ok = false;
      else
        p[k] = glm::vec3(scene.positions[3 * i], scene.positions[3 * i + 1], scene.positions[3 * i + 2]);
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
  BakedView view;
  if (!baked_view(reader, view, error)) return nullptr;
  scene = geom::Scene();
  scene.positions.assign(view.welded, view.welded + 3 * view.welded_count);
  scene.indices.assign(view.indices, view.indices + 3 * view.triangle_count);
  for (uint32_t i : scene.indices)
    if (i >= view.welded_count) {
      error = "an index of the indices section is out of range";
      return nullptr;
    }
  scene.sources.resize(scene.triangle_count());
  if (const gb::Section* lights = reader.find(gb::SectionType::Lights); lights && lights->as<double[4]>())
    for (uint64_t i = 0; i < lights->count; ++i)
      scene.lights.push_back(geom::light_from_homogeneous(lights->as<double[4]>()[i]));
  StatePtr s = create_state(scene, shader_dir, error);
  if (!s) return nullptr;
  // The one caster: the file's buffers as they lie.
  view.indices = scene.indices.data();
  s->baked_adjacency = view.has_adjacency, s->baked_esm = view.has_esm, s->baked_volume = view.has_volume;
  if (!upload_caster(*s, view, error)) return nullptr;
  s->baked = true;
  s->casters_built = true;
  return s;
}

namespace {

View view_of(const geom::Camera& c) {
  View v;
  v.eye = glm::vec3(c.eye[0], c.eye[1], c.eye[2]);
  v.target = glm::vec3(c.target[0], c.target[1], c.target[2]);
  v.up = glm::vec3(c.up[0], c.up[1], c.up[2]);
  v.fovy_deg = c.fovy_deg, v.near_plane = c.near_plane, v.far_plane = c.far_plane;
  return v;
}

}  // namespace

bool render(State& s, const geom::Camera& camera, const geom::Light& light, const FrameSettings& fs,
            geom::PngImage& image, std::vector<PassTime>& times, std::string& error) {
  const int w = camera.width, h = camera.height;
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
    error = "image size out of range";
    return false;
  }
  if (s.camera.width != w || s.camera.height != h) {  // the camera target: RGBA8 colour + depth/stencil texture
    Target& t = s.camera;
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
  PassTimer timer;
  timer.gpu = s.gpu_timers;
  timer.out = &times;
  if (!draw_frame(s, view_of(camera), frame_light(light), fs, s.camera.fbo, w, h, timer, error)) return false;
  timer.collect();
  std::vector<uint8_t> rgba(size_t(w) * h * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, s.camera.fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  const int channels = fs.output == Output::Color ? 3 : 1;
  image.width = w, image.height = h, image.channels = channels;
  image.pixels.resize(size_t(w) * h * channels);
  for (int y = 0; y < h; ++y)  // GL's first row is the bottom one
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        image.pixels[(size_t(y) * w + x) * channels + c] = rgba[(size_t(h - 1 - y) * w + x) * 4 + c];
  GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    std::ostringstream o;
    o << std::hex << err;
    error = "OpenGL error 0x" + o.str();
    return false;
  }
  return true;
}

bool render_to_window(State& s, const geom::Camera& camera, const geom::Light& light, const FrameSettings& fs,
                      int width, int height, std::vector<PassTime>& times, std::string& error) {
  PassTimer timer;
  timer.gpu = s.gpu_timers;
  timer.out = &times;
  if (!draw_frame(s, view_of(camera), frame_light(light), fs, 0, width, height, timer, error)) return false;
  timer.collect();
  return true;
}

std::string drawn_projection(const State& s) { return s.projection; }
std::string renderer_name(State& s) { return s.renderer; }
std::string timing_kind(State& s) {
  return s.gpu_timers ? "GPU timer queries" : "wall time around glFinish (software renderer)";
}
void scene_bounds(const State& s, float out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = s.bounds[k];
}

geom::Camera default_view(const State& s, int width, int height) {
  geom::Camera v;
  v.width = width, v.height = height;
  const glm::vec3 target = glm::vec3(s.bounds) - glm::vec3(0, s.bounds.w * 0.2f, 0);
  const glm::vec3 eye = target + glm::normalize(glm::vec3(0.45f, 0.5f, 1.0f)) * (s.bounds.w * 0.9f);
  for (int k = 0; k < 3; ++k) v.eye[k] = eye[k], v.target[k] = target[k];
  v.fovy_deg = 50;
  v.near_plane = s.bounds.w * 0.01f;
  v.far_plane = s.bounds.w * 100.0f;
  return v;
}

geom::Camera default_view(const State& s, int width, int height, int up_axis) {
  geom::Camera v;
  v.width = width, v.height = height;
  // Right-handed frames with front = right x up: y-up looks along -z, z-up along +y.
  static const glm::vec3 kRight[3] = {{0, 1, 0}, {1, 0, 0}, {1, 0, 0}}, kUp[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int a = std::clamp(up_axis, 0, 2);
  const glm::vec3 right = kRight[a], up = kUp[a], front = glm::cross(right, up);
  const float radius = std::max(s.bounds.w, 1e-3f);
  v.fovy_deg = 50;
  // The eye looks at the box centre along `back` (from the front, right and
  // above); its distance is the least that keeps the 8 corners of the box
  // inside both fields of view, with a 6% margin.
  const glm::vec3 target = (s.scene_lo + s.scene_hi) * 0.5f;
  const glm::vec3 back = glm::normalize(0.45f * right + 0.5f * up + 1.0f * front);
  const glm::vec3 side = glm::normalize(glm::cross(up, back)), top = glm::cross(back, side);
  const float tan_v = std::tan(glm::radians(v.fovy_deg) * 0.5f) / 1.06f;
  const float tan_h = tan_v * float(width) / float(std::max(height, 1));
  float distance = radius * 1e-3f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 p(c & 1 ? s.scene_hi.x : s.scene_lo.x, c & 2 ? s.scene_hi.y : s.scene_lo.y,
                      c & 4 ? s.scene_hi.z : s.scene_lo.z);
    const glm::vec3 d = p - target;
    const float along = glm::dot(d, back);  // towards the eye
    distance =
        std::max({distance, along + std::fabs(glm::dot(d, side)) / tan_h, along + std::fabs(glm::dot(d, top)) / tan_v});
  }
  const glm::vec3 eye = target + back * distance;
  for (int k = 0; k < 3; ++k) v.eye[k] = eye[k], v.target[k] = target[k], v.up[k] = up[k];
  v.near_plane = std::max(distance - radius, radius * 0.002f) * 0.5f;
  v.far_plane = distance + radius * 100.0f;
  return v;
}

}  // namespace render
