// Test helper for geomview's tests (test_gl_viewer*.cpp): runs the geomview of
// this build (optionally under `xvfb-run -a`) with its stdout and stderr in
// files of a scratch folder, and reads PNGs and the figures it prints.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "geom/png.h"
#include "scratch.h"

namespace viewertest {

namespace fs = std::filesystem;

// The scene the geomview tests draw (OBJ, 1-based): a ground square, a box
// standing on it and a floating plate.
//
//            ____ plate (y = 1.6)
//     ___
//    |   |  box
//  ==|===|========== ground y = 0
inline const char* const kScene =
    "v -4 0 -4\nv -4 0 4\nv 4 0 4\nv 4 0 -4\nf 1 2 3\nf 1 3 4\n"
    "v -1.5 0 -0.5\nv -0.5 0 -0.5\nv -0.5 1 -0.5\nv -1.5 1 -0.5\n"
    "v -1.5 0 0.5\nv -0.5 0 0.5\nv -0.5 1 0.5\nv -1.5 1 0.5\n"
    "f 5 10 9\nf 5 9 6\nf 11 12 13\nf 11 13 14\nf 5 11 14\nf 5 14 10\n"
    "f 6 9 13\nf 6 13 12\nf 10 14 13\nf 10 13 9\nf 5 6 12\nf 5 12 11\n"
    "v 0.5 1.6 -1\nv 0.5 1.6 0.5\nv 2 1.6 0.5\nv 2 1.6 -1\nf 13 14 15\nf 13 15 16\n";
// Its view and point light as geomview's flags.
inline const char* const kSceneView =
    "--eye 3,4,6 --target 0,0.3,0 --up 0,1,0 --fovy 50 --near 0.1 --far 100 --light 1,5,2,1";

// The positions and 0-based triangles of an OBJ text of `v x y z` and `f a b c` lines (other lines skipped).
inline void parse_obj(const char* text, std::vector<float>& positions, std::vector<uint32_t>& indices) {
  std::istringstream in(text);
  for (std::string tag; in >> tag;) {
    if (tag == "v") {
      float x, y, z;
      in >> x >> y >> z;
      positions.insert(positions.end(), {x, y, z});
    } else if (tag == "f") {
      uint32_t a, b, c;
      in >> a >> b >> c;
      indices.insert(indices.end(), {a - 1, b - 1, c - 1});
    } else {
      std::string rest;
      std::getline(in, rest);
    }
  }
}

// A scratch folder named geomview_NAME_PID (tests/scratch.h).
struct Scratch : testfs::Scratch {
  explicit Scratch(const std::string& name) : testfs::Scratch("geomview_" + name) {}
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

#ifdef GEOMVIEW_EXE  // a test that runs geomview says so (tests/CMakeLists.txt: RUNS geomview)
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
#endif

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
