// geomview as a graphics programmer uses it, end to end through
// the binary: the --compare grid is the techniques' own images side by side
// with their labels; the HUD's figures are the CLI's and equal an error
// computed here from the mask and the ray-cast reference; the inspection
// shows every boundary and non-manifold edge of a fin and oa_dm1's
// non-manifold edges, with the topology report's counts; the default framing
// keeps the whole scene in view whatever its up axis.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <regex>

#include "geom/shadow_error.h"
#include "geom/shadow_reference.h"
#include "gl_fixtures.h"
#include "viewer_run.h"

namespace {

using namespace viewertest;

const std::string kView = kSceneView;

// Three quads around the edge (0,0,0)-(1,0,0), 120 degrees apart: 6 triangles,
// 9 boundary edges, 1 non-manifold edge (3 faces), 3 manifold diagonals.
const glm::vec3 kFinDirections[3] = {{0, 1, 0}, {0, -0.5f, 0.8660254f}, {0, -0.5f, -0.8660254f}};
std::string fin_obj() {
  std::string s = "v 0 0 0\nv 1 0 0\n";
  for (const glm::vec3& d : kFinDirections) {
    char b[160];
    std::snprintf(b, sizeof b, "v %g %g %g\nv %g %g %g\n", 1 + d.x, d.y, d.z, d.x, d.y, d.z);
    s += b;
  }
  for (int i = 0; i < 3; ++i) {
    const int c = 3 + 2 * i, e = 4 + 2 * i;
    s += "f 1 2 " + std::to_string(c) + "\nf 1 " + std::to_string(c) + " " + std::to_string(e) + "\n";
  }
  return s;
}
// Looking along the shared edge, slightly off its axis: every fin edge in view.
const std::string kFinView = "--eye 4,0.25,0.35 --target 0.5,0,0 --up 0,1,0 --fovy 40 --near 0.05 --far 50";
const int kFinW = 320, kFinH = 240;

std::string write(const Scratch& s, const std::string& name, const std::string& text) {
  std::ofstream(s / name) << text;
  return s / name;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// The error as geombench scores it, computed here: visible pixels outside the
// uncertain band, and those within 3 pixels of a true boundary.
std::string error_line(const geom::PngImage& mask, const geom::ShadowReference& ref) {
  const int w = ref.width, h = ref.height;
  std::vector<uint8_t> band(size_t(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t v = ref.mask[size_t(y) * w + x];
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, t = y + dy;
          if (v == 128 || u < 0 || t < 0 || u >= w || t >= h) continue;
          const uint8_t n = ref.mask[size_t(t) * w + u];
          edge = edge || (n != 128 && n != v);
        }
      if (!edge) continue;
      for (int t = std::max(0, y - 3); t <= std::min(h - 1, y + 3); ++t)
        for (int u = std::max(0, x - 3); u <= std::min(w - 1, x + 3); ++u) band[size_t(t) * w + u] = 1;
    }
  size_t visible = 0, wrong = 0, boundary = 0, wrong_boundary = 0;
  for (size_t i = 0; i < ref.mask.size(); ++i) {
    if (ref.mask[i] == 128 || ref.uncertain[i]) continue;
    const bool bad = mask.pixels[i] != ref.mask[i];
    ++visible, wrong += bad;
    if (band[i]) ++boundary, wrong_boundary += bad;
  }
  char b[128];
  std::snprintf(b, sizeof b, "error %.3f%% visible, %.2f%% boundary", visible ? 100.0 * wrong / visible : 0.0,
                boundary ? 100.0 * wrong_boundary / boundary : 0.0);
  return b;
}

TEST(GlViewer, CompareGridIsTheTechniquesSideBySide) {
  Scratch s("compare");
  const std::string obj = write(s, "scene.obj", kScene);
  const ViewerRun grid =
      geomview(s, obj + " " + kView + " --size 160x120 --compare ssm,edsm,sv -o " + (s / "grid.png"));
  ASSERT_EQ(grid.exit_code, 0) << grid.err;
  const geom::PngImage g = read_rgb(s / "grid.png");
  ASSERT_EQ(g.width, 3 * 160 + 2 * 2);
  ASSERT_EQ(g.height, 120);
  const std::vector<std::string> hud = grid.lines("hud: ");
  ASSERT_EQ(hud.size(), 12u) << grid.out;
  const char* names[3] = {"ssm", "edsm", "sv"};
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(names[i]);
    EXPECT_EQ(hud[4 * i].rfind(std::string(names[i]) + (i < 2 ? " 1024 | " : " | shadow volumes"), 0), 0u)
        << hud[4 * i];  // technique, size, the projection drawn
    EXPECT_TRUE(std::regex_match(hud[4 * i + 1], std::regex(R"(shadow [0-9.]+ ms, frame [0-9.]+ ms \((GPU|wall)\))")))
        << hud[4 * i + 1];
    // The panel's error is the CLI's for the same view.
    const ViewerRun cli =
        geomview(s, obj + " " + kView + " --size 160x120 --error --technique " + names[i] + " -o " + (s / "one.png"));
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    EXPECT_EQ(cli.lines(std::string(names[i]) + " "), (std::vector<std::string>{hud[4 * i + 2], hud[4 * i + 3]}));
    // Below its label the panel is the technique's own image; the label changed the top left.
    const geom::PngImage one = read_rgb(s / "one.png");
    size_t differ = 0, labelled = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const bool same = std::equal(pixel(one, x, y), pixel(one, x, y) + 3, pixel(g, i * 162 + x, y));
        if (y >= 100) differ += !same;  // below the label's 4 lines
        if (y < 40 && x < 120) labelled += !same;
      }
    EXPECT_EQ(differ, 0u);
    EXPECT_GT(labelled, 500u);
  }
  // All techniques: one panel each, 4 columns for 10-20.
  const ViewerRun all = geomview(s, obj + " " + kView + " --size 64x48 --compare all -o " + (s / "all.png"));
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const size_t n = render::available_techniques().size();
  const int columns = n <= 3 ? int(n) : n == 4 ? 2 : n <= 9 ? 3 : 4, rows = int((n + columns - 1) / columns);
  const geom::PngImage a = read_rgb(s / "all.png");
  EXPECT_EQ(a.width, columns * 64 + (columns - 1) * 2);
  EXPECT_EQ(a.height, rows * 48 + (rows - 1) * 2);
  EXPECT_EQ(all.lines("hud: ").size(), 4 * n);
  // 2 to 20 panels.
  const ViewerRun one = geomview(s, obj + " --compare ssm -o " + (s / "x.png"));
  EXPECT_EQ(one.exit_code, 2);  // bad usage (cli::kExitUsage)
  EXPECT_NE(one.err.find("2 to 20"), std::string::npos) << one.err;
}

