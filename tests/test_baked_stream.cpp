// The streamed bake (geom/bake.h bake_scene(Scene&&, name, options, writer),
// geom/baked_writer.h BakedFileWriter): the file it leaves is byte for byte
// write_baked's of bake_scene's sections, for every flag combination and with
// lights; an output already there that holds those bytes is left untouched
// (same inode and mtime), one that differs anywhere (a byte of a section past
// the 1 MiB the comparison reads at a time, of the header, one byte more or
// less) is rewritten, a symlink is replaced and its target left alone; a writer
// given up on before finish() or failing leaves nothing behind.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "geom/bake.h"
#include "geom/baked_writer.h"
#include "geom/crc32c.h"
#include "scratch.h"

namespace {

using testfs::read_all;
using testfs::write_all;

// A closed, rippled sphere: n x n quads and two fans (some edges coplanar, some concave).
geom::Scene sphere(int n) {
  geom::Scene s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = 2 * M_PI * (i % n) / n, v = M_PI * (0.05 + 0.9 * j / n);
      const double r = 1 + (j > n / 2 ? 0.03 * std::sin(7 * u) : 0.0);
      s.positions.insert(s.positions.end(), {float(r * std::cos(u) * std::sin(v)), float(r * std::cos(v)),
                                             float(r * std::sin(u) * std::sin(v))});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.indices.insert(s.indices.end(), {a, b, c, b, d, c});
    }
  const uint32_t top = uint32_t(s.vertex_count()), bottom = top + 1;
  s.positions.insert(s.positions.end(), {0, 1, 0, 0, -1, 0});
  for (int i = 0; i < n; ++i) {
    s.indices.insert(s.indices.end(), {top, uint32_t(i + 1), uint32_t(i)});
    const uint32_t a = n * (n + 1) + i;
    s.indices.insert(s.indices.end(), {bottom, a, a + 1});
  }
  s.sources.resize(s.triangle_count());
  return s;
}

// A soup: duplicated, open, non-manifold and collapsed triangles.
geom::Scene soup(std::mt19937& rng) {
  geom::Scene s;
  const int v = 6 + int(rng() % 40);
  for (int i = 0; i < v; ++i)
    for (int k = 0; k < 3; ++k) s.positions.push_back(float(int(rng() % 9)) * 0.25f);
  const int t = 1 + int(rng() % 120);
  for (int i = 0; i < 3 * t; ++i) s.indices.push_back(uint32_t(rng() % uint32_t(v)));
  s.sources.resize(s.triangle_count());
  return s;
}

geom::Light light(double x, double y, double z, double w) {
  const double h[4] = {x, y, z, w};
  return geom::light_from_homogeneous(h);
}

// The file write_baked makes of bake_scene's sections.
std::vector<unsigned char> plain_bytes(const geom::Scene& scene, const geom::BakeOptions& options) {
  const geom::BakeResult r = geom::bake_scene(scene, "mesh", options);
  EXPECT_TRUE(r.ok) << r.error;
  std::vector<unsigned char> bytes;
  std::string error;
  EXPECT_TRUE(geom::serialize_baked(r.sections, bytes, error)) << error;
  return bytes;
}

// The streamed bake to `path`; its result and finish()'s.
struct Streamed {
  geom::BakeResult result;
  bool finished = false, unchanged = false;
  std::vector<uint32_t> crcs;
  std::string error;
};
Streamed stream(geom::Scene scene, const geom::BakeOptions& options, const std::string& path, bool keep_if_same) {
  Streamed s;
  geom::BakedFileWriter writer;
  writer.open(path, keep_if_same);
  s.result = geom::bake_scene(std::move(scene), "mesh", options, writer);
  if (s.result.ok) s.finished = writer.finish(s.unchanged, &s.crcs);
  s.error = writer.error();
  return s;
}

struct stat stat_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::lstat(path.c_str(), &st), 0) << path;
  return st;
}

size_t entries_in(const std::string& dir) {
  size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) n += !e.path().empty();
  return n;
}

}  // namespace

