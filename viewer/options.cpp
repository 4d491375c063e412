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
#include "cli/output.h"
#include "cli/view_check.h"
#include "geom/baked_file.h"
#include "geom/baked_reader.h"
#include "geom/import.h"

namespace viewer {
namespace {

const char* kUsage =
    "Usage: geomview [FILE] [options]   (FILE: a baked .gbake container, or a mesh or scene file baked in\n"
    "                                    process; the bundled default scene when absent)\n"
    "  --technique NAME[,NAME..]  %s, or all\n"
    "                             (esm: extended shadow maps, Bujnak 2004; not exponential shadow maps)\n"
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

// "a,b" or "all" into techniques; false with `error` (naming `flag`) on an
// unknown or empty name.
bool parse_techniques(const char* flag, const std::vector<std::string>& lists, std::vector<render::Technique>& out,
                      std::string& error) {
  for (const std::string& list : lists) {
    std::vector<std::string> names;
    if (!cli::parse_list(list, names))
      return error = std::string(flag) + ": '" + list + "' is not a comma-separated list of technique names", false;
    for (const std::string& name : names) {
      if (name == "all") {
        for (auto t : render::available_techniques()) out.push_back(t);
        continue;
      }
      render::Technique t;
      if (!render::parse_technique(name, t)) {
        std::string known;
        for (auto a : render::available_techniques()) known += std::string(" ") + render::technique_name(a);
        error = std::string(flag) + ": unknown technique '" + name + "' (this build has:" + known + ")";
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

namespace {

// The numbers and names of the command line, each strictly (cli/args.h): the
// flag is named in the error, and nothing out of range is wrapped or clamped.
bool parse_values(const cli::Args& args, Options& o, std::string& error) {
  o.settings.inspect = args.has("--inspect");
  const std::string output = args.get("--output", "color");
  if (output != "color" && output != "mask")
    return error = "--output must be color or mask, not '" + output + "'", false;
  o.settings.output = output == "mask" ? render::Output::Mask : render::Output::Color;
  double radius = 0;
  if (!cli::int_option(args, "--shadow-map-size", kMinMapSize, kMaxMapSize, o.settings.shadow_map_size, error) ||
      !cli::real_option(args, "--light-radius", 0, 1e6, radius, error) ||
      !cli::int_option(args, "--frames", 1, 100000, o.frames, error))
    return false;
  o.settings.light_radius = float(radius);
  o.view.width = 640, o.view.height = 480;
  if (!o.compare.empty()) o.view.width = 400, o.view.height = 300;
  if (!cli::size_option(args, "--size", 1, kMaxImageSize, o.view.width, o.view.height, error)) return false;
  o.size_given = args.has("--size");
  if (args.has("--up-axis")) {
    const std::string a = args.get("--up-axis");
    if (a != "x" && a != "y" && a != "z") return error = "--up-axis must be x, y or z, not '" + a + "'", false;
    o.up_axis = a[0] - 'x';
  }
  const char* camera_names[6] = {"--eye", "--target", "--up", "--fovy", "--near", "--far"};
  for (int k = 0; k < 6; ++k)
    if (args.has(camera_names[k])) o.camera_flags[k].push_back(args.get(camera_names[k]));
  o.light_flag = args.has("--light") ? args.get("--light") : "";
  o.spot_flag = args.has("--spot") ? args.get("--spot") : "";
  if ((args.has("--light") && o.light_flag.empty()) || (args.has("--spot") && o.spot_flag.empty()))
    return error = std::string(o.light_flag.empty() && args.has("--light") ? "--light" : "--spot") + ": empty value",
           false;
  return true;
}

// The techniques (--technique, --compare), the output and the window.
bool parse_modes(const cli::Args& args, Options& o, std::string& error) {
  if (args.has("--technique") && !parse_techniques("--technique", args.all("--technique"), o.techniques, error))
    return false;
  if (o.techniques.empty()) o.techniques.push_back(render::Technique::Pcf);
  if (args.has("--compare")) {
    if (!parse_techniques("--compare", args.all("--compare"), o.compare, error)) return false;
    if (o.compare.size() < 2 || o.compare.size() > 16)
      return error = "--compare takes 2 to 16 techniques, not " + std::to_string(o.compare.size()), false;
  }
  o.hud = args.has("--hud");
  o.error = args.has("--error");
  o.out_path = args.get("-o");
  o.script = args.get("--script");
  o.screenshot = args.get("--screenshot");
  for (const char* name : {"-o", "--script", "--screenshot", "--shaders"})
    if (args.has(name) && args.get(name).empty()) return error = std::string(name) + ": empty value", false;
  o.shaders = find_shaders(args.get("--shaders"));
  o.window = args.has("--window") || (o.out_path.empty() && std::getenv("DISPLAY"));
  if (!o.window && o.out_path.empty())
    return error = "no display: give -o FILE.png (or run under xvfb-run with --window)", false;
  if (!o.out_path.empty() && !cli::check_output_path(o.out_path, o.compare.empty() && o.techniques.size() > 1, error))
    return false;
  if (!o.screenshot.empty() && !cli::check_output_path(o.screenshot, false, error)) return false;
  if (!o.window && (args.has("--script") || args.has("--screenshot")))
    return error = std::string(args.has("--script") ? "--script" : "--screenshot") +
                   " needs a window (--window, and a display); headless runs write -o FILE.png",
           false;
  return true;
}

}  // namespace

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
  if (args.positional().size() > 1) return fail("one input file at most"), cli::kExitUsage;
  o.file = !args.positional().empty() ? args.positional()[0] : beside_binary("default_scene.gltf");
  std::string error;
  if (!parse_modes(args, o, error) || !parse_values(args, o, error)) return fail(error), cli::kExitUsage;
  return -1;
}

namespace {

// The bytes of a baked file are read only after its header's size matched the
// file (geom/baked_reader.h) and fits the memory this process may take.
uint64_t baked_size_limit() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  const uint64_t memory = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : uint64_t(1) << 32;
  return std::min<uint64_t>(memory / 4, uint64_t(1) << 34);  // the file, its GL copy and the scene's copy fit
}

// Every coordinate of an imported scene within the limit of the float pipeline.
bool check_positions(const std::string& file, const geom::Scene& scene, std::string& error) {
  for (size_t i = 0; i < scene.positions.size(); ++i)
    if (!(std::fabs(scene.positions[i]) <= cli::kMaxCoordinate))
      return error = file + ": vertex " + std::to_string(i / 3) + ": coordinate " + std::to_string(scene.positions[i]) +
                     " is not a finite number within +-1e15",
             false;
  return true;
}

bool read_input(const std::string& file, std::vector<unsigned char>& baked, geom::Scene& scene, std::string& error) {
  std::vector<unsigned char> magic;
  std::string problem;
  // Not a readable regular file (an archive member "PAK:NAME", a FIFO, a
  // device): the importer opens it, or refuses it, by its own rules.
  if (cli::read_file(file, magic, problem, 8) && magic.size() == 8 &&
      std::memcmp(magic.data(), geom::baked::kMagic, 8) == 0) {
    if (!geom::baked::read_baked_file(file, baked, problem, baked_size_limit()))
      return error = file + ": " + problem, false;
    geom::baked::Reader reader;
    if (!reader.open(baked.data(), baked.size())) return error = file + ": " + reader.error(), false;
    if (!geom::baked::validate_floats(reader, problem)) return error = file + ": " + problem, false;
    return true;
  }
  geom::ImportResult imported = geom::import_file(file);
  if (!imported.ok) return error = imported.error, false;
  for (const std::string& w : imported.scene.warnings) cli::warning("%s", w.c_str());
  scene = std::move(imported.scene);
  return check_positions(file, scene, error);
}

bool resolve_camera(const Options& o, geom::Camera& view, std::string& error) {
  float* vectors[3] = {view.eye, view.target, view.up};
  float* scalars[3] = {&view.fovy_deg, &view.near_plane, &view.far_plane};
  const char* names[6] = {"--eye", "--target", "--up", "--fovy", "--near", "--far"};
  for (int k = 0; k < 6; ++k)
    for (const std::string& v : o.camera_flags[k])
      if (!parse_floats(v, k < 3 ? vectors[k] : scalars[k - 3], k < 3 ? 3 : 1))
        return error = std::string(names[k]) + (k < 3 ? " needs X,Y,Z" : " needs a number") + ", not '" + v + "'",
               false;
  return cli::check_camera(view, "the camera (--eye --target --up --fovy --near --far)", error);
}

bool resolve_light(const Options& o, const geom::Scene& scene, geom::Light& light, std::string& error) {
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (!cli::check_light(scene.lights[i], o.file + ": light " + std::to_string(i), error)) return false;
  light = geom::light_from_scene(scene.lights);
  if (!o.light_flag.empty()) {
    float v[4];
    if (!parse_floats(o.light_flag, v, 4) || (v[3] != 0 && v[3] != 1))
      return error = "--light needs X,Y,Z,W with W = 1 (point) or 0 (directional)", false;
    const double h[4] = {v[0], v[1], v[2], v[3]};
    light = geom::light_from_homogeneous(h);
  }
  if (!o.spot_flag.empty()) {
    float v[4];
    if (!parse_floats(o.spot_flag, v, 4) || !(v[3] > 0 && v[3] < 90))
      return error = "--spot needs DX,DY,DZ,DEG with a non-zero direction and 0 < DEG < 90", false;
    if (light.type == geom::LightType::Directional)
      return error = "--spot needs a point light position (--light X,Y,Z,1)", false;
    light.type = geom::LightType::Spot;
    for (int k = 0; k < 3; ++k) light.direction[k] = v[k];
    light.outer_cone = glm::radians(double(v[3]));
  }
  const std::string source = !o.spot_flag.empty()    ? "--light, --spot"
                             : !o.light_flag.empty() ? "--light"
                                                     : o.file + ": the scene's light";
  return cli::check_light(light, source, error);
}

}  // namespace

bool open_session(Options& o, Session& s, std::string& error) {
  std::vector<unsigned char> baked;
  if (!read_input(o.file, baked, s.scene, error)) return false;
  std::string note;
  s.platform = render::Platform::open(o.window, o.view.width, o.view.height, "geomview " + o.file, note, error);
  if (!s.platform) return false;
  if (!note.empty()) cli::warning("%s", note.c_str());
  if (!s.platform->has_window() && (!o.script.empty() || !o.screenshot.empty()))
    return error = std::string(o.script.empty() ? "--screenshot" : "--script") +
                   " needs a window, and none could open" + (note.empty() ? "" : " (" + note + ")"),
           false;
  if (!s.platform->has_window() && o.out_path.empty())
    return error = "no window could open" + (note.empty() ? "" : " (" + note + ")") + ": give -o FILE.png", false;
  if (!check_resources(o, error)) return false;
  s.state = baked.empty() ? render::create_state(s.scene, o.shaders, error)
                          : render::create_state_baked(baked.data(), baked.size(), o.shaders, s.scene, error);
  if (!s.state) return error = o.file + ": " + error, false;
  if (const std::string gl = render::gl_error_text(); !gl.empty()) return error = o.file + ": " + gl, false;
  s.up_axis = o.up_axis >= 0 ? o.up_axis : format_up_axis(o.file);
  o.view = framed_view(s, o.view.width, o.view.height);
  if (!resolve_camera(o, o.view, error)) return false;
  return resolve_light(o, s.scene, o.light, error);
}

geom::Camera framed_view(const Session& s, int width, int height) {
  return render::default_view(*s.state, width, height, s.up_axis);
}

}  // namespace viewer
