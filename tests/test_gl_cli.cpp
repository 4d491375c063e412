// geomview's scripted use, end to end: an OBJ written here, the camera, light
// and spot flags, `--output mask` read back from the PNG (top row first) and
// compared with the ray-cast reference of the same setup; multi-technique runs
// into a folder; `Error:` and a non-zero exit on bad flags and bad files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geom/png.h"
#include "geom/shadow_reference.h"
#include "gl_fixtures.h"
#include "viewer_run.h"

namespace {

namespace fs = std::filesystem;

using viewertest::kScene;  // the geomview tests' scene (viewer_run.h)
const char* const kObj = kScene;

struct Temp : testfs::Scratch {
  Temp() : testfs::Scratch("geomview_cli") {}
};

int run(const std::string& args, std::string* output = nullptr) {
  const std::string command = std::string(GEOMVIEW_EXE) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[512];
  std::string text;
  while (fgets(buffer, sizeof buffer, pipe)) text += buffer;
  const int status = pclose(pipe);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(GlCli, MaskMatchesTheReference) {
  Temp temp;
  const fs::path obj = temp.dir / "scene.obj";
  std::ofstream(obj) << kObj;
  std::vector<float> p;
  std::vector<uint32_t> idx;
  viewertest::parse_obj(kObj, p, idx);
  struct Case {
    std::string flags;
    geom::Light light;
  };
  std::vector<Case> cases(3);
  cases[0].flags = "--light -2,5,-3,1";
  cases[0].light = gltest::point_light({-2, 5, -3});
  cases[1].flags = "--light -0.5,1,-0.8,0";
  cases[1].light = gltest::sun({-0.5f, 1, -0.8f});
  cases[2].flags = "--light 2,5,2,1 --spot -2,-5,-2,30";
  cases[2].light = gltest::spot_light({2, 5, 2}, {-2, -5, -2}, 30);
  geom::Camera camera;
  const float eye[3] = {3, 4, 6}, target[3] = {0, 0.5f, 0}, up[3] = {0, 1, 0};
  for (int k = 0; k < 3; ++k) camera.eye[k] = eye[k], camera.target[k] = target[k], camera.up[k] = up[k];
  camera.fovy_deg = 45, camera.near_plane = 0.1f, camera.far_plane = 50, camera.width = 120, camera.height = 90;
  for (const Case& c : cases) {
    const fs::path png = temp.dir / "mask.png";
    std::string out;
    ASSERT_EQ(
        run(obj.string() + " --technique sv --eye 3,4,6 --target 0,0.5,0 --up 0,1,0 --fovy 45 --near 0.1 --far 50 " +
                c.flags + " --size 120x90 --output mask -o " + png.string(),
            &out),
        0)
        << out;
    geom::PngImage mask;
    std::string error;
    ASSERT_TRUE(geom::read_png(png.string(), mask, error)) << error;
    ASSERT_EQ(mask.channels, 1);
    ASSERT_EQ(mask.width, 120);
    ASSERT_EQ(mask.height, 90);
    const geom::ShadowReference ref =
        geom::shadow_reference(geom::positions_of(p.data(), p.size() / 3), idx.data(), idx.size(), camera, c.light);
    ASSERT_TRUE(ref.ok) << ref.error;
    size_t wrong = 0, certain = 0, shadowed = 0, lit = 0, background = 0;
    for (size_t i = 0; i < ref.mask.size(); ++i) {
      if (ref.uncertain[i]) continue;
      ++certain;
      wrong += mask.pixels[i] != ref.mask[i];
      shadowed += ref.mask[i] == 0, lit += ref.mask[i] == 255, background += ref.mask[i] == 128;
    }
    SCOPED_TRACE(c.flags);
    EXPECT_EQ(wrong, 0u) << wrong << " of " << certain;
    EXPECT_GT(shadowed, 200u);
    EXPECT_GT(lit, 200u);
    EXPECT_GT(background, 200u);
  }
}

TEST(GlCli, SeveralTechniquesIntoAFolder) {
  Temp temp;
  const fs::path obj = temp.dir / "scene.obj";
  std::ofstream(obj) << kObj;
  std::string out;
  ASSERT_EQ(run(obj.string() + " --technique ssm,edsm,cube --light -2,5,-3,1 --size 64x48 --shadow-map-size 256 -o " +
                    (temp.dir / "out").string(),
                &out),
            0)
      << out;
  for (const char* name : {"ssm", "edsm", "cube"}) {
    geom::PngImage image;
    std::string error;
    EXPECT_TRUE(geom::read_png((temp.dir / "out" / (std::string(name) + ".png")).string(), image, error)) << error;
    EXPECT_EQ(image.channels, 3);
    EXPECT_EQ(image.width, 64);
  }
  ASSERT_EQ(run(obj.string() + " --technique ssm --frames 3 --size 32x24 -o " + (temp.dir / "f.png").string(), &out), 0)
      << out;
  EXPECT_NE(out.find("ssm frame 2:"), std::string::npos) << out;
}

TEST(GlCli, ErrorsAreReported) {
  Temp temp;
  const fs::path obj = temp.dir / "scene.obj";
  std::ofstream(obj) << kObj;
  const std::string o = " -o " + (temp.dir / "x.png").string();
  const char* bad[] = {" --technique nope",    " --light 1,2,3",  " --light 1,2,3,0 --spot 0,-1,0,30",
                       " --size 0x10",         " --fovy 200",     " --near 5 --far 1",
                       " --shadow-map-size 3", " --output depth", " --eye 0,0,0 --target 0,0,0"};
  for (const char* flags : bad) {
    std::string out;
    EXPECT_NE(run(obj.string() + flags + o, &out), 0) << flags;
    EXPECT_NE(out.find("Error:"), std::string::npos) << flags << ": " << out;
  }
  std::string out;
  EXPECT_NE(run((temp.dir / "missing.obj").string() + o, &out), 0);
  EXPECT_NE(out.find("missing.obj"), std::string::npos) << out;
  std::ofstream(temp.dir / "broken.obj") << "v 0 0 0\nf 1 2 3\n";
  EXPECT_NE(run((temp.dir / "broken.obj").string() + o, &out), 0);
  EXPECT_NE(out.find("Error:"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(temp.dir / "x.png"));
}

}  // namespace