TEST(GlViewer, HudFiguresAreTheCliAndTheReference) {
  Scratch s("hud");
  const std::string obj = write(s, "scene.obj", kScene);
  const std::string base = obj + " " + kView + " --size 400x300 --shadow-map-size 128 --technique pcf ";
  const ViewerRun hud = geomview(s, base + "--hud -o " + (s / "hud.png"));
  ASSERT_EQ(hud.exit_code, 0) << hud.err;
  const std::vector<std::string> lines = hud.lines("hud: ");
  ASSERT_GE(lines.size(), 5u) << hud.out;
  EXPECT_EQ(lines[0].rfind("pcf 128 | 6 faces", 0), 0u) << lines[0];  // a point light among the receivers
  // The error: the CLI's line, and the one computed here from the mask and the reference.
  const ViewerRun cli = geomview(s, base + "--error -o " + (s / "plain.png"));
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_EQ(cli.lines("pcf "), (std::vector<std::string>{lines[2], lines[3]}));
  ASSERT_EQ(geomview(s, base + "--output mask -o " + (s / "mask.png")).exit_code, 0);
  geom::PngImage mask;
  std::string error;
  ASSERT_TRUE(geom::read_png(s / "mask.png", mask, error, 1)) << error;
  std::vector<float> p;
  std::vector<uint32_t> idx;
  parse_obj(kScene, p, idx);
  const geom::Camera view = gltest::camera({3, 4, 6}, {0, 0.3f, 0}, 50, 0.1f, 100, 400, 300);
  const geom::ShadowReference ref = geom::shadow_reference(geom::positions_of(p.data(), p.size() / 3), idx.data(),
                                                           idx.size(), view, gltest::point_light({1, 5, 2}));
  ASSERT_TRUE(ref.ok) << ref.error;
  EXPECT_EQ(lines[2], error_line(mask, ref));
  // The per-class figures: geom/shadow_error.h's, as geombench reports them.
  const geom::ShadowError classes = geom::shadow_error(mask.pixels, ref);
  char per_class[128];
  std::snprintf(per_class, sizeof per_class, "per class: %.3f%% cast, %.3f%% self", 100 * classes.error_cast,
                100 * classes.error_self);
  EXPECT_EQ(lines[3], per_class);
  // The passes: the names the CLI's --frames prints, each with its time.
  const ViewerRun frames = geomview(s, base + "--frames 2 -o " + (s / "f.png"));
  ASSERT_EQ(frames.exit_code, 0) << frames.err;
  std::vector<std::string> cli_passes, hud_passes;
  for (const std::string& l : frames.lines("pcf frame 1:")) {
    std::smatch m;
    for (std::string rest = l; std::regex_search(rest, m, std::regex(R"( ([a-zA-Z +(),-]+?) [0-9.]+ ms)"));
         rest = m.suffix())
      if (m[1] != "total") cli_passes.push_back(m[1]);
  }
  // The last line: the shadow passes' pipeline statistics, as --frames prints them.
  ASSERT_EQ(lines.back().rfind("shadow passes: ", 0), 0u) << hud.out;
  EXPECT_NE(frames.lines("pcf frame 1:").at(0).find("; " + lines.back()), std::string::npos) << frames.out;
  for (size_t i = 4; i + 1 < lines.size(); ++i)
    hud_passes.push_back(lines[i].substr(2, lines[i].rfind(' ', lines[i].size() - 4) - 2));
  EXPECT_EQ(hud_passes, cli_passes) << hud.out << frames.out;
  // The HUD is drawn into the top left of the image, and nowhere else.
  const geom::PngImage a = read_rgb(s / "hud.png"), b = read_rgb(s / "plain.png");
  size_t top_left = 0, elsewhere = 0;
  const int hud_bottom = 8 + 10 + 19 * int(lines.size());  // the box's padding and line height, with a margin
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 400; ++x) {
      const bool same = std::equal(pixel(a, x, y), pixel(a, x, y) + 3, pixel(b, x, y));
      if (x < 200 && y < 40) top_left += !same;
      if (y > hud_bottom) elsewhere += !same;
    }
  EXPECT_GT(top_left, 1000u);
  EXPECT_EQ(elsewhere, 0u);
}

