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
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "geom/baked_reader.h"
#include "geom/import.h"
#include "geombake/args.h"
#include "platform.h"
#include "renderer.h"

namespace {

const char* kUsage =
    "Usage: geomview [FILE] [options]   (FILE: a baked .gbake container, or a mesh or scene file baked in\n"
    "                                    process; the bundled default scene when absent)\n"
    "  --technique NAME[,NAME..]  ssm pcf esm edsm sv sv-zpass sv-zfail cube psm lispsm uniform, or all\n"
    "  --eye X,Y,Z --target X,Y,Z --up X,Y,Z --fovy DEG --near N --far F   the camera\n"
    "  --light X,Y,Z,W            W=1 point light at X,Y,Z; W=0 directional light at infinity towards X,Y,Z\n"
    "  --spot DX,DY,DZ,DEG        a spot at the --light position shining along DX,DY,DZ, cone half-angle DEG\n"
    "  --shadow-map-size N        (default 1024)    --size WxH  image size (default 640x480)\n"
    "  -o FILE.png                output (several techniques: -o DIR, one DIR/NAME.png per technique)\n"
    "  --output color|mask        mask: 8-bit grey, 255 lit, 0 shadow, 128 no geometry\n"
    "  --frames N                 render N frames and print the time of each pass\n"
    "  --inspect                  overlay silhouette quads, topology problems, focus body\n"
    "  --window                   open a window (default when no -o is given and a display exists)\n"
    "  --shaders DIR              the shaders/ folder (default: $GEOMVIEW_SHADERS, " GEOMVIEW_SHADER_DIR ",\n"
    "                             then " GEOMVIEW_INSTALLED_SHADER_DIR ")\n"
    "Window keys: T technique, L light type, [ ] shadow-map size, I inspection, Esc quit; drag to orbit, scroll to zoom.\n";

bool parse_floats(const std::string& text, float* out, int n) {
  std::stringstream ss(text);
  std::string item;
  int i = 0;
  while (std::getline(ss, item, ',')) {
    if (i >= n) return false;
    char* end = nullptr;
    out[i] = std::strtof(item.c_str(), &end);
    if (end == item.c_str() || *end || !std::isfinite(out[i])) return false;
    ++i;
  }
  return i == n;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "Error: %s\n", message.c_str());
  return 1;
}

viewer::LightSetup light_from_scene(const geom::Scene& scene) {
  viewer::LightSetup l;
  l.position = glm::vec4(0.4f, 1.0f, 0.6f, 0.0f);
  if (scene.lights.empty()) return l;
  const geom::Light& s = scene.lights.front();
  const glm::vec3 p(s.position[0], s.position[1], s.position[2]), d(s.direction[0], s.direction[1], s.direction[2]);
  if (s.type == geom::LightType::Directional) {
    l.position = glm::vec4(-d, 0.0f);
  } else {
    l.position = glm::vec4(p, 1.0f);
    l.spot = s.type == geom::LightType::Spot;
    l.spot_direction = d;
    l.spot_angle_deg = glm::degrees(s.outer_cone);
  }
  return l;
}

}  // namespace

