// geombake focus FRAME.json: the focus body and shadow matrix the toolkit
// computes for one frame (geom/focus.h), as JSON on stdout, so an engine's
// programmer can paste a frame and compare. Input:
//   {"camera": {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z],
//               "fovy_degrees": 60, "aspect": 1.5, "near": 0.1, "far": 100 (null: infinite)},
//    "light": {"type": "directional" | "point" | "spot", "position": [..], "direction": [..],
//              "spot_angle_degrees": 30, "range": 50},   (only the keys the type needs)
//    "scene_bounds": {"min": [..], "max": [..]},
//    "receiver_bounds": {"min": [..], "max": [..]},      (optional)
//    "method": "psm" | "lispsm" | "uniform",             (optional, default psm)
//    "cube_cone_degrees": 120,                           (optional: six faces for a point light wider than this)
//    "min_warp_gain": 0.75}                              (optional: FocusOptions::min_warp_gain)
// Bad JSON, anything after the JSON value (a NUL byte included), a missing key
// or an invalid frame (outside the limits of cli/view_check.h: coordinates
// within 1e15, fovy within 0.001..179.9 degrees, aspect within 1e-5..1e5):
// `Error: FILE: ...`, exit 1. Every matrix printed is finite and not singular:
// where the method's is not, the uniform one is, with fallback_kind
// "unusable_matrix"; where neither is, the frame is an error.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cli/args.h"
#include "cli/file.h"
#include "cli/view_check.h"
#include "geom/focus.h"
#include "geombake/command.h"

namespace geombake {
namespace {

using Json = nlohmann::json;

const char* kFocusHelp =
    "usage: geombake focus FRAME.json\n"
    "  Prints, as JSON, the focus body H and the world-to-shadow-clip matrix (column-major)\n"
    "  of a camera, a light and the scene bounds: method, fallback (null or the reason),\n"
    "  light_kind, camera_shift, focus_vertices, focus_faces, matrix, and for a point light among the\n"
    "  receivers the six fitted cube faces (faces: matrix, near, far, empty, method, focused).\n";

struct BadFrame : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const Json& member(const Json& obj, const char* parent, const char* key) {
  if (!obj.is_object()) throw BadFrame(std::string(parent) + ": expected an object");
  auto it = obj.find(key);
  if (it == obj.end()) throw BadFrame(std::string("missing key ") + parent + "." + key);
  return *it;
}

double number(const Json& obj, const char* parent, const char* key) {
  const Json& v = member(obj, parent, key);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw BadFrame(std::string(parent) + "." + key + ": expected a finite number");
  return v.get<double>();
}

void vec3(const Json& obj, const char* parent, const char* key, double out[3]) {
  const Json& v = member(obj, parent, key);
  if (!v.is_array() || v.size() != 3) throw BadFrame(std::string(parent) + "." + key + ": expected 3 numbers");
  for (int k = 0; k < 3; ++k) {
    if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
      throw BadFrame(std::string(parent) + "." + key + ": expected 3 finite numbers");
    out[k] = v[k].get<double>();
  }
}

geom::FocusBox box(const Json& obj, const char* parent) {
  geom::FocusBox b;
  vec3(obj, parent, "min", b.min);
  vec3(obj, parent, "max", b.max);
  for (int k = 0; k < 3; ++k)
    if (std::fabs(b.min[k]) > cli::kMaxCoordinate || std::fabs(b.max[k]) > cli::kMaxCoordinate)
      throw BadFrame(std::string(parent) + ": a coordinate is over the limit of +-1e15");
  return b;
}

// The frame's text: JSON and nothing else. nlohmann's parser stops at a NUL
// byte as at the end of the input, so a NUL (and whatever follows it) is
// refused here; anything else after the value is refused by the parser.
void check_frame_text(const std::string& text) {
  const size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw BadFrame("a NUL byte at offset " + std::to_string(nul) + ": a frame is JSON text and nothing after it");
}

// A matrix a shadow pass can use: every entry finite and not singular (its
// determinant not below 1e-12 of the product of its column lengths, the
// largest it can be: Hadamard's bound).
bool usable_matrix(const double m[16]) {
  double bound = 1;
  for (int c = 0; c < 4; ++c) {
    double l = 0;
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[4 * c + r])) return false;
      l += m[4 * c + r] * m[4 * c + r];
    }
    bound *= std::sqrt(l);
  }
  auto at = [&](int r, int c) { return m[4 * c + r]; };
  double det = 0;
  for (int c = 0; c < 4; ++c) {  // Laplace along the first row
    double minor[9];
    int k = 0;
    for (int r = 1; r < 4; ++r)
      for (int cc = 0; cc < 4; ++cc)
        if (cc != c) minor[k++] = at(r, cc);
    const double d3 = minor[0] * (minor[4] * minor[8] - minor[5] * minor[7]) -
                      minor[1] * (minor[3] * minor[8] - minor[5] * minor[6]) +
                      minor[2] * (minor[3] * minor[7] - minor[4] * minor[6]);
    det += (c % 2 ? -1 : 1) * at(0, c) * d3;
  }
  return std::isfinite(det) && bound > 0 && std::fabs(det) > 1e-12 * bound;
}

