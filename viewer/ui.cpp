// ui.cpp: the one file that includes Dear ImGui (ui.h): the window's panels
// (technique, light, map size, inspection, camera, error, compare grid), the
// HUD and the legend; headless labels through an offscreen framebuffer.
#define GL_GLEXT_PROTOTYPES 1
#include "ui.h"

#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace viewer {
namespace {

ImU32 colour(const float rgb[3], float alpha = 1) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(rgb[0], rgb[1], rgb[2], alpha));
}

// A readable font at 100%: DejaVu Sans Mono when installed, else ImGui's own.
void load_font() {
  ImGuiIO& io = ImGui::GetIO();
  const char* path = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf";
  if (std::filesystem::exists(path) && io.Fonts->AddFontFromFileTTF(path, 15.0f)) return;
  ImFontConfig config;
  config.SizePixels = 13;
  io.Fonts->AddFontDefault(&config);
}

void begin_context() {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  load_font();
}

// Label boxes on a draw list: a dark translucent box, a swatch per line where given.
void draw_label(ImDrawList* list, const Label& label) {
  const float pad = 5, line_h = ImGui::GetTextLineHeight() + 2, swatch = ImGui::GetTextLineHeight() - 2;
  float width = 0;
  for (size_t i = 0; i < label.lines.size(); ++i) {
    const bool has = i < label.swatches.size() && label.swatches[i][3] > 0;
    width = std::max(width, ImGui::CalcTextSize(label.lines[i].c_str()).x + (has ? swatch + 6 : 0));
  }
  const bool clipped = label.clip[2] > label.clip[0];
  if (clipped)
    list->PushClipRect(ImVec2(float(label.clip[0]), float(label.clip[1])),
                       ImVec2(float(label.clip[2]), float(label.clip[3])), true);
  const ImVec2 a(float(label.x), float(label.y));
  const ImVec2 b(a.x + width + 2 * pad, a.y + line_h * float(label.lines.size()) + 2 * pad - 2);
  list->AddRectFilled(a, b, IM_COL32(0, 0, 0, 190), 3);
  for (size_t i = 0; i < label.lines.size(); ++i) {
    float x = a.x + pad;
    const float y = a.y + pad + line_h * float(i);
    if (i < label.swatches.size() && label.swatches[i][3] > 0) {
      list->AddRectFilled(ImVec2(x, y + 2), ImVec2(x + swatch, y + 2 + swatch), colour(label.swatches[i].data()));
      x += swatch + 6;
    }
    list->AddText(ImVec2(x, y), i == 0 ? IM_COL32(255, 255, 255, 255) : IM_COL32(225, 228, 235, 255),
                  label.lines[i].c_str());
  }
  if (clipped) list->PopClipRect();
}

std::array<float, 4> swatch(render::InspectKind kind) {
  std::array<float, 4> c{0, 0, 0, 1};
  render::inspection_colour(kind, c.data());
  return c;
}

}  // namespace

Label legend_label(const render::InspectionCounts& c, int x, int y) {
  Label l;
  l.x = x, l.y = y;
  auto line = [&](render::InspectKind kind, const std::string& text) {
    l.lines.push_back(text);
    l.swatches.push_back(swatch(kind));
  };
  l.lines.push_back("inspection (topology report)");
  l.swatches.push_back({0, 0, 0, 0});
  auto counted = [&](render::InspectKind kind, const char* name, uint64_t report, uint64_t drawn) {
    std::string text = std::string(name) + " " + std::to_string(report);
    if (drawn != report) text += " (" + std::to_string(drawn) + " drawn in " + std::to_string(c.casters) + " casters)";
    line(kind, text);
  };
  counted(render::InspectKind::Boundary, "boundary edges", c.report.boundary_edges, c.drawn.boundary_edges);
  counted(render::InspectKind::NonManifold, "non-manifold edges", c.report.non_manifold_edges,
          c.drawn.non_manifold_edges);
  counted(render::InspectKind::Inconsistent, "inconsistent edges", c.report.inconsistent_edges,
          c.drawn.inconsistent_edges);
  counted(render::InspectKind::Degenerate, "degenerate faces", c.report.degenerate_faces, c.drawn.degenerate_faces);
  line(render::InspectKind::Silhouette, "silhouette quads (this light)");
  line(render::InspectKind::FocusBody, "focus body H (psm, lispsm, uniform)");
  return l;
}

unsigned ui_upload_rgba(unsigned texture, const uint8_t* rgba, int w, int h) {
  if (texture) glDeleteTextures(1, &texture);
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA8, w, h);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return texture;
}

void ui_delete_texture(unsigned texture) {
  if (texture) glDeleteTextures(1, &texture);
}