glm::vec2 project(glm::vec3 p) {
  const glm::mat4 m = glm::infinitePerspective(glm::radians(40.0f), float(kFinW) / kFinH, 0.05f) *
                      glm::lookAt(glm::vec3(4, 0.25f, 0.35f), glm::vec3(0.5f, 0, 0), glm::vec3(0, 1, 0));
  const glm::vec4 c = m * glm::vec4(p, 1);
  return {(c.x / c.w * 0.5f + 0.5f) * kFinW, (0.5f - c.y / c.w * 0.5f) * kFinH};
}

TEST(GlViewer, InspectionShowsEveryEdgeOfTheFin) {
  Scratch s("fin");
  const std::string obj = write(s, "fin.obj", fin_obj());
  const ViewerRun r =
      geomview(s, obj + " " + kFinView + " --size 320x240 --light 3,4,2,1 --technique ssm --inspect --hud -o " +
                      (s / "fin.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.lines("hud: inspection report: "),
            std::vector<std::string>{"boundary 9 non-manifold 1 inconsistent 0 degenerate 0"});
  // Without the HUD (it covers the top left), each edge seen at three points.
  ASSERT_EQ(geomview(s, obj + " " + kFinView + " --size 320x240 --light 3,4,2,1 --technique ssm --inspect -o " +
                            (s / "plain.png"))
                .exit_code,
            0);
  const geom::PngImage im = read_rgb(s / "plain.png");
  float yellow[3], red[3];
  render::inspection_colour(render::InspectKind::Boundary, yellow);
  render::inspection_colour(render::InspectKind::NonManifold, red);
  const glm::vec3 a(0, 0, 0), b(1, 0, 0);
  int boundary_edges_seen = 0;
  for (const glm::vec3& d : kFinDirections) {
    // b - (b+d), (b+d) - (a+d), (a+d) - a; sampled away from the shared edge.
    const glm::vec3 edges[3][2] = {{b, b + d}, {b + d, a + d}, {a + d, a}};
    for (const auto& e : edges) {
      bool seen = true;
      for (float t : {0.35f, 0.6f, 0.85f}) {
        const float u = e[0] == b || e[0] == a ? t : (e[1] == a ? 1 - t : t);
        const glm::vec2 q = project(glm::mix(e[0], e[1], e[1] == a ? 1 - u : u));
        seen = seen && colour_near(im, int(q.x), int(q.y), yellow);
      }
      boundary_edges_seen += seen;
    }
  }
  EXPECT_EQ(boundary_edges_seen, 9);
  for (float t : {0.3f, 0.5f, 0.7f}) {
    const glm::vec2 q = project(glm::mix(a, b, t));
    EXPECT_TRUE(colour_near(im, int(q.x), int(q.y), red)) << t;
  }
}

const char* kOaDm1 = "/usr/share/games/openarena/baseoa/pak1-maps.pk3:maps/oa_dm1.bsp";

TEST(GlViewer, InspectionShowsOaDm1sNonManifoldEdges) {
  Scratch s("dm1");
  // The report's counts: those of geombake info.
  const std::string info_path = s / "info.txt";
  ASSERT_EQ(std::system((std::string(GEOMBAKE_EXE) + " info '" + kOaDm1 + "' >" + info_path + " 2>/dev/null").c_str()),
            0);
  std::smatch m;
  const std::string info = slurp(info_path);
  ASSERT_TRUE(std::regex_search(info, m, std::regex(R"((\d+) boundary, (\d+) inconsistent, (\d+) non-manifold)")))
      << info;
  const ViewerRun r =
      geomview(s, quoted(kOaDm1) + " --size 320x240 --technique ssm --inspect --hud -o " + (s / "dm1.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> report = r.lines("hud: inspection report: ");
  ASSERT_EQ(report.size(), 1u) << r.out;
  EXPECT_EQ(report[0].substr(0, report[0].find(" degenerate")),
            "boundary " + m[1].str() + " non-manifold " + m[3].str() + " inconsistent " + m[2].str());
  // The framing shows the whole map (Z-up) and its non-manifold edges: hundreds of red pixels.
  float red[3], yellow[3];
  render::inspection_colour(render::InspectKind::NonManifold, red);
  render::inspection_colour(render::InspectKind::Boundary, yellow);
  ASSERT_EQ(geomview(s, quoted(kOaDm1) + " --size 320x240 --technique ssm --inspect -o " + (s / "plain.png")).exit_code,
            0);
  const geom::PngImage im = read_rgb(s / "plain.png");
  EXPECT_GT(count_colour(im, red), 300u);
  EXPECT_GT(count_colour(im, yellow), 1000u);
}

// An installed geomview (bin/ beside share/geom/shaders) reads the shaders
// beside it, whatever the source tree; GEOMVIEW_SHADERS and --shaders
// override it.
TEST(GlViewer, ShadersAreFoundBesideTheBinary) {
  Scratch s("install");
  fs::create_directories(s.dir / "prefix/bin");
  fs::create_directories(s.dir / "prefix/share/geom");
  fs::copy(GEOMVIEW_EXE, s.dir / "prefix/bin/geomview");
  fs::copy(GEOM_SHADER_DIR, s.dir / "prefix/share/geom/shaders", fs::copy_options::recursive);
  const std::string obj = write(s, "scene.obj", kScene);
  const std::string installed = (s.dir / "prefix/bin/geomview").string();
  const std::string out = s / "x.png", log = s / "log.txt";
  auto run = [&](const std::string& prefix, const std::string& args) {
    const int rc =
        std::system((prefix + installed + " " + obj + " --size 32x24 -o " + out + " " + args + " 2>" + log).c_str());
    return std::make_pair(rc, slurp(log));
  };
  const auto [rc, err] = run("env -u GEOMVIEW_SHADERS ", "");
  ASSERT_EQ(rc, 0) << err;
  EXPECT_NE(err.find("shaders from " + (s.dir / "prefix/share/geom/shaders").string() + "\n"), std::string::npos)
      << err;
  const auto [rc2, err2] = run("GEOMVIEW_SHADERS=" + std::string(GEOM_SHADER_DIR) + " ", "");
  ASSERT_EQ(rc2, 0) << err2;
  EXPECT_NE(err2.find("shaders from " + std::string(GEOM_SHADER_DIR) + "\n"), std::string::npos) << err2;
  const auto [rc3, err3] = run("GEOMVIEW_SHADERS=/nonexistent ", "--shaders " + std::string(GEOM_SHADER_DIR));
  ASSERT_EQ(rc3, 0) << err3;
  // Without any shaders beside it, none: the binary holds no path of the build
  // machine; the error names the folder it looked in.
  fs::remove_all(s.dir / "prefix/share/geom/shaders");
  const auto [rc4, err4] = run("env -u GEOMVIEW_SHADERS ", "");
  EXPECT_NE(rc4, 0) << err4;
  EXPECT_NE(err4.find((s.dir / "prefix/share/geom/shaders").string()), std::string::npos) << err4;
}

// The default framing keeps every corner of the scene's box inside the image
// and looks from above along the up axis: random boxes, every axis, aspects.
TEST(GlViewer, DefaultViewFitsTheBoundsForAnyUpAxis) {
  ASSERT_NE(gltest::context(), nullptr);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> size(0.01f, 200.0f), at(-1000, 1000);
  for (int trial = 0; trial < 60; ++trial) {
    const glm::vec3 centre(at(rng), at(rng), at(rng)), half(size(rng), size(rng), size(rng));
    geom::Scene scene;
    gltest::add_box(scene, gltest::box_at(centre, half));
    std::string error;
    render::StatePtr state = render::create_state(scene, GEOM_SHADER_DIR, error);
    ASSERT_TRUE(state) << error;
    const int w = 100 + trial * 13, h = 80 + (trial * 7) % 300, axis = trial % 3;
    const geom::Camera v = render::default_view(*state, w, h, axis);
    const glm::vec3 eye = gltest::vec3(v.eye), target = gltest::vec3(v.target);
    EXPECT_GT(eye[axis] - target[axis], 0.2f * glm::length(eye - target)) << trial;
    const glm::mat4 m = glm::perspective(glm::radians(v.fovy_deg), float(w) / h, v.near_plane, v.far_plane) *
                        glm::lookAt(eye, target, gltest::vec3(v.up));
    float widest = 0;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 p = centre + half * glm::vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
      const glm::vec4 q = m * glm::vec4(p, 1);
      ASSERT_GT(q.w, v.near_plane) << trial;
      EXPECT_LE(std::fabs(q.x / q.w), 1.0f) << trial;
      EXPECT_LE(std::fabs(q.y / q.w), 1.0f) << trial;
      widest = std::max({widest, std::fabs(q.x / q.w), std::fabs(q.y / q.w)});
    }
    EXPECT_GT(widest, 0.8f) << trial;  // fitted, not a speck
  }
}

}  // namespace