int main(int argc, char** argv) {
  geombake::Args args(std::vector<std::string>(argv + 1, argv + argc), {"--help", "-h", "--inspect", "--window"},
                      {"--technique", "--eye", "--target", "--up", "--fovy", "--near", "--far", "--light", "--spot",
                       "--shadow-map-size", "--size", "-o", "--output", "--frames", "--shaders"});
  if (!args.error().empty()) return fail(args.error() + " (see geomview --help)");
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (args.positional().size() > 1) return fail("one input file at most");
  const std::string file = args.positional().empty() ? GEOMVIEW_DEFAULT_SCENE : args.positional()[0];

  // Techniques.
  std::vector<viewer::Technique> techniques;
  for (const std::string& list : args.all("--technique")) {
    std::stringstream ss(list);
    std::string name;
    while (std::getline(ss, name, ',')) {
      if (name == "all") {
        for (auto t : viewer::available_techniques()) techniques.push_back(t);
        continue;
      }
      viewer::Technique t;
      if (!viewer::parse_technique(name, t)) {
        std::string known;
        for (auto a : viewer::available_techniques()) known += std::string(" ") + viewer::technique_name(a);
        return fail("unknown technique '" + name + "' (this build has:" + known + ")");
      }
      techniques.push_back(t);
    }
  }
  if (techniques.empty()) techniques.push_back(viewer::Technique::Pcf);

  viewer::FrameSettings settings;
  settings.inspect = args.has("--inspect");
  const std::string output = args.get("--output", "color");
  if (output != "color" && output != "mask") return fail("--output must be color or mask, not '" + output + "'");
  settings.output = output == "mask" ? viewer::Output::Mask : viewer::Output::Color;
  settings.shadow_map_size = std::atoi(args.get("--shadow-map-size", "1024").c_str());
  if (settings.shadow_map_size < 16 || settings.shadow_map_size > 16384)
    return fail("--shadow-map-size must be within 16..16384");
  const int frames = std::atoi(args.get("--frames", "1").c_str());
  if (frames < 1 || frames > 100000) return fail("--frames must be within 1..100000");

  viewer::View view;
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
    for (const std::string& w : imported.scene.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  }

  const std::string out_path = args.get("-o");
  const bool window = args.has("--window") || (out_path.empty() && std::getenv("DISPLAY"));
  if (!window && out_path.empty()) return fail("no display: give -o FILE.png (or run under xvfb-run with --window)");
  std::string note, error;
  auto platform = viewer::Platform::open(window, view.width, view.height, "geomview " + file, note, error);
  if (!platform) return fail(error);
  if (!note.empty()) std::fprintf(stderr, "Warning: %s\n", note.c_str());
  const char* shader_dir = std::getenv("GEOMVIEW_SHADERS");
  // Shaders: --shaders, GEOMVIEW_SHADERS, the source tree's, or the installed ones.
  std::string shaders = args.get("--shaders", shader_dir ? shader_dir : GEOMVIEW_SHADER_DIR);
  if (!args.has("--shaders") && !shader_dir && !std::filesystem::exists(shaders + "/shade.frag"))
    shaders = GEOMVIEW_INSTALLED_SHADER_DIR;
  viewer::StatePtr state =
      baked_bytes.empty() ? viewer::create_state(imported.scene, shaders, error)
                          : viewer::create_state_baked(baked_bytes.data(), baked_bytes.size(), shaders, imported.scene, error);
  if (!state) return fail(file + ": " + error);

  // Camera: the flags, or a view of the whole scene's bounding sphere.
  const glm::vec4 b = viewer::scene_bounds(*state);
  view = viewer::default_view(*state, view.width, view.height);
  struct VecFlag {
    const char* name;
    glm::vec3* value;
  };
  for (VecFlag f : {VecFlag{"--eye", &view.eye}, VecFlag{"--target", &view.target}, VecFlag{"--up", &view.up}})
    if (args.has(f.name) && !parse_floats(args.get(f.name), &f.value->x, 3))
      return fail(std::string(f.name) + " needs X,Y,Z");
  struct FloatFlag {
    const char* name;
    float* value;
  };
  for (FloatFlag f : {FloatFlag{"--fovy", &view.fovy_deg}, FloatFlag{"--near", &view.near_plane},
                      FloatFlag{"--far", &view.far_plane}})
    if (args.has(f.name) && !parse_floats(args.get(f.name), f.value, 1)) return fail(std::string(f.name) + " needs a number");
  if (!(view.fovy_deg > 0 && view.fovy_deg < 180)) return fail("--fovy must be within (0, 180) degrees");
  if (!(view.near_plane > 0 && view.far_plane > view.near_plane)) return fail("need 0 < --near < --far");
  if (glm::length(view.target - view.eye) == 0 || glm::length(glm::cross(view.target - view.eye, view.up)) == 0)
    return fail("--eye, --target and --up must span a view (eye != target, up not along the view)");

  viewer::LightSetup light = light_from_scene(imported.scene);
  if (args.has("--light")) {
    float v[4];
    if (!parse_floats(args.get("--light"), v, 4) || (v[3] != 0 && v[3] != 1))
      return fail("--light needs X,Y,Z,W with W = 1 (point) or 0 (directional)");
    light = viewer::LightSetup();
    light.position = glm::vec4(v[0], v[1], v[2], v[3]);
    if (v[3] == 0 && glm::length(glm::vec3(light.position)) == 0) return fail("--light direction is zero");
  }
  if (args.has("--spot")) {
    float v[4];
    if (!parse_floats(args.get("--spot"), v, 4) || !(v[3] > 0 && v[3] < 90) || glm::length(glm::vec3(v[0], v[1], v[2])) == 0)
      return fail("--spot needs DX,DY,DZ,DEG with a non-zero direction and 0 < DEG < 90");
    if (light.position.w == 0) return fail("--spot needs a point light position (--light X,Y,Z,1)");
    light.spot = true;
    light.spot_direction = glm::vec3(v[0], v[1], v[2]);
    light.spot_angle_deg = v[3];
  }

  std::fprintf(stderr, "geomview: %s, %s (%zu triangles)\n", platform->description().c_str(),
               viewer::renderer_name(*state).c_str(), imported.scene.triangle_count());

  if (platform->has_window()) {
    // Orbit camera around the target; keys change technique, light type, map size.
    size_t current = 0;
    std::vector<viewer::Technique> all = viewer::available_techniques();
    for (size_t i = 0; i < all.size(); ++i)
      if (all[i] == techniques[0]) current = i;
    int light_kind = light.position.w == 0 ? 2 : light.spot ? 1 : 0;  // point, spot, directional
    const glm::vec4 scene_light = light.position.w == 0 ? glm::vec4(b) + glm::vec4(glm::vec3(light.position) * b.w * 2.0f, 0)
                                                        : light.position;
    viewer::PlatformEvents events;
    bool quit = false;
    events.key = [&](int key) {
      if (key == GLFW_KEY_ESCAPE) quit = true;
      if (key == GLFW_KEY_T) current = (current + 1) % all.size();
      if (key == GLFW_KEY_I) settings.inspect = !settings.inspect;
      if (key == GLFW_KEY_RIGHT_BRACKET) settings.shadow_map_size = std::min(settings.shadow_map_size * 2, 8192);
      if (key == GLFW_KEY_LEFT_BRACKET) settings.shadow_map_size = std::max(settings.shadow_map_size / 2, 64);
      if (key == GLFW_KEY_L) {
        light_kind = (light_kind + 1) % 3;
        const glm::vec3 p(scene_light);
        light.position = light_kind == 2 ? glm::vec4(glm::normalize(p - glm::vec3(b)), 0) : glm::vec4(p, 1);
        light.spot = light_kind == 1;
        light.spot_direction = glm::vec3(b) - p;
        light.spot_angle_deg = 35;
      }
    };
    events.drag = [&](double dx, double dy, int button) {
      glm::vec3 offset = view.eye - view.target;
      if (button == 0) {
        const glm::vec3 up = glm::normalize(view.up);
        offset = glm::vec3(glm::rotate(glm::mat4(1), float(-dx * 0.01), up) * glm::vec4(offset, 0));
        const glm::vec3 right = glm::normalize(glm::cross(offset, up));
        const glm::vec3 tilted = glm::vec3(glm::rotate(glm::mat4(1), float(dy * 0.01), right) * glm::vec4(offset, 0));
        if (std::fabs(glm::dot(glm::normalize(tilted), up)) < 0.99f) offset = tilted;
      } else {
        offset *= float(std::exp(dy * 0.01));
      }
      view.eye = view.target + offset;
    };
    events.scroll = [&](double dy) { view.eye = view.target + (view.eye - view.target) * float(std::exp(-dy * 0.1)); };
    auto last_print = std::chrono::steady_clock::now();
    while (!platform->should_close() && !quit) {
      int w = 0, h = 0;
      platform->framebuffer_size(w, h);
      settings.technique = all[current];
      std::vector<viewer::PassTime> times;
      if (w > 0 && h > 0 && !viewer::render_to_window(*state, view, light, settings, w, h, times, error)) {
        std::fprintf(stderr, "Warning: %s\n", error.c_str());
        current = (current + 1) % all.size();
      }
      if (std::chrono::steady_clock::now() - last_print > std::chrono::seconds(1)) {
        last_print = std::chrono::steady_clock::now();
        std::fprintf(stderr, "%s %d:", viewer::technique_name(settings.technique), settings.shadow_map_size);
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
  if (frames > 1) std::printf("# pass times: %s\n", viewer::timing_kind(*state).c_str());
  for (viewer::Technique t : techniques) {
    settings.technique = t;
    if (t == viewer::Technique::Cube && light.position.w == 0 && several) {
      std::fprintf(stderr, "Warning: cube skipped: it needs a point or spot light\n");
      continue;
    }
    geom::PngImage image;
    for (int f = 0; f < frames; ++f) {
      std::vector<viewer::PassTime> times;
      if (!viewer::render(*state, view, light, settings, image, times, error))
        return fail(file + ": " + viewer::technique_name(t) + ": " + error);
      if (frames > 1) {
        std::printf("%s frame %d:", viewer::technique_name(t), f);
        double total = 0;
        for (auto& pt : times) std::printf(" %s %.3f ms", pt.pass.c_str(), pt.ms), total += pt.ms;
        std::printf(" total %.3f ms\n", total);
      }
    }
    const std::string path = several ? out_path + "/" + viewer::technique_name(t) + ".png" : out_path;
    if (!geom::write_png(path, image, error)) return fail(error);
  }
  return 0;
}