TEST(BakedStream, SameBytesAsWriteBakedForEveryFlagCombination) {
  testfs::Scratch dir("baked_stream_flags");
  std::mt19937 rng(14);
  std::vector<geom::Scene> scenes = {sphere(12), sphere(3), soup(rng), soup(rng), geom::Scene()};
  for (size_t k = 0; k < scenes.size(); ++k)
    for (unsigned flags = 0; flags < 256; flags += (k == 0 ? 1 : 7)) {
      geom::BakeOptions o;
      o.positions = flags & 1;
      o.indices = flags & 2;
      o.weld_remap = flags & 4;
      o.pipeline.face_planes = flags & 8;
      o.topology_report = flags & 16;
      o.pipeline.esm = flags & 32;
      o.pipeline.volume = flags & 64;
      o.pipeline.adjacency = flags & 128;
      if (flags % 3 == 1) o.lights = {light(3, 4, 5, 1)};
      if (flags % 3 == 2) o.lights = {light(0.2, 1, 0.3, 0), light(-2, 0.5, 4, 1)};
      const std::string what = "scene " + std::to_string(k) + " flags " + std::to_string(flags);
      const std::vector<unsigned char> want = plain_bytes(scenes[k], o);
      const std::string path = dir / "flags.gbake";
      const Streamed s = stream(scenes[k], o, path, false);
      ASSERT_TRUE(s.result.ok) << what << ": " << s.result.error;
      ASSERT_TRUE(s.finished) << what << ": " << s.error;
      EXPECT_FALSE(s.unchanged) << what;
      EXPECT_EQ(read_all(path), want) << what;
      // The result describes what was written; the CRCs are the file's.
      const geom::BakeResult plain = geom::bake_scene(scenes[k], "mesh", o);
      ASSERT_EQ(s.result.sections.size(), plain.sections.size()) << what;
      ASSERT_EQ(s.crcs.size(), plain.sections.size()) << what;
      for (size_t i = 0; i < plain.sections.size(); ++i) {
        const geom::BakedSection &a = s.result.sections[i], &b = plain.sections[i];
        EXPECT_EQ(a.name, b.name) << what;
        EXPECT_EQ(a.count * a.stride, b.size()) << what << " " << b.name;
        EXPECT_EQ(a.size(), 0u) << what << " " << b.name;  // the bytes are gone
        EXPECT_EQ(s.crcs[i], geom::crc32c(b.data(), b.size())) << what << " " << b.name;
      }
      EXPECT_EQ(s.result.silhouette, plain.silhouette) << what;
      EXPECT_EQ(geom::report_json(s.result.report), geom::report_json(plain.report)) << what;
    }
}

TEST(BakedStream, ComparesWithTheOutputThere) {
  testfs::Scratch dir("baked_stream_compare");
  const geom::Scene scene = sphere(160);  // sections over the 1 MiB the comparison reads at a time
  const geom::BakeOptions o;
  const std::vector<unsigned char> want = plain_bytes(scene, o);
  ASSERT_GT(want.size(), size_t(3) << 20);
  const std::string path = dir / "out.gbake", other = dir / "target.gbake";

  Streamed s = stream(scene, o, path, true);  // nothing there: written
  ASSERT_TRUE(s.finished) << s.error;
  EXPECT_FALSE(s.unchanged);
  ASSERT_EQ(read_all(path), want);

  // The same bytes there: untouched.
  const struct stat before = stat_of(path);
  ::usleep(2000);
  s = stream(scene, o, path, true);
  ASSERT_TRUE(s.finished) << s.error;
  EXPECT_TRUE(s.unchanged);
  const struct stat after = stat_of(path);
  EXPECT_EQ(after.st_ino, before.st_ino);
  EXPECT_EQ(after.st_mtim.tv_sec, before.st_mtim.tv_sec);
  EXPECT_EQ(after.st_mtim.tv_nsec, before.st_mtim.tv_nsec);

  // Not asked to keep it: rewritten all the same.
  s = stream(scene, o, path, false);
  ASSERT_TRUE(s.finished) << s.error;
  EXPECT_FALSE(s.unchanged);
  EXPECT_NE(stat_of(path).st_ino, before.st_ino);
  EXPECT_EQ(read_all(path), want);

  // Anything else there: rewritten to the new bytes.
  std::vector<std::vector<unsigned char>> olds;
  for (size_t at : {size_t(3), size_t(100), size_t(2000), want.size() / 3, want.size() / 2 + 12345, want.size() - 1}) {
    std::vector<unsigned char> old = want;
    old[at] ^= 0x5a;
    olds.push_back(old);
  }
  olds.push_back(std::vector<unsigned char>(want.begin(), want.end() - 1));
  std::vector<unsigned char> longer = want;
  longer.push_back(0);
  olds.push_back(longer);
  olds.push_back({});
  for (size_t k = 0; k < olds.size(); ++k) {
    write_all(path, olds[k]);
    s = stream(scene, o, path, true);
    ASSERT_TRUE(s.finished) << k << ": " << s.error;
    EXPECT_FALSE(s.unchanged) << k;
    EXPECT_EQ(read_all(path), want) << k;
  }

  // A symlink there, even to the same bytes: replaced, never compared through; its target left alone.
  write_all(other, want);
  std::filesystem::remove(path);
  std::filesystem::create_symlink(other, path);
  s = stream(scene, o, path, true);
  ASSERT_TRUE(s.finished) << s.error;
  EXPECT_FALSE(s.unchanged);
  EXPECT_FALSE(std::filesystem::is_symlink(path));
  EXPECT_EQ(read_all(path), want);
  EXPECT_EQ(read_all(other), want);
  EXPECT_EQ(entries_in(dir.dir.string()), 2u);  // out.gbake and target.gbake: no temporary file
}