// One frame as FRAME.json states it, checked against the limits of cli/view_check.h.
struct Frame {
  double eye[3], target[3], up[3], fovy = 0, aspect = 0, near_d = 0, far_d = 0;
  geom::Light light;
  geom::FocusBox scene, receivers;
  geom::FocusOptions options;  // options.receivers points at `receivers` when given
};

void read_camera(const Json& frame, Frame& f) {
  const Json& cam = member(frame, "frame", "camera");
  vec3(cam, "camera", "eye", f.eye);
  vec3(cam, "camera", "target", f.target);
  vec3(cam, "camera", "up", f.up);
  f.fovy = number(cam, "camera", "fovy_degrees"), f.aspect = number(cam, "camera", "aspect");
  f.near_d = number(cam, "camera", "near");
  f.far_d = member(cam, "camera", "far").is_null() ? HUGE_VAL : number(cam, "camera", "far");
  std::string problem;  // the limits of every program's cameras (cli/view_check.h)
  if (!cli::check_view({f.eye, f.target, f.up, f.fovy, f.aspect, f.near_d, f.far_d, true, false}, "camera", problem))
    throw BadFrame(problem);
}

geom::Light read_light(const Json& frame) {
  const Json& lj = member(frame, "frame", "light");
  geom::Light light;
  const Json& type = member(lj, "light", "type");
  std::string t = type.is_string() ? type.get<std::string>() : "";
  if (t == "directional") {
    light.type = geom::LightType::Directional;
    vec3(lj, "light", "direction", light.direction);
  } else if (t == "point" || t == "spot") {
    light.type = t == "point" ? geom::LightType::Point : geom::LightType::Spot;
    vec3(lj, "light", "position", light.position);
    if (lj.contains("range")) light.range = number(lj, "light", "range");
    if (light.range < 0) throw BadFrame("light.range: must not be negative");
    if (t == "spot") {
      vec3(lj, "light", "direction", light.direction);
      double a = number(lj, "light", "spot_angle_degrees");
      if (!(a > 0 && a <= 90)) throw BadFrame("light.spot_angle_degrees: must lie in (0, 90]");
      light.outer_cone = a * 3.14159265358979323846 / 180;
    }
  } else {
    throw BadFrame("light.type: expected \"directional\", \"point\" or \"spot\"");
  }
  std::string problem;
  if (!cli::check_light(light, "light", problem)) throw BadFrame(problem);
  return light;
}

