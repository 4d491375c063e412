// options.cpp: geomview's flags (options.h), the shaders folder, the input and
// the session (context, state, camera framing, light).
#include "options.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <sstream>

#include "cli/args.h"
#include "cli/file.h"
#include "geom/baked_reader.h"
#include "geom/import.h"

namespace viewer {
namespace {

const char* kUsage =
    "Usage: geomview [FILE] [options]   (FILE: a baked .gbake container, or a mesh or scene file baked in\n"
    "                                    process; the bundled default scene when absent)\n"
    "  --technique NAME[,NAME..]  %s, or all\n"
    "  --compare NAME,NAME[,..]   a grid of 2 to 16 techniques from one camera and light, each panel labelled\n"
    "                             with technique, map size, pass time and error (or all); -o grid.png headless\n"
    "  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fovy DEG --near N --far F   the camera\n"
    "  --up-axis x|y|z            the scene's up axis for the default framing (default: z for Quake 3's\n"
    "                             .bsp and .md3, else y)\n"
    "  --light X,Y,Z,W            W=1 point light at X,Y,Z; W=0 directional light at infinity towards X,Y,Z\n"
    "  --spot DX,DY,DZ,DEG        a spot at the --light position shining along DX,DY,DZ, cone half-angle DEG\n"
    "  --shadow-map-size N        (default 1024)    --size WxH  image size (default 640x480; a grid's panel:\n"
    "                             400x300)\n"
    "  -o FILE.png                output (several techniques: -o DIR, one DIR/NAME.png per technique)\n"
    "  --output color|mask        mask: 8-bit grey, 255 lit, 0 shadow, 128 no geometry\n"
    "  --light-radius R           the *-soft techniques: the light's disc (world units; radians for a sun; default 0)\n"
    "  --frames N                 render N frames and print the time of each pass\n"
    "  --inspect                  overlay silhouette quads, topology problems, focus body, with a legend\n"
    "  --error                    measure the error against the ray-cast reference (printed; in the HUD)\n"
    "  --hud                      headless: draw the HUD (technique, passes, error) into the PNG, print it\n"
    "  --window                   open a window (default when no -o is given and a display exists)\n"
    "  --script KEYS              window: press these keys, one per frame (e.g. tti)  --screenshot FILE.png\n"
    "  --shaders DIR              the shaders/ folder (default: $GEOMVIEW_SHADERS, else\n"
    "                             %s)\n"
    "Window keys: T technique, L light type, [ ] shadow-map size, I inspection, E error, C compare grid,\n"
    "R reset camera, H panels, Esc quit; drag to orbit, right-drag or scroll to zoom.\n";

// The techniques of this build (render/techniques.def), wrapped under --technique.
std::string technique_names() {
  std::string out, line;
  for (render::Technique t : render::available_techniques()) {
    const std::string name = render::technique_name(t);
    if (!line.empty() && line.size() + 1 + name.size() > 78) out += line + "\n" + std::string(29, ' '), line.clear();
    line += (line.empty() ? "" : " ") + name;
  }
  return out + line;
}

bool parse_floats(const std::string& text, float* out, int n) {
  if (!cli::parse_floats(text, n, out)) return false;
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(out[i])) return false;
  return true;
}

glm::vec3 vec3(const float v[3]) { return glm::vec3(v[0], v[1], v[2]); }

// "a,b" or "all" into techniques; false with `error`.
bool parse_techniques(const std::vector<std::string>& lists, std::vector<render::Technique>& out, std::string& error) {
  for (const std::string& list : lists) {
    std::stringstream ss(list);
    std::string name;
    while (std::getline(ss, name, ',')) {
      if (name == "all") {
        for (auto t : render::available_techniques()) out.push_back(t);
        continue;
      }
      render::Technique t;
      if (!render::parse_technique(name, t)) {
        std::string known;
        for (auto a : render::available_techniques()) known += std::string(" ") + render::technique_name(a);
        error = "unknown technique '" + name + "' (this build has:" + known + ")";
        return false;
      }
      out.push_back(t);
    }
  }
  return true;
}

std::string self_dir() {
  char buffer[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) return "";
  buffer[n] = 0;
  return std::filesystem::path(buffer).parent_path().string();
}

}  // namespace

int fail(const std::string& message) {
  cli::error("%s", message.c_str());
  return cli::kExitFailure;
}

// BIN/../share/geom/NAME beside this program's binary, as installed wherever
// the prefix was moved (the build tree has the same layout: build/share/geom
// links to the source tree's files, viewer/CMakeLists.txt), so the binary
// holds no path of the machine it was built on.
std::string beside_binary(const std::string& name) {
  const std::string dir = self_dir();
  if (dir.empty()) return "share/geom/" + name;
  return (std::filesystem::path(dir) / ".." / "share" / "geom" / name).lexically_normal().string();
}

