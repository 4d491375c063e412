// geomview: draws a mesh or scene with every shadow technique of the project,
// headless into PNG files (EGL) or in a window (GLFW) with an orbit camera.
// Usage: geomview [FILE] [options]; `geomview --help` lists them.
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "cli/args.h"
#include "geom/baked_reader.h"
#include "geom/import.h"
#include "render/platform.h"
#include "render/render.h"

namespace {

const char* kUsage =
    "Usage: geomview [FILE] [options]   (FILE: a baked .gbake container, or a mesh or scene file baked in\n"
    "                                    process; the bundled default scene when absent)\n"
    "  --technique NAME[,NAME..]  ssm pcf esm edsm sv sv-zpass sv-zfail cube psm lispsm uniform sssm edsm-soft\n"
    "                             pcf-soft, or all\n"
    "  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fovy DEG --near N --far F   the camera\n"
    "  --light X,Y,Z,W            W=1 point light at X,Y,Z; W=0 directional light at infinity towards X,Y,Z\n"
    "  --spot DX,DY,DZ,DEG        a spot at the --light position shining along DX,DY,DZ, cone half-angle DEG\n"
    "  --shadow-map-size N        (default 1024)    --size WxH  image size (default 640x480)\n"
    "  -o FILE.png                output (several techniques: -o DIR, one DIR/NAME.png per technique)\n"
    "  --output color|mask        mask: 8-bit grey, 255 lit, 0 shadow, 128 no geometry\n"
    "  --light-radius R           edsm-soft, pcf-soft: the light's disc (world units; radians for a sun; default 0)\n"
    "  --frames N                 render N frames and print the time of each pass\n"
    "  --inspect                  overlay silhouette quads, topology problems, focus body\n"
    "  --window                   open a window (default when no -o is given and a display exists)\n"
    "  --shaders DIR              the shaders/ folder (default: $GEOMVIEW_SHADERS, " GEOM_SHADER_DIR
    ",\n"
    "                             then " GEOMVIEW_INSTALLED_SHADER_DIR
    ")\n"
    "Window keys: T technique, L light type, [ ] shadow-map size, I inspection, Esc quit; drag to orbit, scroll to "
    "zoom.\n";

// "a,b,c" into n finite floats.
bool parse_floats(const std::string& text, float* out, int n) {
  if (!cli::parse_floats(text, n, out)) return false;
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(out[i])) return false;
  return true;
}

int fail(const std::string& message) {
  cli::error("%s", message.c_str());
  return cli::kExitFailure;
}

glm::vec3 vec3(const float v[3]) { return glm::vec3(v[0], v[1], v[2]); }
void store(float out[3], glm::vec3 v) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }

}  // namespace

