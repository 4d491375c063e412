// Test helper for geomview's tests (test_gl_viewer*.cpp): runs the geomview of
// this build (optionally under `xvfb-run -a`) with its stdout and stderr in
// files of a scratch folder, and reads PNGs and the figures it prints.
#pragma once
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "geom/png.h"

namespace viewertest {

namespace fs = std::filesystem;

struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name)
      : dir(fs::temp_directory_path() / ("geomview_" + name + "_" + std::to_string(::getpid()))) {
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

struct ViewerRun {
  int exit_code = -1;
  std::string out, err;
  std::vector<std::string> lines(const std::string& prefix) const {  // stdout lines starting with prefix, prefix cut
    std::vector<std::string> found;
    std::istringstream in(out);
    for (std::string l; std::getline(in, l);)
      if (l.rfind(prefix, 0) == 0) found.push_back(l.substr(prefix.size()));
    return found;
  }
};

inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// `args` is pasted into a shell command line (the tests quote what needs it).
inline ViewerRun geomview(const Scratch& s, const std::string& args, const std::string& wrapper = "") {
  ViewerRun r;
  const std::string out = s / "stdout.txt", err = s / "stderr.txt";
  const std::string command = wrapper + (wrapper.empty() ? "" : " ") + "timeout 120 " + GEOMVIEW_EXE + " " + args +
                              " >" + out + " 2>" + err + " </dev/null";
  const int status = std::system(command.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out), r.err = slurp(err);
  return r;
}

inline geom::PngImage read_rgb(const std::string& path) {
  geom::PngImage image;
  std::string error;
  if (!geom::read_png(path, image, error, 3)) image = geom::PngImage();
  return image;
}

inline const uint8_t* pixel(const geom::PngImage& im, int x, int y) {
  return im.pixels.data() + (size_t(y) * im.width + x) * im.channels;
}

// True when a pixel within `radius` (Chebyshev) of (x, y) has colour `rgb` (0..1) within 3/255.
inline bool colour_near(const geom::PngImage& im, int x, int y, const float rgb[3], int radius = 1) {
  for (int v = y - radius; v <= y + radius; ++v)
    for (int u = x - radius; u <= x + radius; ++u) {
      if (u < 0 || v < 0 || u >= im.width || v >= im.height) continue;
      const uint8_t* p = pixel(im, u, v);
      bool same = true;
      for (int c = 0; c < 3; ++c) same = same && std::abs(int(p[c]) - int(rgb[c] * 255.0f + 0.5f)) <= 3;
      if (same) return true;
    }
  return false;
}

inline size_t count_colour(const geom::PngImage& im, const float rgb[3]) {
  size_t n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += colour_near(im, x, y, rgb, 0);
  return n;
}

}  // namespace viewertest