namespace {

// Reads the bound read framebuffer (w x h) into RGB, top row first.
void read_rgb(int w, int h, geom::PngImage& image) {
  std::vector<uint8_t> rgba(size_t(w) * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  image.width = w, image.height = h, image.channels = 3;
  image.pixels.resize(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) image.pixels[(size_t(y) * w + x) * 3 + c] = rgba[(size_t(h - 1 - y) * w + x) * 4 + c];
}

}  // namespace

bool ui_read_window(int w, int h, geom::PngImage& image) {
  if (w <= 0 || h <= 0) return false;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  read_rgb(w, h, image);
  return glGetError() == GL_NO_ERROR;
}

bool draw_labels(geom::PngImage& image, const std::vector<Label>& labels, std::string& error) {
  const int w = image.width, h = image.height;
  if (w <= 0 || h <= 0 || (image.channels != 1 && image.channels != 3))
    return error = "labels: an RGB or grey image is needed", false;
  static bool ready = false;
  if (!ready) {
    begin_context();
    if (!ImGui_ImplOpenGL3_Init("#version 450")) return error = "ImGui's OpenGL 3 backend did not start", false;
    ready = true;
  }
  std::vector<uint8_t> rgba(size_t(w) * h * 4);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < 4; ++c)
      rgba[4 * i + c] = c == 3 ? 255 : image.pixels[i * image.channels + (image.channels == 3 ? c : 0)];
  const GLuint source = ui_upload_rgba(0, rgba.data(), w, h);
  GLuint target = 0, fbo = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &target);
  glTextureStorage2D(target, 1, GL_RGBA8, w, h);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, w, h);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(w), float(h));
  io.DisplayFramebufferScale = ImVec2(1, 1);
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  ImDrawList* list = ImGui::GetBackgroundDrawList();
  list->AddImage(reinterpret_cast<ImTextureID>(intptr_t(source)), ImVec2(0, 0), ImVec2(float(w), float(h)));
  for (const Label& l : labels) draw_label(list, l);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  read_rgb(w, h, image);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &target);
  ui_delete_texture(source);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    char b[64];
    std::snprintf(b, sizeof b, "labels: OpenGL error 0x%x", e);
    return error = b, false;
  }
  return true;
}

bool ui_init_window() {
  GLFWwindow* window = glfwGetCurrentContext();
  if (!window) return false;
  begin_context();
  return ImGui_ImplGlfw_InitForOpenGL(window, true) && ImGui_ImplOpenGL3_Init("#version 450");
}

void ui_shutdown() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

bool ui_wants_mouse() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse; }
bool ui_wants_keyboard() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard; }

namespace {

void controls(WindowModel& m, int width) {
  const float panel_w = 290;
  ImGui::SetNextWindowPos(ImVec2(std::max(0.0f, float(width) - panel_w - 10), 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(panel_w, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("geomview (H hides)");
  ImGui::PushItemWidth(130);
  std::string current = render::technique_name(m.all[m.current]);
  if (ImGui::BeginCombo("technique (T)", current.c_str())) {
    for (size_t i = 0; i < m.all.size(); ++i)
      if (ImGui::Selectable(render::technique_name(m.all[i]), i == m.current)) m.current = i;
    ImGui::EndCombo();
  }
  const char* kinds[3] = {"point", "spot", "directional"};
  if (ImGui::Combo("light (L)", &m.light_kind, kinds, 3)) m.light_changed = true;
  if (ImGui::DragFloat3(m.light_kind == 2 ? "towards" : "position", m.light_position, 0.05f)) m.light_changed = true;
  int log2 = 0;
  while ((1 << (log2 + 1)) <= m.settings.shadow_map_size) ++log2;
  if (ImGui::SliderInt("map size ([ ])", &log2, 6, 13, "")) m.settings.shadow_map_size = 1 << log2;
  ImGui::SameLine();
  ImGui::Text("%d", m.settings.shadow_map_size);
  ImGui::Checkbox("inspection (I)", &m.settings.inspect);
  if (ImGui::Button("reset camera (R)")) m.reset_camera = true;
  ImGui::SameLine();
  if (ImGui::Button("measure error (E)")) m.measure = true;
  ImGui::Checkbox("error overlay", &m.show_error_overlay);
  ImGui::Checkbox("compare grid (C)", &m.compare);
  if (m.compare && ImGui::TreeNode("grid techniques")) {
    for (size_t i = 0; i < m.all.size(); ++i) {
      bool pick = m.compare_pick[i];
      if (ImGui::Checkbox(render::technique_name(m.all[i]), &pick)) m.compare_pick[i] = pick;
      if (i % 3 != 2 && i + 1 < m.all.size()) ImGui::SameLine();
    }
    ImGui::TreePop();
  }
  if (!m.status.empty()) ImGui::TextWrapped("%s", m.status.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace

void ui_window_frame(WindowModel& m, int width, int height) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  ImDrawList* back = ImGui::GetBackgroundDrawList();
  if (m.compare && m.grid_texture) {
    back->AddImage(reinterpret_cast<ImTextureID>(intptr_t(m.grid_texture)), ImVec2(0, 0),
                   ImVec2(float(m.grid_w), float(m.grid_h)));
    for (const Label& l : m.grid_labels) draw_label(back, l);
  } else {
    if (m.show_error_overlay && m.overlay_texture && m.figures.error.valid && m.overlay_w == width &&
        m.overlay_h == height)
      back->AddImage(reinterpret_cast<ImTextureID>(intptr_t(m.overlay_texture)), ImVec2(0, 0),
                     ImVec2(float(width), float(height)));
    // The HUD: top left, always on.
    Label hud;
    hud.lines = hud_lines(m.figures);
    hud.x = 10, hud.y = 10;
    draw_label(back, hud);
    if (m.settings.inspect && m.counts_valid) draw_label(back, legend_label(m.counts, 10, height - 150));
  }
  if (m.show_panels) controls(m, width);
  ImGui::Render();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace viewer
