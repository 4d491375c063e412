// render/platform.h: the platform glue of the apps (the only file that knows
// EGL and GLFW). Opens an OpenGL 4.5 core context:
//  - a GLFW window when one is asked for and a display can be opened;
//  - otherwise headless through EGL: by device enumeration first (finds the GPU
//    on an NVIDIA machine; hardware devices before software ones), then Mesa's
//    surfaceless platform (llvmpipe). Headless contexts have no default
//    framebuffer: everything renders into framebuffer objects.
#pragma once
#include <functional>
#include <memory>
#include <string>

namespace render {

struct PlatformEvents {
  std::function<void(int key)> key;                            // GLFW key code on press / repeat
  std::function<void(double dx, double dy, int button)> drag;  // mouse motion with a button held
  std::function<void(double dy)> scroll;
};

class Platform {
 public:
  // Opens a context; `window` asks for a GLFW window of width x height (falls back
  // to headless when no display can be opened, saying so in `note`).
  static std::unique_ptr<Platform> open(bool window, int width, int height, const std::string& title, std::string& note,
                                        std::string& error);
  virtual ~Platform() = default;
  virtual bool has_window() const = 0;
  virtual bool should_close() = 0;  // window closed (headless: never)
  virtual void framebuffer_size(int& width, int& height) = 0;
  virtual void swap_and_poll(const PlatformEvents& events) = 0;  // present and dispatch events
  virtual std::string description() const = 0;                   // "EGL surfaceless: llvmpipe ..." etc.
};

// What the current context can hold, queried from it (glGetIntegerv): the
// largest texture, cube-map face, renderbuffer and viewport. The apps check
// image, grid and shadow-map sizes against them before any work.
struct GlLimits {
  int max_texture = 0, max_cube_map = 0, max_renderbuffer = 0, max_viewport[2] = {0, 0};
  // The largest width or height an image target can have (texture, renderbuffer, viewport).
  int max_image_width() const;
  int max_image_height() const;
};
GlLimits gl_limits();

// The current context's pending GL errors, cleared: "" when none, else e.g.
// "OpenGL error 0x505 (GL_OUT_OF_MEMORY: out of GPU memory)". The apps check
// it after uploading a scene, so an upload the driver could not hold is an
// Error, not an empty image.
std::string gl_error_text();

}  // namespace render