TEST(BakedStream, GivenUpOrFailedLeavesNothing) {
  testfs::Scratch dir("baked_stream_fail");
  const geom::Scene scene = sphere(20);
  const geom::BakeOptions o;
  const std::string path = dir / "out.gbake";

  {  // baked, never finished (the CLI's time-out): no file
    geom::BakedFileWriter writer;
    writer.open(path, true);
    ASSERT_TRUE(geom::bake_scene(geom::Scene(scene), "mesh", o, writer).ok);
  }
  EXPECT_EQ(entries_in(dir.dir.string()), 0u);

  // An old file that differs, given up on after the writing started: the old file as it was.
  const std::vector<unsigned char> old(5000, 7);
  write_all(path, old);
  {
    geom::BakedFileWriter writer;
    writer.open(path, true);
    ASSERT_TRUE(geom::bake_scene(geom::Scene(scene), "mesh", o, writer).ok);
  }
  EXPECT_EQ(read_all(path), old);
  EXPECT_EQ(entries_in(dir.dir.string()), 1u);

  // No folder to write in: the bake fails with the writer's error, nothing is made.
  const std::string missing = dir / "no/such/dir/out.gbake";
  const Streamed s = stream(scene, o, missing, true);
  EXPECT_FALSE(s.result.ok);
  EXPECT_NE(s.result.error.find("mesh: cannot write the output: cannot create a temporary file in"), std::string::npos)
      << s.result.error;
  EXPECT_NE(s.error.find("cannot create a temporary file in"), std::string::npos) << s.error;
  EXPECT_FALSE(std::filesystem::exists(dir / "no"));

  // A writer used out of order says so and writes nothing.
  geom::BakedFileWriter writer;
  writer.open(path, false);
  ASSERT_TRUE(writer.expect(2));
  const geom::BakedSection one = geom::make_baked_section(geom::baked::SectionType::Indices, geom::baked::Format::U32,
                                                          4, "one", std::vector<uint32_t>{1, 2, 3});
  ASSERT_TRUE(writer.put(one)) << writer.error();
  bool unchanged = true;
  EXPECT_FALSE(writer.finish(unchanged));  // one of the two sections
  EXPECT_NE(writer.error().find("internal: 1 sections of the 2 expected"), std::string::npos) << writer.error();
  EXPECT_FALSE(writer.put(one));  // every later call fails too
  EXPECT_EQ(read_all(path), old);
}

// A section begun without its size (begin_records) is the bytes written to
// it: the same file as put() of the whole, in any pieces; a piece that ends
// inside a record fails at end() and nothing is left.
TEST(BakedStream, RecordsOfUnknownCountAreTheBytesWritten) {
  testfs::Scratch dir("baked_stream_records");
  using geom::baked::Format;
  using geom::baked::SectionType;
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    std::vector<uint32_t> a(rng() % 3000), b(1 + rng() % 50);
    for (uint32_t& x : a) x = rng();
    for (uint32_t& x : b) x = rng();
    const std::vector<geom::BakedSection> whole = {
        geom::make_baked_section(SectionType::VolumeSides, Format::U32, 4, "a", a),
        geom::make_baked_section(SectionType::Indices, Format::U32, 4, "b", b)};
    std::vector<unsigned char> expected;
    std::string error;
    ASSERT_TRUE(geom::serialize_baked(whole, expected, error)) << error;

    const std::string path = dir / "out.gbake";
    geom::BakedFileWriter writer;
    writer.open(path, round % 2 == 0);  // compared with the last round's file, or written
    ASSERT_TRUE(writer.expect(2));
    geom::BakedSection head = whole[0];
    head.count = 12345;  // ignored
    ASSERT_TRUE(writer.begin_records(head)) << writer.error();
    for (size_t at = 0; at < a.size();) {
      const size_t n = std::min(a.size() - at, size_t(rng() % 700));
      ASSERT_TRUE(writer.write(a.data() + at, 4 * n)) << writer.error();
      at += n;
    }
    ASSERT_TRUE(writer.end()) << writer.error();
    ASSERT_TRUE(writer.put(whole[1])) << writer.error();
    bool unchanged = false;
    ASSERT_TRUE(writer.finish(unchanged)) << writer.error();
    EXPECT_EQ(read_all(path), expected) << "round " << round;
  }

  geom::BakedFileWriter writer;
  const std::string path = dir / "torn.gbake";
  writer.open(path, false);
  ASSERT_TRUE(writer.expect(1));
  geom::BakedSection s = geom::make_baked_section(SectionType::VolumeSides, Format::Record, 32, "sides",
                                                  std::vector<unsigned char>(64));
  ASSERT_TRUE(writer.begin_records(s));
  const std::vector<unsigned char> bytes(40, 1);
  ASSERT_TRUE(writer.write(bytes.data(), bytes.size()));
  EXPECT_FALSE(writer.end());
  EXPECT_NE(writer.error().find("ends inside a record"), std::string::npos) << writer.error();
  bool unchanged = true;
  EXPECT_FALSE(writer.finish(unchanged));
  EXPECT_FALSE(std::filesystem::exists(path));
}
