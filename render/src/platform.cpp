// Platform glue: EGL (device enumeration, then surfaceless Mesa) or a GLFW window.
// Facts this relies on: the display comes from eglGetPlatformDisplay with
// EGL_PLATFORM_SURFACELESS_MESA (eglGetDisplay(EGL_DEFAULT_DISPLAY) fails without
// X) or from device enumeration (EGL_PLATFORM_DEVICE_EXT, the path that finds an
// NVIDIA GPU); surfaceless has no default framebuffer (render into FBOs, config
// with EGL_PBUFFER_BIT); glfwInit fails without DISPLAY, so fall back to EGL.
#include "render/platform.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace render {
namespace {

class EglPlatform : public Platform {
 public:
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string what;
  ~EglPlatform() override {
    if (display != EGL_NO_DISPLAY) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
      eglTerminate(display);
    }
  }
  bool has_window() const override { return false; }
  bool should_close() override { return false; }
  void framebuffer_size(int& w, int& h) override { w = h = 0; }
  void swap_and_poll(const PlatformEvents&) override {}
  std::string description() const override { return what; }

  // Initializes `d` and makes a 4.5 core context current on it, without surface.
  bool try_display(EGLDisplay d, const std::string& name) {
    EGLint major = 0, minor = 0;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) return false;
    const char* extensions = eglQueryString(d, EGL_EXTENSIONS);
    if (!eglBindAPI(EGL_OPENGL_API) || !extensions || !std::strstr(extensions, "EGL_KHR_surfaceless_context")) {
      eglTerminate(d);
      return false;
    }
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(d, config_attribs, &config, 1, &count) || count < 1) config = nullptr;
    const EGLint context_attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext c = eglCreateContext(d, config, EGL_NO_CONTEXT, context_attribs);
    if (c == EGL_NO_CONTEXT || !eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
      if (c != EGL_NO_CONTEXT) eglDestroyContext(d, c);
      eglTerminate(d);
      return false;
    }
    display = d, context = c, what = "EGL " + name;
    return true;
  }
};

class GlfwPlatform : public Platform {
 public:
  GLFWwindow* window = nullptr;
  const PlatformEvents* events = nullptr;
  double last_x = 0, last_y = 0;
  ~GlfwPlatform() override {
    if (window) glfwDestroyWindow(window);
    glfwTerminate();
  }
  bool has_window() const override { return true; }
  bool should_close() override { return glfwWindowShouldClose(window); }
  void framebuffer_size(int& w, int& h) override { glfwGetFramebufferSize(window, &w, &h); }
  void swap_and_poll(const PlatformEvents& e) override {
    events = &e;
    glfwSwapBuffers(window);
    glfwPollEvents();
    double x = 0, y = 0;
    glfwGetCursorPos(window, &x, &y);
    for (int button : {GLFW_MOUSE_BUTTON_LEFT, GLFW_MOUSE_BUTTON_RIGHT})
      if (glfwGetMouseButton(window, button) == GLFW_PRESS && e.drag && (x != last_x || y != last_y))
        e.drag(x - last_x, y - last_y, button == GLFW_MOUSE_BUTTON_LEFT ? 0 : 1);
    last_x = x, last_y = y;
    events = nullptr;
  }
  std::string description() const override { return "GLFW window"; }
};

std::unique_ptr<Platform> open_egl(std::string& error) {
  auto p = std::make_unique<EglPlatform>();
  // 1. Device enumeration: hardware devices first (the GPU of an NVIDIA machine).
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_device_string =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (query_devices && get_platform_display) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices(16, devices, &count) && count > 0) {
      for (int pass = 0; pass < 2; ++pass)
        for (EGLint i = 0; i < count; ++i) {
          const char* ext = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
          const bool software = ext && std::strstr(ext, "EGL_MESA_device_software");
          if (software != (pass == 1)) continue;
          EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
          if (p->try_display(d, std::string("device ") + std::to_string(i) + (software ? " (software)" : ""))) return p;
        }
    }
  }
  // 2. Mesa surfaceless.
  if (get_platform_display &&
      p->try_display(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), "surfaceless"))
    return p;
  error = "no OpenGL 4.5 core context through EGL (device enumeration and surfaceless both failed)";
  return nullptr;
}

}  // namespace

std::unique_ptr<Platform> Platform::open(bool window, int width, int height, const std::string& title,
                                         std::string& note, std::string& error) {
  if (window) {
    glfwSetErrorCallback(nullptr);
    if (glfwInit()) {
      glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
      glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
      glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
      glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
      GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
      if (w) {
        auto p = std::make_unique<GlfwPlatform>();
        p->window = w;
        glfwMakeContextCurrent(w);
        glfwSwapInterval(1);
        glfwSetWindowUserPointer(w, p.get());
        glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
          auto* self = static_cast<GlfwPlatform*>(glfwGetWindowUserPointer(win));
          if (action != GLFW_RELEASE && self->events && self->events->key) self->events->key(key);
        });
        glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
          auto* self = static_cast<GlfwPlatform*>(glfwGetWindowUserPointer(win));
          if (self->events && self->events->scroll) self->events->scroll(dy);
        });
        return p;
      }
      glfwTerminate();
      note = "no OpenGL 4.5 window could be opened; rendering headless";
    } else {
      note = "no display; rendering headless";
    }
  }
  return open_egl(error);
}

}  // namespace render
