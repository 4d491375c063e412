// The apps' strict number parsing (tools/common/cli/args.h): the whole text,
// the range, integers where integers are meant, the flag named in the error;
// and the one light and camera validation (cli/view_check.h) every program
// applies, whatever the source.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/view_check.h"

namespace {

TEST(CliArgs, IntegersAreWholeAndInRange) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const long long lo = -1000 + (long long)(rng() % 1000), hi = lo + (long long)(rng() % 100000);
    const long long v = lo - 50 + (long long)(rng() % uint32_t(hi - lo + 100));
    long long out = 12345;
    const std::string text = std::to_string(v);
    EXPECT_EQ(cli::parse_int(text, lo, hi, out), v >= lo && v <= hi) << text;
    if (v >= lo && v <= hi) EXPECT_EQ(out, v);
    // Anything around the digits is refused.
    for (const std::string& bad :
         {text + "abc", text + " ", " " + text, text + ".0", text + "e0", "0x" + text, text + "\n", std::string("")})
      EXPECT_FALSE(cli::parse_int(bad, lo, hi, out)) << "'" << bad << "'";
  }
  long long out = 0;
  EXPECT_FALSE(cli::parse_int("1e3", 1, 100000, out));                         // --frames 1e3 is not 1
  EXPECT_FALSE(cli::parse_int("4294968320", 16, 16384, out));                  // not wrapped to 1024
  EXPECT_FALSE(cli::parse_int("99999999999999999999999", 0, 1LL << 62, out));  // overflow
  EXPECT_FALSE(cli::parse_int("-", -5, 5, out));
  EXPECT_TRUE(cli::parse_int("+7", 0, 10, out));
  EXPECT_EQ(out, 7);
}

TEST(CliArgs, RealsAreWholeFiniteAndInRange) {
  double out = 0;
  for (const char* bad : {"abc", "", " 1", "1 ", "1x", "nan", "inf", "-inf", "1e999", "0.5.5"})
    EXPECT_FALSE(cli::parse_real(bad, -1e300, 1e300, out)) << bad;
  EXPECT_FALSE(cli::parse_real("-0.5", 0, 1e6, out));
  EXPECT_FALSE(cli::parse_real("2e6", 0, 1e6, out));
  EXPECT_TRUE(cli::parse_real("2.5e-3", 0, 1, out));
  EXPECT_DOUBLE_EQ(out, 2.5e-3);
}

TEST(CliArgs, SizesAndListsAreStrict) {
  int w = 0, h = 0;
  EXPECT_TRUE(cli::parse_size("640x480", 1, 16384, w, h));
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  for (const char* bad : {"640x", "x480", "640x480x", "640 x480", "0x10", "640x16385", "1e3x10", "640X480", "640"})
    EXPECT_FALSE(cli::parse_size(bad, 1, 16384, w, h)) << bad;
  std::vector<std::string> items;
  EXPECT_TRUE(cli::parse_list("a,b,c", items));
  EXPECT_EQ(items, (std::vector<std::string>{"a", "b", "c"}));
  for (const char* bad : {"", ",", "a,", ",a", "a,,b"}) EXPECT_FALSE(cli::parse_list(bad, items)) << bad;
  // parse_floats: no blank before a number (strtof would skip it).
  float v[3];
  EXPECT_TRUE(cli::parse_floats("1,2,3", 3, v));
  for (const char* bad : {" 1,2,3", "1, 2,3", "1,2,3 ", "1,2,", "1,2"})
    EXPECT_FALSE(cli::parse_floats(bad, 3, v)) << bad;
}

