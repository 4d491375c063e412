// window.cpp: the window app (app.h): an orbit camera, keys, the ImGui panels
// and HUD (ui.cpp), the error of the current view on E with the wrong pixels
// as an overlay, the compare grid on C, the technique in the window title.
#define GL_GLEXT_PROTOTYPES 1
#define GLFW_INCLUDE_GLCOREARB 1
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "app.h"
#include "cli/args.h"
#include "compare.h"
#include "ui.h"

namespace viewer {
namespace {

glm::vec3 vec3(const float v[3]) { return glm::vec3(v[0], v[1], v[2]); }
void store(float out[3], glm::vec3 v) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }

int key_of(char c) {
  switch (c) {
    case '[':
      return GLFW_KEY_LEFT_BRACKET;
    case ']':
      return GLFW_KEY_RIGHT_BRACKET;
    case 'q':
      return GLFW_KEY_ESCAPE;
    default:
      return c >= 'a' && c <= 'z' ? GLFW_KEY_A + (c - 'a') : -1;
  }
}

// Everything the frame depends on, to know when a measured error or a grid is stale.
std::string view_key(const geom::Camera& v, const geom::Light& l, const render::FrameSettings& s, int w, int h) {
  char b[512];
  std::snprintf(b, sizeof b, "%g %g %g %g %g %g %g %g %g|%d %g %g %g %g %g %g %g|%d %d %d|%d %d", v.eye[0], v.eye[1],
                v.eye[2], v.target[0], v.target[1], v.target[2], v.up[0], v.up[1], v.up[2], int(l.type), l.position[0],
                l.position[1], l.position[2], l.direction[0], l.direction[1], l.direction[2], l.outer_cone,
                int(s.technique), s.shadow_map_size, int(s.inspect), w, h);
  return b;
}

// What the window's loop shares between its steps.
struct WindowRun {
  WindowRun(Options& options, Session& session) : o(options), s(session), view(options.view), light(options.light) {}
  Options& o;
  Session& s;
  geom::Camera& view;
  geom::Light& light;
  WindowModel m;
  float bounds[4] = {0, 0, 0, 1};
  glm::vec3 centre{0};
  bool quit = false, gpu = false;
  int fb_w = 0, fb_h = 0;
  std::string error, title, measured_key, grid_key;
  Reference ref;
  size_t script_at = 0;
  int frames_after_script = 0;
};

// The model from the flags: the technique, the grid's picks, the light kind.
void init_model(WindowRun& r) {
  WindowModel& m = r.m;
  m.all = render::available_techniques();
  m.settings = r.o.settings;
  for (size_t i = 0; i < m.all.size(); ++i)
    if (m.all[i] == r.o.techniques[0]) m.current = i;
  m.compare_pick.assign(m.all.size(), false);
  // The grid's techniques: --compare, else several --technique (all: the first 16), else four defaults.
  std::vector<render::Technique> picks = r.o.compare;
  if (picks.empty() && r.o.techniques.size() > 1) picks = r.o.techniques;
  m.compare = !picks.empty();
  if (picks.empty())
    picks = {render::Technique::Ssm, render::Technique::Pcf, render::Technique::Edsm, render::Technique::Sv};
  for (size_t k = 0; k < picks.size() && k < 16; ++k)
    for (size_t i = 0; i < m.all.size(); ++i)
      if (m.all[i] == picks[k]) m.compare_pick[i] = true;
  m.light_kind = r.light.type == geom::LightType::Directional ? 2 : r.light.type == geom::LightType::Spot ? 1 : 0;
  render::scene_bounds(*r.s.state, r.bounds);
  r.centre = glm::vec3(r.bounds[0], r.bounds[1], r.bounds[2]);
  double h[4];
  geom::light_homogeneous(r.light, h);
  store(m.light_position, glm::vec3(float(h[0]), float(h[1]), float(h[2])));
  r.gpu = render::timing_kind(*r.s.state).rfind("GPU", 0) == 0;
}

// The panel's light kind and position into the frame's light.
void apply_light(WindowRun& r) {
  const WindowModel& m = r.m;
  const glm::vec3 p = vec3(m.light_position);
  geom::Light& light = r.light;
  light = geom::Light();
  light.type = m.light_kind == 2   ? geom::LightType::Directional
               : m.light_kind == 1 ? geom::LightType::Spot
                                   : geom::LightType::Point;
  const glm::vec3 axis = glm::length(r.centre - p) > 0 ? r.centre - p : glm::vec3(0, -1, 0);
  for (int k = 0; k < 3; ++k) light.position[k] = p[k], light.direction[k] = m.light_kind == 2 ? -p[k] : axis[k];
  if (m.light_kind == 2 && glm::length(p) == 0) light.direction[1] = -1;
  light.outer_cone = glm::radians(35.0);
}

void on_key(WindowRun& r, int key) {
  WindowModel& m = r.m;
  if (key == GLFW_KEY_ESCAPE) r.quit = true;
  if (key == GLFW_KEY_T) m.current = (m.current + 1) % m.all.size();
  if (key == GLFW_KEY_I) m.settings.inspect = !m.settings.inspect;
  if (key == GLFW_KEY_E) m.measure = true;
  if (key == GLFW_KEY_C) m.compare = !m.compare;
  if (key == GLFW_KEY_R) m.reset_camera = true;
  if (key == GLFW_KEY_H) m.show_panels = !m.show_panels;
  if (key == GLFW_KEY_RIGHT_BRACKET) m.settings.shadow_map_size = std::min(m.settings.shadow_map_size * 2, 8192);
  if (key == GLFW_KEY_LEFT_BRACKET) m.settings.shadow_map_size = std::max(m.settings.shadow_map_size / 2, 64);
  if (key == GLFW_KEY_L) {
    m.light_kind = (m.light_kind + 1) % 3;
    if (m.light_kind == 0 && glm::length(vec3(m.light_position) - r.centre) > 1e4f * r.bounds[3])
      store(m.light_position, r.centre + glm::normalize(vec3(m.light_position)) * r.bounds[3] * 2.0f);
    m.light_changed = true;
  }
}

// Keys, orbit (left drag), zoom (right drag, scroll), unless ImGui has them.
render::PlatformEvents make_events(WindowRun& r) {
  render::PlatformEvents events;
  events.key = [&r](int key) {
    if (!ui_wants_keyboard()) on_key(r, key);
  };
  events.drag = [&r](double dx, double dy, int button) {
    if (ui_wants_mouse()) return;
    geom::Camera& view = r.view;
    glm::vec3 offset = vec3(view.eye) - vec3(view.target);
    if (button == 0) {
      const glm::vec3 up = glm::normalize(vec3(view.up));
      offset = glm::vec3(glm::rotate(glm::mat4(1), float(-dx * 0.01), up) * glm::vec4(offset, 0));
      const glm::vec3 right = glm::normalize(glm::cross(offset, up));
      const glm::vec3 tilted = glm::vec3(glm::rotate(glm::mat4(1), float(dy * 0.01), right) * glm::vec4(offset, 0));
      if (std::fabs(glm::dot(glm::normalize(tilted), up)) < 0.99f) offset = tilted;
    } else {
      offset *= float(std::exp(dy * 0.01));
    }
    store(view.eye, vec3(view.target) + offset);
  };
  events.scroll = [&r](double dy) {
    if (ui_wants_mouse()) return;
    geom::Camera& view = r.view;
    store(view.eye, vec3(view.target) + (vec3(view.eye) - vec3(view.target)) * float(std::exp(-dy * 0.1)));
  };
  return events;
}

// The next scripted key, a changed light, a camera reset, the window title.
void begin_frame(WindowRun& r) {
  WindowModel& m = r.m;
  geom::Camera& view = r.view;
  r.s.platform->framebuffer_size(r.fb_w, r.fb_h);
  if (r.script_at < r.o.script.size()) on_key(r, key_of(r.o.script[r.script_at++]));
  if (m.light_changed) apply_light(r), m.light_changed = false;
  if (m.reset_camera) {
    const geom::Camera framed = framed_view(r.s, r.fb_w, r.fb_h);
    store(view.eye, vec3(framed.eye)), store(view.target, vec3(framed.target)), store(view.up, vec3(framed.up));
    view.fovy_deg = framed.fovy_deg, view.near_plane = framed.near_plane, view.far_plane = framed.far_plane;
    m.reset_camera = false;
  }
  m.settings.technique = m.all[m.current];
  view.width = std::max(r.fb_w, 1), view.height = std::max(r.fb_h, 1);
  const std::string name = render::technique_name(m.settings.technique);
  const std::string want_title = "geomview: " +
                                 (m.compare ? std::string("compare grid")
                                            : name + (render::technique_has_map(m.settings.technique)
                                                          ? " " + std::to_string(m.settings.shadow_map_size)
                                                          : std::string())) +
                                 " - " + r.o.file;
  if (want_title != r.title) glfwSetWindowTitle(glfwGetCurrentContext(), (r.title = want_title).c_str());
  if (m.settings.inspect && !m.counts_valid) m.counts_valid = render::inspection_counts(*r.s.state, m.counts, r.error);
}

// The compare grid, re-rendered when the view or the picks changed.
void draw_grid(WindowRun& r, const std::string& key) {
  WindowModel& m = r.m;
  std::vector<render::Technique> picked;
  for (size_t i = 0; i < m.all.size() && picked.size() < 16; ++i)
    if (m.compare_pick[i]) picked.push_back(m.all[i]);
  if (picked.empty()) picked.push_back(m.settings.technique);
  std::string gk = key;
  for (render::Technique t : picked) gk += " " + std::to_string(int(t));
  if (gk != r.grid_key) {
    const int cols = grid_columns(picked.size()), rows = int((picked.size() + size_t(cols) - 1) / size_t(cols));
    geom::Camera panel = r.view;
    panel.width = std::max(16, (r.fb_w - 2 * (cols - 1)) / cols);
    panel.height = std::max(16, (r.fb_h - 2 * (rows - 1)) / rows);
    Grid grid;
    if (render_grid(*r.s.state, r.s.scene, picked, panel, r.light, m.settings, true, grid, r.error)) {
      std::vector<uint8_t> rgba(size_t(grid.image.width) * grid.image.height * 4, 255);
      for (size_t i = 0; i < size_t(grid.image.width) * grid.image.height; ++i)
        for (int c = 0; c < 3; ++c) rgba[4 * i + c] = grid.image.pixels[3 * i + c];
      m.grid_texture = ui_upload_rgba(m.grid_texture, rgba.data(), grid.image.width, grid.image.height);
      m.grid_w = grid.image.width, m.grid_h = grid.image.height, m.grid_labels = grid.labels;
      for (const Figures& f : grid.figures)
        for (const std::string& l : hud_lines(f, false)) std::printf("grid: %s\n", l.c_str());
      std::fflush(stdout);
    } else {
      m.status = r.error, m.compare = false;
    }
    r.grid_key = gk;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glClearColor(0.05f, 0.05f, 0.05f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

// The current technique into the window; on E its error, the wrong pixels as an overlay.
void draw_view(WindowRun& r, const std::string& key) {
  WindowModel& m = r.m;
  const std::string name = render::technique_name(m.settings.technique);
  std::vector<render::PassTime> times;
  if (!render::render_to_window(*r.s.state, r.view, r.light, m.settings, r.fb_w, r.fb_h, times, r.error)) {
    m.status = name + ": " + r.error;
    cli::warning("%s", m.status.c_str());
    m.current = (m.current + 1) % m.all.size();
    times.clear();
  }
  m.figures.technique = m.settings.technique, m.figures.map_size = m.settings.shadow_map_size;
  m.figures.gpu_timers = r.gpu, m.figures.times = times, m.figures.message.clear();
  m.figures.projection = render::drawn_projection(*r.s.state);
  if (m.measure) {
    m.measure = false;
    std::vector<uint8_t> overlay;
    if (make_reference(r.s.scene, r.view, r.light, r.ref, r.error) &&
        measure_error(*r.s.state, r.ref, r.view, r.light, m.settings, m.figures.error, &overlay, r.error)) {
      m.overlay_texture = ui_upload_rgba(m.overlay_texture, overlay.data(), r.fb_w, r.fb_h);
      m.overlay_w = r.fb_w, m.overlay_h = r.fb_h, r.measured_key = key;
      for (const std::string& l : hud_lines(m.figures)) std::printf("hud: %s\n", l.c_str());
      std::fflush(stdout);
      // The mask pass drew into the render layer's own target; redraw the frame for the window.
      render::render_to_window(*r.s.state, r.view, r.light, m.settings, r.fb_w, r.fb_h, times, r.error);
    } else {
      m.status = r.error;
    }
  }
  if (key != r.measured_key) m.figures.error.valid = false;
}

}  // namespace

int run_window(Options& o, Session& s) {
  if (!ui_init_window()) return fail("Dear ImGui could not start on the window");
  WindowRun r(o, s);
  init_model(r);
  const render::PlatformEvents events = make_events(r);
  while (!s.platform->should_close() && !r.quit) {
    begin_frame(r);
    const std::string key = view_key(r.view, r.light, r.m.settings, r.fb_w, r.fb_h);
    if (r.fb_w > 0 && r.fb_h > 0 && r.m.compare)
      draw_grid(r, key);
    else if (r.fb_w > 0 && r.fb_h > 0)
      draw_view(r, key);
    ui_window_frame(r.m, r.fb_w, r.fb_h);
    if (r.m.quit) r.quit = true;
    if (!o.screenshot.empty() && r.script_at >= o.script.size() && ++r.frames_after_script >= 3) {
      geom::PngImage shot;
      if (!ui_read_window(r.fb_w, r.fb_h, shot) || !geom::write_png(o.screenshot, shot, r.error))
        return fail("screenshot: " + r.error);
      r.quit = true;
    }
    s.platform->swap_and_poll(events);
  }
  ui_delete_texture(r.m.overlay_texture);
  ui_delete_texture(r.m.grid_texture);
  ui_shutdown();
  return 0;
}

}  // namespace viewer