std::string default_shaders() { return beside_binary("shaders"); }

std::string find_shaders(const std::string& flag) {
  if (!flag.empty()) return flag;
  if (const char* env = std::getenv("GEOMVIEW_SHADERS"); env && *env) return env;
  return default_shaders();
}

int format_up_axis(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".bsp" || ext == ".md3" ? 2 : 1;
}

int parse_options(int argc, char** argv, Options& o) {
  cli::Args args(std::vector<std::string>(argv + 1, argv + argc),
                 {"--help", "-h", "--inspect", "--window", "--hud", "--error"}, {"--technique",
                                                                                 "--compare",
                                                                                 "--eye",
                                                                                 "--target",
                                                                                 "--up",
                                                                                 "--fovy",
                                                                                 "--near",
                                                                                 "--far",
                                                                                 "--light",
                                                                                 "--spot",
                                                                                 "--shadow-map-size",
                                                                                 "--size",
                                                                                 "-o",
                                                                                 "--output",
                                                                                 "--frames",
                                                                                 "--shaders",
                                                                                 "--up-axis",
                                                                                 "--script",
                                                                                 "--screenshot",
                                                                                 "--light-radius"});
  if (!args.error().empty()) return fail(args.error() + " (see geomview --help)"), cli::kExitUsage;
  if (args.has("--help") || args.has("-h")) {
    std::printf(kUsage, technique_names().c_str(), default_shaders().c_str());
    return 0;
  }
  if (args.positional().size() > 1) return fail("one input file at most");
  o.file = !args.positional().empty() ? args.positional()[0]
                                      : beside_binary("default_scene.gltf");
  std::string error;
  if (!parse_techniques(args.all("--technique"), o.techniques, error)) return fail(error);
  if (o.techniques.empty()) o.techniques.push_back(render::Technique::Pcf);
  if (args.has("--compare")) {
    if (!parse_techniques(args.all("--compare"), o.compare, error)) return fail(error);
    if (o.compare.size() < 2 || o.compare.size() > 16)
      return fail("--compare takes 2 to 16 techniques, not " + std::to_string(o.compare.size()));
  }
  o.settings.inspect = args.has("--inspect");
  const std::string output = args.get("--output", "color");
  if (output != "color" && output != "mask") return fail("--output must be color or mask, not '" + output + "'");
  o.settings.output = output == "mask" ? render::Output::Mask : render::Output::Color;
  o.settings.shadow_map_size = std::atoi(args.get("--shadow-map-size", "1024").c_str());
  o.settings.light_radius = float(std::atof(args.get("--light-radius", "0").c_str()));
  if (!(o.settings.light_radius >= 0) || o.settings.light_radius > 1e6) return fail("--light-radius must be >= 0");
  if (o.settings.shadow_map_size < 16 || o.settings.shadow_map_size > 16384)
    return fail("--shadow-map-size must be within 16..16384");
  o.frames = std::atoi(args.get("--frames", "1").c_str());
  if (o.frames < 1 || o.frames > 100000) return fail("--frames must be within 1..100000");
  o.view.width = 640, o.view.height = 480;
  if (!o.compare.empty()) o.view.width = 400, o.view.height = 300;
  if (args.has("--size")) {
    const std::string s = args.get("--size");
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 || h < 1 || w > 16384 ||
        h > 16384)
      return fail("--size must be WxH within 1..16384, not '" + s + "'");
    o.view.width = w, o.view.height = h, o.size_given = true;
  }
  if (args.has("--up-axis")) {
    const std::string a = args.get("--up-axis");
    if (a != "x" && a != "y" && a != "z") return fail("--up-axis must be x, y or z, not '" + a + "'");
    o.up_axis = a[0] - 'x';
  }
  const char* camera_names[6] = {"--eye", "--target", "--up", "--fovy", "--near", "--far"};
  for (int k = 0; k < 6; ++k)
    if (args.has(camera_names[k])) o.camera_flags[k].push_back(args.get(camera_names[k]));
  o.light_flag = args.get("--light");
  o.spot_flag = args.get("--spot");
  o.hud = args.has("--hud");
  o.error = args.has("--error");
  o.out_path = args.get("-o");
  o.script = args.get("--script");
  o.screenshot = args.get("--screenshot");
  o.shaders = find_shaders(args.get("--shaders"));
  o.window = args.has("--window") || (o.out_path.empty() && std::getenv("DISPLAY"));
  if (!o.window && o.out_path.empty())
    return fail("no display: give -o FILE.png (or run under xvfb-run with --window)");
  return -1;
}

