// geom/png.h: PNG writing and reading as the apps and the GL tests use them.
// Laws: what is written reads back bit for bit at every channel count and
// size (odd widths, one-pixel images); reading converts channel counts;
// inconsistent images and unreadable or non-PNG files are refused with an
// error naming the file, and a refused write leaves no file.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "geom/png.h"
#include "scratch.h"

namespace {

namespace fs = std::filesystem;

struct Scratch : testfs::Scratch {
  Scratch() : testfs::Scratch("geom_png") {}
};

TEST(Png, WrittenImagesReadBackExactly) {
  Scratch s;
  std::mt19937 rng(3);
  for (int trial = 0; trial < 60; ++trial) {
    geom::PngImage im;
    im.channels = 1 + trial % 4;
    im.width = 1 + int(rng() % 67), im.height = 1 + int(rng() % 45);
    im.pixels.resize(size_t(im.width) * im.height * im.channels);
    for (uint8_t& p : im.pixels) p = uint8_t(trial % 5 == 0 ? (rng() & 1) * 255 : rng());
    std::string error;
    const std::string path = s / ("im" + std::to_string(trial) + ".png");
    ASSERT_TRUE(geom::write_png(path, im, error)) << error;
    geom::PngImage back;
    ASSERT_TRUE(geom::read_png(path, back, error)) << error;
    EXPECT_EQ(back.width, im.width);
    EXPECT_EQ(back.height, im.height);
    EXPECT_EQ(back.channels, im.channels);
    EXPECT_EQ(back.pixels, im.pixels) << "trial " << trial;
  }
}

TEST(Png, ReadingConvertsTheChannelCount) {
  Scratch s;
  geom::PngImage grey{3, 2, 1, {0, 50, 100, 150, 200, 255}};
  std::string error;
  ASSERT_TRUE(geom::write_png(s / "grey.png", grey, error)) << error;
  geom::PngImage rgb;
  ASSERT_TRUE(geom::read_png(s / "grey.png", rgb, error, 3)) << error;
  ASSERT_EQ(rgb.channels, 3);
  for (size_t i = 0; i < grey.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb.pixels[3 * i + c], grey.pixels[i]);
  geom::PngImage rgba;
  ASSERT_TRUE(geom::read_png(s / "grey.png", rgba, error, 4)) << error;
  for (size_t i = 0; i < grey.pixels.size(); ++i) EXPECT_EQ(rgba.pixels[4 * i + 3], 255);
}

TEST(Png, BadImagesAndFilesAreRefusedNamingTheFile) {
  Scratch s;
  std::string error;
  geom::PngImage bad{4, 4, 3, std::vector<uint8_t>(47)};  // one byte short
  EXPECT_FALSE(geom::write_png(s / "short.png", bad, error));
  EXPECT_NE(error.find("short.png"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(s / "short.png"));
  geom::PngImage five{1, 1, 5, std::vector<uint8_t>(5)};
  EXPECT_FALSE(geom::write_png(s / "five.png", five, error));
  EXPECT_FALSE(fs::exists(s / "five.png"));
  geom::PngImage ok{1, 1, 1, {7}};
  EXPECT_FALSE(geom::write_png(s / "no_such_dir/x.png", ok, error));
  EXPECT_NE(error.find("no_such_dir/x.png"), std::string::npos) << error;

  geom::PngImage im;
  EXPECT_FALSE(geom::read_png(s / "missing.png", im, error));
  EXPECT_NE(error.find("missing.png"), std::string::npos) << error;
  std::ofstream(s / "text.png") << "not a png at all";
  EXPECT_FALSE(geom::read_png(s / "text.png", im, error));
  EXPECT_NE(error.find("text.png"), std::string::npos) << error;
  // A real PNG cut short.
  ASSERT_TRUE(geom::write_png(s / "whole.png", geom::PngImage{16, 16, 3, std::vector<uint8_t>(768, 9)}, error));
  std::ifstream in(s / "whole.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(s / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_FALSE(geom::read_png(s / "cut.png", im, error));
  EXPECT_NE(error.find("cut.png"), std::string::npos) << error;
  EXPECT_FALSE(geom::read_png(s / "whole.png", im, error, 5));
}

}  // namespace

// Writes are checked to the end, as geombake's are: a device that fails every
// write (/dev/full) and a full disk (a file size limit, SIGXFSZ ignored, so the
// writes fail with EFBIG) give an error naming the file, and leave neither a
// truncated PNG nor a temporary file; a FIFO or a device is never a target.
TEST(Png, FailedWritesAreReportedAndLeaveNothing) {
  Scratch t;
  std::mt19937 rng(4);
  geom::PngImage noise;  // incompressible: its PNG is about 200 KB
  noise.width = 256, noise.height = 256, noise.channels = 3;
  for (int i = 0; i < 256 * 256 * 3; ++i) noise.pixels.push_back(uint8_t(rng()));
  std::string error;
  EXPECT_FALSE(geom::write_png("/dev/full", noise, error));
  EXPECT_NE(error.find("/dev/full"), std::string::npos) << error;

  const std::string path = (t.dir / "full.png").string();
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  void (*old_handler)(int) = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const bool written = geom::write_png(path, noise, error);
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_FALSE(written);
  EXPECT_NE(error.find("full.png"), std::string::npos) << error;
  for (const auto& e : std::filesystem::directory_iterator(t.dir)) ADD_FAILURE() << "left behind: " << e.path();
  EXPECT_TRUE(geom::write_png(path, noise, error)) << error;  // without the limit it is written
}