// The optional keys: receiver_bounds, min_warp_gain, cube_cone_degrees, method.
void read_options(const Json& frame, Frame& f) {
  geom::FocusOptions& options = f.options;
  if (frame.contains("receiver_bounds")) {
    f.receivers = box(frame["receiver_bounds"], "receiver_bounds");
    options.receivers = &f.receivers;
  }
  if (frame.contains("min_warp_gain")) {
    options.min_warp_gain = number(frame, "frame", "min_warp_gain");
    if (!(options.min_warp_gain >= 0 && options.min_warp_gain <= 1))
      throw BadFrame("min_warp_gain: must lie in [0, 1]");
  }
  if (frame.contains("cube_cone_degrees")) {
    options.cube_cone_degrees = number(frame, "frame", "cube_cone_degrees");
    if (!(options.cube_cone_degrees >= 0 && options.cube_cone_degrees < 360))
      throw BadFrame("cube_cone_degrees: must lie in [0, 360)");
  }
  if (frame.contains("method")) {
    const Json& m = frame["method"];
    std::string name = m.is_string() ? m.get<std::string>() : "";
    if (name == "psm")
      options.method = geom::FocusMethod::Psm;
    else if (name == "lispsm")
      options.method = geom::FocusMethod::Lispsm;
    else if (name == "uniform")
      options.method = geom::FocusMethod::Uniform;
    else
      throw BadFrame("method: expected \"psm\", \"lispsm\" or \"uniform\"");
  }
}

// The frame's text, parsed and checked in the order of its keys' use.
void read_frame(const std::string& text, Frame& f) {
  check_frame_text(text);
  Json frame = Json::parse(text);  // throws on bad JSON and on anything after the value
  read_camera(frame, f);
  f.light = read_light(frame);
  f.scene = box(member(frame, "frame", "scene_bounds"), "scene_bounds");
  read_options(frame, f);
}

// The focus of the frame. The matrix a frame gives must be usable; where the
// method's is not, the uniform matrix of the same frame is (fallback_kind
// "unusable_matrix"); where that is not either, the frame is an error.
// Returns the fallback kind.
const char* focus_frame(const Frame& f, geom::FocusResult& r) {
  geom::CameraMatrices camera = geom::camera_look_at(f.eye, f.target, f.up, f.fovy, f.aspect, f.near_d, f.far_d);
  if (!geom::compute_focus(camera, f.light, f.scene, f.options, r))
    throw BadFrame(std::string("invalid frame: ") + r.reason);
  const char* fallback_kind = geom::focus_fallback_name(r.fallback);
  if (!usable_matrix(r.matrix)) {
    geom::FocusOptions uniform = f.options;
    uniform.method = geom::FocusMethod::Uniform;
    if (!geom::compute_focus(camera, f.light, f.scene, uniform, r) || !usable_matrix(r.matrix))
      throw BadFrame("no usable shadow matrix for this frame (not finite or singular, uniform too)");
    r.reason = "the method's matrix was not finite or singular: uniform used";
    fallback_kind = "unusable_matrix";
  }
  return fallback_kind;
}

std::string num(double v) {
  char buf[32];
  if (!std::isfinite(v)) return std::string("null");
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return std::string(buf);
}
std::string str(const char* text) { return Json(text).dump(); }
std::string numbers16(const double m[16]) {
  std::string o;
  for (int i = 0; i < 16; ++i) o += (i ? ", " : "") + num(m[i]);
  return o;
}