namespace {

bool read_input(const std::string& file, std::vector<unsigned char>& baked, geom::Scene& scene, std::string& error) {
  std::vector<unsigned char> magic;
  std::string unread;
  if (cli::read_file(file, magic, unread, 8) && magic.size() == 8 &&
      std::memcmp(magic.data(), geom::baked::kMagic, 8) == 0) {
    if (!cli::read_file(file, baked, unread) || baked.empty())
      return error = file + ": cannot read the baked file", false;
    return true;
  }
  geom::ImportResult imported = geom::import_file(file);
  if (!imported.ok) return error = imported.error, false;
  for (const std::string& w : imported.scene.warnings) cli::warning("%s", w.c_str());
  scene = std::move(imported.scene);
  return true;
}

bool resolve_camera(const Options& o, geom::Camera& view, std::string& error) {
  float* vectors[3] = {view.eye, view.target, view.up};
  float* scalars[3] = {&view.fovy_deg, &view.near_plane, &view.far_plane};
  const char* names[6] = {"--eye", "--target", "--up", "--fovy", "--near", "--far"};
  for (int k = 0; k < 6; ++k)
    for (const std::string& v : o.camera_flags[k])
      if (!parse_floats(v, k < 3 ? vectors[k] : scalars[k - 3], k < 3 ? 3 : 1))
        return error = std::string(names[k]) + (k < 3 ? " needs X,Y,Z" : " needs a number"), false;
  if (!(view.fovy_deg > 0 && view.fovy_deg < 180)) return error = "--fovy must be within (0, 180) degrees", false;
  if (!(view.near_plane > 0 && view.far_plane > view.near_plane)) return error = "need 0 < --near < --far", false;
  if (glm::length(vec3(view.target) - vec3(view.eye)) == 0 ||
      glm::length(glm::cross(vec3(view.target) - vec3(view.eye), vec3(view.up))) == 0)
    return error = "--eye, --target and --up must span a view (eye != target, up not along the view)", false;
  return true;
}

bool resolve_light(const Options& o, const geom::Scene& scene, geom::Light& light, std::string& error) {
  light = geom::light_from_scene(scene.lights);
  if (!o.light_flag.empty()) {
    float v[4];
    if (!parse_floats(o.light_flag, v, 4) || (v[3] != 0 && v[3] != 1))
      return error = "--light needs X,Y,Z,W with W = 1 (point) or 0 (directional)", false;
    if (v[3] == 0 && glm::length(glm::vec3(v[0], v[1], v[2])) == 0) return error = "--light direction is zero", false;
    const double h[4] = {v[0], v[1], v[2], v[3]};
    light = geom::light_from_homogeneous(h);
  }
  if (!o.spot_flag.empty()) {
    float v[4];
    if (!parse_floats(o.spot_flag, v, 4) || !(v[3] > 0 && v[3] < 90) || glm::length(glm::vec3(v[0], v[1], v[2])) == 0)
      return error = "--spot needs DX,DY,DZ,DEG with a non-zero direction and 0 < DEG < 90", false;
    if (light.type == geom::LightType::Directional)
      return error = "--spot needs a point light position (--light X,Y,Z,1)", false;
    light.type = geom::LightType::Spot;
    for (int k = 0; k < 3; ++k) light.direction[k] = v[k];
    light.outer_cone = glm::radians(double(v[3]));
  }
  return true;
}

}  // namespace

bool open_session(Options& o, Session& s, std::string& error) {
  std::vector<unsigned char> baked;
  if (!read_input(o.file, baked, s.scene, error)) return false;
  std::string note;
  s.platform = render::Platform::open(o.window, o.view.width, o.view.height, "geomview " + o.file, note, error);
  if (!s.platform) return false;
  if (!note.empty()) cli::warning("%s", note.c_str());
  s.state = baked.empty() ? render::create_state(s.scene, o.shaders, error)
                          : render::create_state_baked(baked.data(), baked.size(), o.shaders, s.scene, error);
  if (!s.state) return error = o.file + ": " + error, false;
  s.up_axis = o.up_axis >= 0 ? o.up_axis : format_up_axis(o.file);
  o.view = framed_view(s, o.view.width, o.view.height);
  if (!resolve_camera(o, o.view, error)) return false;
  return resolve_light(o, s.scene, o.light, error);
}

geom::Camera framed_view(const Session& s, int width, int height) {
  return render::default_view(*s.state, width, height, s.up_axis);
}

}  // namespace viewer
