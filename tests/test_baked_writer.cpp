// geom/baked_writer.h's write_baked_if_changed: the file it leaves is the one
// write_baked writes (serialize_baked's bytes) whatever was there before, it
// leaves a file that already holds those bytes untouched (same inode, same
// mtime) and rewrites one that differs anywhere: one byte of any section, one
// byte of the header, a byte more or less, a symlink in its place. Random
// sections, some over the 1 MiB the comparison reads at a time.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "geom/baked_writer.h"
#include "scratch.h"

namespace {

using testfs::read_all;
using testfs::write_all;

std::vector<geom::BakedSection> random_sections(std::mt19937& rng) {
  std::vector<geom::BakedSection> sections;
  const int n = 1 + int(rng() % 5);
  for (int i = 0; i < n; ++i) {
    std::vector<uint32_t> values(rng() % 3 == 0 ? 300000 + rng() % 300000 : rng() % 2000);
    for (uint32_t& v : values) v = rng();
    sections.push_back(geom::make_baked_section(geom::baked::SectionType::Indices, geom::baked::Format::U32, 4,
                                                "s" + std::to_string(i), std::move(values)));
  }
  return sections;
}

struct stat stat_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::lstat(path.c_str(), &st), 0) << path;
  return st;
}

}  // namespace

TEST(BakedWriter, WritesOnlyWhatChanged) {
  testfs::Scratch dir("baked_writer_changed");  // this process's own: two test runs at once share nothing
  const std::string path = dir / "written_if_changed.gbake", other = dir / "symlink_target.gbake";
  std::mt19937 rng(3);
  for (int round = 0; round < 24; ++round) {
    const std::vector<geom::BakedSection> sections = random_sections(rng);
    std::vector<unsigned char> want;
    std::string error;
    ASSERT_TRUE(geom::serialize_baked(sections, want, error)) << error;
    std::vector<uint32_t> crcs_plain, crcs;
    ASSERT_TRUE(geom::write_baked(path, sections, error, &crcs_plain)) << error;

    // The same bytes there: untouched.
    const struct stat before = stat_of(path);
    ::usleep(2000);
    bool unchanged = false;
    ASSERT_TRUE(geom::write_baked_if_changed(path, sections, unchanged, error, &crcs)) << error;
    EXPECT_TRUE(unchanged) << round;
    EXPECT_EQ(crcs, crcs_plain);
    const struct stat after = stat_of(path);
    EXPECT_EQ(after.st_ino, before.st_ino);
    EXPECT_EQ(after.st_mtim.tv_nsec, before.st_mtim.tv_nsec);
    EXPECT_EQ(after.st_mtim.tv_sec, before.st_mtim.tv_sec);

    // Anything else there: rewritten to the new bytes.
    std::vector<std::vector<unsigned char>> olds;
    std::vector<unsigned char> old = want;
    old[rng() % old.size()] ^= uint8_t(1 + rng() % 255);  // one byte anywhere
    olds.push_back(old);
    old = want;
    old[old.size() - 1] ^= 0x80;  // the last byte
    olds.push_back(old);
    old = want;
    old[rng() % geom::baked::kHeaderSize] ^= 1;  // the header
    olds.push_back(old);
    old = want;
    old.push_back(0);  // one byte more
    olds.push_back(old);
    old = want;
    old.pop_back();  // one byte less
    olds.push_back(old);
    olds.push_back({});  // empty
    for (const auto& o : olds) {
      write_all(path, o);
      ASSERT_TRUE(geom::write_baked_if_changed(path, sections, unchanged, error)) << error;
      EXPECT_FALSE(unchanged) << round;
      EXPECT_EQ(read_all(path), want) << round;
    }

    // A symlink to a file with the very bytes: replaced by a file, its target left alone.
    write_all(other, want);
    std::remove(path.c_str());
    ASSERT_EQ(::symlink(other.c_str(), path.c_str()), 0);
    ASSERT_TRUE(geom::write_baked_if_changed(path, sections, unchanged, error)) << error;
    EXPECT_FALSE(unchanged);
    EXPECT_FALSE(S_ISLNK(stat_of(path).st_mode));
    EXPECT_EQ(read_all(path), want);
    EXPECT_EQ(read_all(other), want);
  }
  std::remove(path.c_str());
  std::remove(other.c_str());
}

// A bad section: the error, nothing written, the old file kept.
TEST(BakedWriter, BadSectionWritesNothing) {
  testfs::Scratch dir("baked_writer_bad");
  const std::string path = dir / "bad_section.gbake";
  write_all(path, {1, 2, 3});
  geom::BakedSection s;
  s.name = "a name far longer than fifteen characters";
  s.stride = 4;
  bool unchanged = true;
  std::string error;
  EXPECT_FALSE(geom::write_baked_if_changed(path, {s}, unchanged, error));
  EXPECT_FALSE(unchanged);
  EXPECT_NE(error.find("name longer than"), std::string::npos) << error;
  EXPECT_EQ(read_all(path), (std::vector<unsigned char>{1, 2, 3}));
  std::remove(path.c_str());
}