// focus_vertices, focus_faces, matrix and faces: the geometry of the result.
std::string geometry_json(const geom::FocusResult& r) {
  std::string o = "  \"focus_vertices\": [";
  for (size_t i = 0; i < r.vertex_count(); ++i)
    o += std::string(i ? ",\n    [" : "\n    [") + num(r.vertices[3 * i]) + ", " + num(r.vertices[3 * i + 1]) + ", " +
         num(r.vertices[3 * i + 2]) + "]";
  o += r.vertex_count() ? "\n  ],\n" : "],\n";
  o += "  \"focus_faces\": [";
  size_t base = 0;
  for (size_t f = 0; f < r.face_sizes.size(); ++f) {
    o += f ? ", [" : "[";
    for (uint32_t i = 0; i < r.face_sizes[f]; ++i) o += (i ? ", " : "") + std::to_string(r.face_indices[base + i]);
    o += "]";
    base += r.face_sizes[f];
  }
  o += "],\n  \"matrix\": [" + numbers16(r.matrix);
  // A point light's six fitted cube faces (+X -X +Y -Y +Z -Z); [] when one map serves.
  o += "],\n  \"faces\": [";
  for (int f = 0; r.cube && f < 6; ++f) {
    const geom::FocusFace& face = r.cube_faces[f];
    o += std::string(f ? ",\n" : "\n") + "    {\"matrix\": [" + numbers16(face.matrix);
    o += "], \"near\": " + num(face.near) + ", \"far\": " + num(face.far) +
         ", \"empty\": " + (face.empty ? "true" : "false") +
         ", \"method\": " + str(geom::focus_method_name(face.method)) + ", \"focused\": [" + numbers16(face.focused);
    o += "]}";
  }
  o += r.cube ? "\n  ]\n}\n" : "]\n}\n";
  return o;
}

// Compact output: one key per line, number arrays on one line.
std::string focus_json(const geom::FocusResult& r, const geom::FocusOptions& options, const char* fallback_kind) {
  std::string o = "{\n";
  o += "  \"method\": " + str(geom::focus_method_name(r.method)) + ",\n";
  o += "  \"requested_method\": " + str(geom::focus_method_name(options.method)) + ",\n";
  o += "  \"fallback\": " + (std::string(fallback_kind) == "none" ? std::string("null") : str(r.reason)) + ",\n";
  o += "  \"fallback_kind\": " + str(fallback_kind) + ",\n";
  o += "  \"light_kind\": " + str(geom::light_kind_name(r.light_kind)) + ",\n";
  o += "  \"psm_light_kind\": " + str(geom::light_kind_name(r.psm_light_kind)) + ",\n";
  o += std::string("  \"needs_cube_map\": ") + (r.needs_cube_map ? "true" : "false") + ",\n";
  o += "  \"light_near\": " + num(r.light_near) + ",\n";
  o += std::string("  \"near_floor_cut\": ") + (r.near_floor_cut ? "true" : "false") + ",\n";
  o += "  \"camera_shift\": " + num(r.camera_shift) + ",\n";
  o += "  \"psm_near\": " + num(r.psm_near) + ",\n";
  o += "  \"psm_far\": " + num(r.psm_far) + ",\n";
  o += "  \"lispsm_n\": " + num(r.lispsm_n) + ",\n";
  return o + geometry_json(r);
}

int run_focus(const std::vector<std::string>& argv) {
  cli::Args args(argv, {"--help", "-h"}, {});
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kFocusHelp, stdout);
    return 0;
  }
  if (!args.error().empty() || args.positional().size() != 1) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().empty() ? "expected one FRAME.json" : args.error().c_str(),
                 kFocusHelp);
    return 2;
  }
  const std::string& file = args.positional()[0];
  std::string text, problem;
  if (!cli::read_file(file, text, problem)) {
    std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), problem.c_str());
    return 1;
  }
  try {
    Frame frame;
    read_frame(text, frame);
    geom::FocusResult r;
    const char* fallback_kind = focus_frame(frame, r);
    const std::string o = focus_json(r, frame.options, fallback_kind);
    std::fwrite(o.data(), 1, o.size(), stdout);
    return 0;
  } catch (const std::exception& e) {  // nlohmann parse errors and BadFrame
    std::fprintf(stderr, "Error: %s: %s\n", file.c_str(), e.what());
    return 1;
  }
}

GEOMBAKE_COMMAND("focus", "focus body and shadow matrix of one frame (JSON in, JSON out)", run_focus);

}  // namespace
}  // namespace geombake