TEST(CliArgs, TheErrorNamesTheFlagTheValueAndTheRange) {
  cli::Args args({"--frames", "1e3", "--light-radius", "abc", "--size", "16x0", "--scenes", ""}, {},
                 {"--frames", "--light-radius", "--size", "--scenes"});
  ASSERT_EQ(args.error(), "");
  std::string error;
  int frames = 1;
  EXPECT_FALSE(cli::int_option(args, "--frames", 1, 100000, frames, error));
  EXPECT_EQ(error, "--frames: '1e3' is not an integer within 1..100000");
  EXPECT_EQ(frames, 1);
  double radius = 0;
  EXPECT_FALSE(cli::real_option(args, "--light-radius", 0, 1e6, radius, error));
  EXPECT_EQ(error.rfind("--light-radius: 'abc'", 0), 0u) << error;
  int w = 0, h = 0;
  EXPECT_FALSE(cli::size_option(args, "--size", 1, 16384, w, h, error));
  EXPECT_EQ(error.rfind("--size: '16x0'", 0), 0u) << error;
  std::vector<std::string> items;
  EXPECT_FALSE(cli::list_option(args, "--scenes", items, error));
  EXPECT_EQ(error.rfind("--scenes: ''", 0), 0u) << error;
  int absent = 42;
  EXPECT_TRUE(cli::int_option(args, "--nothing", 0, 1, absent, error));
  EXPECT_EQ(absent, 42);
}

// The light check: finite is not enough; every source's light goes through it.
TEST(ViewCheck, LightsWithinTheLimits) {
  std::string error;
  geom::Light l;
  l.position[0] = 2e18;  // Embree's ray validity ends at 1.8e18
  EXPECT_FALSE(cli::check_light(l, "--light", error));
  EXPECT_EQ(error.rfind("--light: position coordinate 2e+18", 0), 0u) << error;
  l.position[0] = 1e15;
  EXPECT_TRUE(cli::check_light(l, "--light", error)) << error;
  geom::Light sun;
  sun.type = geom::LightType::Directional;
  for (double d : {1e20, 1e154, 0.0, 1e-30, std::nan("")}) {
    sun.direction[0] = d, sun.direction[1] = sun.direction[2] = 0;
    EXPECT_FALSE(cli::check_light(sun, "light", error)) << d;
  }
  sun.direction[0] = 1e-3;
  EXPECT_TRUE(cli::check_light(sun, "light", error)) << error;
}

// The camera check: near against far for a 24-bit depth buffer, the eye and
// the target apart, up off the view direction; random sane cameras pass.
TEST(ViewCheck, CamerasThatCannotGiveAnImageAreRefused) {
  std::string error;
  geom::Camera c;  // eye (0,0,5), target 0, up y, near 0.1, far 1000
  EXPECT_TRUE(cli::check_camera(c, "camera", error)) << error;
  c.near_plane = 1e-7f, c.far_plane = 100;
  EXPECT_FALSE(cli::check_camera(c, "camera", error));
  EXPECT_NE(error.find("24-bit depth"), std::string::npos) << error;
  c = geom::Camera();
  c.up[0] = 0, c.up[1] = 0, c.up[2] = 1;  // along the view
  EXPECT_FALSE(cli::check_camera(c, "camera", error));
  EXPECT_NE(error.find("parallel"), std::string::npos) << error;
  c = geom::Camera();
  c.eye[0] = 1e19f;
  EXPECT_FALSE(cli::check_camera(c, "camera", error));
  c = geom::Camera();
  c.eye[0] = 1e15f, c.target[0] = 1e15f + 1;  // the same float
  EXPECT_FALSE(cli::check_camera(c, "camera", error));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1e4f, 1e4f);
  for (int trial = 0; trial < 500; ++trial) {
    geom::Camera r;
    for (int k = 0; k < 3; ++k) r.eye[k] = u(rng), r.target[k] = u(rng);
    r.near_plane = 0.01f + std::fabs(u(rng)) * 1e-3f, r.far_plane = r.near_plane * (2 + std::fabs(u(rng)) * 10);
    r.fovy_deg = 1 + std::fabs(u(rng)) * 0.0170f;
    EXPECT_TRUE(cli::check_camera(r, "camera", error)) << error;
  }
}

}  // namespace