int main(int argc, char** argv) {
  cli::Args args(std::vector<std::string>(argv + 1, argv + argc), {"--help", "-h", "--inspect", "--window"},
                 {"--technique", "--eye", "--target", "--up", "--fovy", "--near", "--far", "--light", "--spot",
                  "--shadow-map-size", "--size", "-o", "--output", "--frames", "--shaders", "--light-radius"});
  if (!args.error().empty()) return fail(args.error() + " (see geomview --help)");
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (args.positional().size() > 1) return fail("one input file at most");
  const std::string file = args.positional().empty() ? GEOMVIEW_DEFAULT_SCENE : args.positional()[0];

  // Techniques.
  std::vector<render::Technique> techniques;
  for (const std::string& list : args.all("--technique")) {
    std::stringstream ss(list);
    std::string name;
    while (std::getline(ss, name, ',')) {
      if (name == "all") {
        for (auto t : render::available_techniques()) techniques.push_back(t);
        continue;
      }
      render::Technique t;
      if (!render::parse_technique(name, t)) {
        std::string known;
        for (auto a : render::available_techniques()) known += std::string(" ") + render::technique_name(a);
        return fail("unknown technique '" + name + "' (this build has:" + known + ")");
      }
      techniques.push_back(t);
    }
  }
  if (techniques.empty()) techniques.push_back(render::Technique::Pcf);

  render::FrameSettings settings;
  settings.inspect = args.has("--inspect");
  const std::string output = args.get("--output", "color");
  if (output != "color" && output != "mask") return fail("--output must be color or mask, not '" + output + "'");
  settings.output = output == "mask" ? render::Output::Mask : render::Output::Color;
  settings.shadow_map_size = std::atoi(args.get("--shadow-map-size", "1024").c_str());
  settings.light_radius = float(std::atof(args.get("--light-radius", "0").c_str()));
  if (!(settings.light_radius >= 0) || settings.light_radius > 1e6) return fail("--light-radius must be >= 0");
  if (settings.shadow_map_size < 16 || settings.shadow_map_size > 16384)
    return fail("--shadow-map-size must be within 16..16384");
  const int frames = std::atoi(args.get("--frames", "1").c_str());
  if (frames < 1 || frames > 100000) return fail("--frames must be within 1..100000");

  geom::Camera view;
  view.width = 640, view.height = 480;
  if (args.has("--size")) {
    const std::string s = args.get("--size");
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 || h < 1 || w > 16384 ||
        h > 16384)
      return fail("--size must be WxH within 1..16384, not '" + s + "'");
    view.width = w, view.height = h;
  }

  // The input: a baked container (by its magic bytes), or a mesh / scene file
  // imported and baked in process on first use.
  std::vector<unsigned char> baked_bytes;
  {
    std::FILE* f = std::fopen(file.c_str(), "rb");
    unsigned char magic[8] = {};
    if (f && std::fread(magic, 1, 8, f) == 8 && std::memcmp(magic, geom::baked::kMagic, 8) == 0) {
      std::fseek(f, 0, SEEK_END);
      const long size = std::ftell(f);
      std::fseek(f, 0, SEEK_SET);
      if (size > 0) {
        baked_bytes.resize(size_t(size));
        if (std::fread(baked_bytes.data(), 1, baked_bytes.size(), f) != baked_bytes.size()) baked_bytes.clear();
      }
      if (baked_bytes.empty()) {
        std::fclose(f);
        return fail(file + ": cannot read the baked file");
      }
    }
    if (f) std::fclose(f);
  }
  geom::ImportResult imported;
  if (baked_bytes.empty()) {
    imported = geom::import_file(file);
    if (!imported.ok) return fail(imported.error);
    for (const std::string& w : imported.scene.warnings) cli::warning("%s", w.c_str());
  }

  const std::string out_path = args.get("-o");
  const bool window = args.has("--window") || (out_path.empty() && std::getenv("DISPLAY"));
  if (!window && out_path.empty()) return fail("no display: give -o FILE.png (or run under xvfb-run with --window)");
  std::string note, error;
  auto platform = render::Platform::open(window, view.width, view.height, "geomview " + file, note, error);
  if (!platform) return fail(error);
  if (!note.empty()) cli::warning("%s", note.c_str());
  const char* shader_dir = std::getenv("GEOMVIEW_SHADERS");
  // Shaders: --shaders, GEOMVIEW_SHADERS, the source tree's, or the installed ones.
  std::string shaders = args.get("--shaders", shader_dir ? shader_dir : GEOM_SHADER_DIR);
  if (!args.has("--shaders") && !shader_dir && !std::filesystem::exists(shaders + "/shade.frag"))
    shaders = GEOMVIEW_INSTALLED_SHADER_DIR;
  render::StatePtr state = baked_bytes.empty() ? render::create_state(imported.scene, shaders, error)
                                               : render::create_state_baked(baked_bytes.data(), baked_bytes.size(),
                                                                            shaders, imported.scene, error);
  if (!state) return fail(file + ": " + error);

  // Camera: the flags, or a view of the whole scene's bounding sphere.
  float bounds[4];
  render::scene_bounds(*state, bounds);
  const glm::vec4 b(bounds[0], bounds[1], bounds[2], bounds[3]);
  view = render::default_view(*state, view.width, view.height);
  struct VecFlag {
    const char* name;
    float* value;
  };
  for (VecFlag f : {VecFlag{"--eye", view.eye}, VecFlag{"--target", view.target}, VecFlag{"--up", view.up}})
    if (args.has(f.name) && !parse_floats(args.get(f.name), f.value, 3))
      return fail(std::string(f.name) + " needs X,Y,Z");
  struct FloatFlag {
    const char* name;
    float* value;
  };
  for (FloatFlag f : {FloatFlag{"--fovy", &view.fovy_deg}, FloatFlag{"--near", &view.near_plane},
                      FloatFlag{"--far", &view.far_plane}})
    if (args.has(f.name) && !parse_floats(args.get(f.name), f.value, 1))
      return fail(std::string(f.name) + " needs a number");
  if (!(view.fovy_deg > 0 && view.fovy_deg < 180)) return fail("--fovy must be within (0, 180) degrees");
  if (!(view.near_plane > 0 && view.far_plane > view.near_plane)) return fail("need 0 < --near < --far");
  if (glm::length(vec3(view.target) - vec3(view.eye)) == 0 ||
      glm::length(glm::cross(vec3(view.target) - vec3(view.eye), vec3(view.up))) == 0)
    return fail("--eye, --target and --up must span a view (eye != target, up not along the view)");

  geom::Light light = geom::light_from_scene(imported.scene.lights);
  if (args.has("--light")) {
    float v[4];
    if (!parse_floats(args.get("--light"), v, 4) || (v[3] != 0 && v[3] != 1))
      return fail("--light needs X,Y,Z,W with W = 1 (point) or 0 (directional)");
    const double h[4] = {v[0], v[1], v[2], v[3]};
    light = geom::light_from_homogeneous(h);
    if (v[3] == 0 && glm::length(glm::vec3(v[0], v[1], v[2])) == 0) return fail("--light direction is zero");
  }
  if (args.has("--spot")) {
    float v[4];
    if (!parse_floats(args.get("--spot"), v, 4) || !(v[3] > 0 && v[3] < 90) ||
        glm::length(glm::vec3(v[0], v[1], v[2])) == 0)
      return fail("--spot needs DX,DY,DZ,DEG with a non-zero direction and 0 < DEG < 90");
    if (light.type == geom::LightType::Directional)
      return fail("--spot needs a point light position (--light X,Y,Z,1)");
    light.type = geom::LightType::Spot;
    for (int k = 0; k < 3; ++k) light.direction[k] = v[k];
    light.outer_cone = glm::radians(double(v[3]));
  }

  std::fprintf(stderr, "geomview: %s, %s (%zu triangles)\n", platform->description().c_str(),
               render::renderer_name(*state).c_str(), imported.scene.triangle_count());

  if (platform->has_window()) {
    // Orbit camera around the target; keys change technique, light type, map size.
    size_t current = 0;
    std::vector<render::Technique> all = render::available_techniques();
    for (size_t i = 0; i < all.size(); ++i)
      if (all[i] == techniques[0]) current = i;
    int light_kind = light.type == geom::LightType::Directional ? 2 : light.type == geom::LightType::Spot ? 1 : 0;
    double h[4];
    geom::light_homogeneous(light, h);
    const glm::vec4 position = glm::vec4(float(h[0]), float(h[1]), float(h[2]), float(h[3]));
    const glm::vec4 scene_light =
        position.w == 0 ? glm::vec4(b) + glm::vec4(glm::vec3(position) * b.w * 2.0f, 0) : position;
    render::PlatformEvents events;
    bool quit = false;
    events.key = [&](int key) {
      if (key == GLFW_KEY_ESCAPE) quit = true;
      if (key == GLFW_KEY_T) current = (current + 1) % all.size();
      if (key == GLFW_KEY_I) settings.inspect = !settings.inspect;
      if (key == GLFW_KEY_RIGHT_BRACKET) settings.shadow_map_size = std::min(settings.shadow_map_size * 2, 8192);
      if (key == GLFW_KEY_LEFT_BRACKET) settings.shadow_map_size = std::max(settings.shadow_map_size / 2, 64);
      if (key == GLFW_KEY_L) {
        light_kind = (light_kind + 1) % 3;
        const glm::vec3 p(scene_light), towards = glm::normalize(p - glm::vec3(b)), axis = glm::vec3(b) - p;
        light = geom::Light();
        light.type = light_kind == 2   ? geom::LightType::Directional
                     : light_kind == 1 ? geom::LightType::Spot
                                       : geom::LightType::Point;
        for (int k = 0; k < 3; ++k)
          light.position[k] = p[k], light.direction[k] = light_kind == 2 ? -towards[k] : axis[k];
        light.outer_cone = glm::radians(35.0);
      }
    };
    events.drag = [&](double dx, double dy, int button) {
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
    events.scroll = [&](double dy) {
      store(view.eye, vec3(view.target) + (vec3(view.eye) - vec3(view.target)) * float(std::exp(-dy * 0.1)));
    };
    auto last_print = std::chrono::steady_clock::now();
    while (!platform->should_close() && !quit) {
      int w = 0, h = 0;
      platform->framebuffer_size(w, h);
      settings.technique = all[current];
      std::vector<render::PassTime> times;
      if (w > 0 && h > 0 && !render::render_to_window(*state, view, light, settings, w, h, times, error)) {
        cli::warning("%s", error.c_str());
        current = (current + 1) % all.size();
      }
      if (std::chrono::steady_clock::now() - last_print > std::chrono::seconds(1)) {
        last_print = std::chrono::steady_clock::now();
        std::fprintf(stderr, "%s %d:", render::technique_name(settings.technique), settings.shadow_map_size);
        for (auto& t : times) std::fprintf(stderr, " %s %.2f ms", t.pass.c_str(), t.ms);
        std::fprintf(stderr, "\n");
      }
      platform->swap_and_poll(events);
    }
    return 0;
  }

  // Headless: one PNG per technique.
  const bool several = techniques.size() > 1;
  if (several) {
    std::error_code ec;
    std::filesystem::create_directories(out_path, ec);
    if (ec) return fail(out_path + ": cannot create the folder (" + ec.message() + ")");
  }
  if (frames > 1) std::printf("# pass times: %s\n", render::timing_kind(*state).c_str());
  for (render::Technique t : techniques) {
    settings.technique = t;
    if (render::technique_needs_point_light(t) && light.type == geom::LightType::Directional && several) {
      cli::warning("%s skipped: it needs a point or spot light", render::technique_name(t));
      continue;
    }
    geom::PngImage image;
    for (int f = 0; f < frames; ++f) {
      std::vector<render::PassTime> times;
      if (!render::render(*state, view, light, settings, image, times, error))
        return fail(file + ": " + render::technique_name(t) + ": " + error);
      if (frames > 1) {
        std::printf("%s frame %d:", render::technique_name(t), f);
        double total = 0;
        for (auto& pt : times) std::printf(" %s %.3f ms", pt.pass.c_str(), pt.ms), total += pt.ms;
        std::printf(" total %.3f ms\n", total);
      }
    }
    const std::string path = several ? out_path + "/" + render::technique_name(t) + ".png" : out_path;
    if (!geom::write_png(path, image, error)) return fail(error);
  }
  return 0;
}
