// geomview's window, tested as the headless path is: under `xvfb-run -a` (setup
// installs Xvfb) it opens a GLFW window with its ImGui panels, is driven by
// keys (--script feeds them through the window's key handler, one per
// frame), and its screenshot (--screenshot: the window's back buffer after
// the keys) shows the HUD, the panels and the inspection; the error the HUD
// shows after E is the headless CLI's for the same view.
#include <gtest/gtest.h>

#include <fstream>

#include "render/render.h"
#include "viewer_run.h"

namespace {

using namespace viewertest;

const std::string kView = std::string(kSceneView) + " --size 320x240";

TEST(GlViewerWindow, KeysHudPanelsAndScreenshot) {
  Scratch s("window");
  const std::string obj = s / "scene.obj";
  std::ofstream(obj) << kScene;
  // pcf, T -> esm, T -> edsm, I inspection on, E measure the error.
  const ViewerRun w = geomview(
      s, obj + " " + kView + " --window --technique pcf --script ttie --screenshot " + (s / "shot.png"), "xvfb-run -a");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  EXPECT_EQ(w.err.find("rendering headless"), std::string::npos) << w.err;
  const std::vector<std::string> hud = w.lines("hud: ");
  ASSERT_GE(hud.size(), 4u) << w.out;
  EXPECT_EQ(hud[0].rfind("edsm 1024 | ", 0), 0u) << hud[0];  // then the projection drawn
  const ViewerRun cli = geomview(s, obj + " " + kView + " --technique edsm --error -o " + (s / "cli.png"));
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_EQ(cli.lines("edsm "), (std::vector<std::string>{hud[2], hud[3]}));
  const geom::PngImage shot = read_rgb(s / "shot.png");
  ASSERT_EQ(shot.width, 320);
  ASSERT_EQ(shot.height, 240);
  // The HUD (top left): near-white text on its dark box.
  size_t text = 0;
  for (int y = 10; y < 40; ++y)
    for (int x = 10; x < 120; ++x) {
      const uint8_t* p = pixel(shot, x, y);
      text += p[0] > 200 && p[1] > 200 && p[2] > 200;
    }
  EXPECT_GT(text, 40u);
  // The inspection (I): the ground's four boundary edges in yellow.
  float yellow[3];
  render::inspection_colour(render::InspectKind::Boundary, yellow);
  EXPECT_GT(count_colour(shot, yellow), 60u);
  // The panels differ from the headless frame of the same view; H hides them, then the
  // window's frame below the HUD is the headless one.
  const ViewerRun bare = geomview(
      s, obj + " " + kView + " --window --technique edsm --script h --screenshot " + (s / "bare.png"), "xvfb-run -a");
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  const geom::PngImage b = read_rgb(s / "bare.png"), c = read_rgb(s / "cli.png");
  ASSERT_EQ(b.width, 320);
  size_t differ = 0, panel = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      if (y >= 200)
        differ += !std::equal(pixel(b, x, y), pixel(b, x, y) + 3, pixel(c, x, y));  // below the HUD's 10 lines
      if (x >= 200 && y < 100) panel += !std::equal(pixel(b, x, y), pixel(b, x, y) + 3, pixel(shot, x, y));
    }
  EXPECT_LT(differ, size_t(320 * 40 / 100));  // within 1%: the same frame
  EXPECT_GT(panel, 1000u);                    // the panel was there, top right
  // C: the compare grid of the default picks, each panel's figures printed.
  const ViewerRun grid =
      geomview(s, obj + " " + kView + " --window --script c --screenshot " + (s / "grid.png"), "xvfb-run -a");
  ASSERT_EQ(grid.exit_code, 0) << grid.err;
  const std::vector<std::string> g = grid.lines("grid: ");
  ASSERT_EQ(g.size(), 16u) << grid.out;
  EXPECT_EQ(g[0].rfind("ssm 1024 | ", 0), 0u) << g[0];  // then the projection drawn
  EXPECT_EQ(g[4].rfind("pcf 1024 | ", 0), 0u) << g[4];
  EXPECT_EQ(g[8].rfind("edsm 1024 | ", 0), 0u) << g[8];
  EXPECT_EQ(g[12], "sv | shadow volumes");
}

}  // namespace
