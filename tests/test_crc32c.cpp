// geom/crc32c.h (the dispatching CRC-32C) and the writer's one-pass output path
// (geom/baked_writer.h write_baked: sections viewed, gathered into one write,
// each checksum computed once and handed back).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "geom/atomic_file.h"
#include "geom/bake.h"
#include "geom/baked_reader.h"
#include "geom/baked_writer.h"
#include "geom/crc32c.h"

namespace {

std::vector<unsigned char> random_bytes(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<unsigned char> v(n);
  for (auto& b : v) b = uint8_t(rng());
  return v;
}

std::vector<unsigned char> read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(f), {});
}

}  // namespace

TEST(Crc32c, CheckValueOnBothPaths) {
  EXPECT_EQ(geom::crc32c("123456789", 9), 0xE3069283u);
  EXPECT_EQ(geom::crc32c_portable("123456789", 9), 0xE3069283u);
  EXPECT_EQ(geom::crc32c(nullptr, 0), 0u);
  std::printf("crc32c on this CPU: %s\n", geom::crc32c_uses_hardware() ? "SSE4.2 instruction" : "table");
}

// Whatever path crc32c() takes, it equals the table on every length and every
// misalignment (the instruction path handles a head up to 8-byte alignment,
// 8-byte steps, then a tail).
TEST(Crc32c, EqualsTheTableAtEveryLengthAndOffset) {
  const std::vector<unsigned char> data = random_bytes(600, 7);
  for (size_t offset = 0; offset < 16; ++offset)
    for (size_t n = 0; offset + n <= 300; ++n)
      ASSERT_EQ(geom::crc32c(data.data() + offset, n), geom::baked::crc32c(data.data() + offset, n))
          << "offset " << offset << " length " << n;
  const std::vector<unsigned char> big = random_bytes(1 << 20, 8);
  EXPECT_EQ(geom::crc32c(big.data(), big.size()), geom::crc32c_portable(big.data(), big.size()));
}

// The instruction path's three streams (12 KiB at a time, joined by a table):
// equal to the table on lengths around those blocks, at every 8-byte phase.
TEST(Crc32c, EqualsTheTableAcrossThreeStreamBlocks) {
  const std::vector<unsigned char> data = random_bytes(5 * 12288 + 64, 10);
  for (size_t offset : {0, 1, 5, 8})
    for (size_t n : {12287, 12288, 12289, 12295, 24575, 24576, 24583, 3 * 12288 + 17, 5 * 12288})
      ASSERT_EQ(geom::crc32c(data.data() + offset, n), geom::crc32c_portable(data.data() + offset, n))
          << "offset " << offset << " length " << n;
  const std::vector<unsigned char> zeros(40000, 0);
  EXPECT_EQ(geom::crc32c(zeros.data(), zeros.size()), geom::crc32c_portable(zeros.data(), zeros.size()));
}

// Chaining: the CRC of a concatenation continues from the CRC of its head.
TEST(Crc32c, ContinuesAcrossSplits) {
  const std::vector<unsigned char> data = random_bytes(1000, 9);
  const uint32_t whole = geom::crc32c(data.data(), data.size());
  for (size_t cut : {0, 1, 7, 8, 9, 63, 500, 999, 1000})
    EXPECT_EQ(geom::crc32c(data.data() + cut, data.size() - cut, geom::crc32c(data.data(), cut)), whole) << cut;
}

// write_baked gathers header, padding and the sections' own buffers into the
// file: the bytes equal serialize_baked's, the reader accepts them, and the
// CRCs it hands back are the ones the table holds.
TEST(WriteBaked, GatheredFileEqualsTheSerializedOne) {
  geom::Scene scene;
  scene.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0};  // a tetrahedron and a seam copy of vertex 1
  scene.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 4, 2, 3};
  geom::BakeResult r = geom::bake_scene(scene, "tet");
  ASSERT_TRUE(r.ok) << r.error;
  size_t viewed = 0;
  for (const auto& s : r.sections) viewed += s.view != nullptr;
  EXPECT_GE(viewed, 8u);  // the stage buffers are not copied into the sections
  std::vector<unsigned char> serialized;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(r.sections, serialized, error)) << error;
  const std::string path = ::testing::TempDir() + "gathered" + std::to_string(::getpid()) + ".gbake";
  std::vector<uint32_t> crcs;
  ASSERT_TRUE(geom::write_baked(path, r.sections, error, &crcs)) << error;
  const std::vector<unsigned char> written = read_file(path);
  std::remove(path.c_str());
  EXPECT_EQ(written, serialized);
  geom::baked::Reader rd;
  ASSERT_TRUE(rd.open(written.data(), written.size())) << rd.error();
  ASSERT_EQ(crcs.size(), r.sections.size());
  for (size_t i = 0; i < crcs.size(); ++i) {
    EXPECT_EQ(crcs[i], rd.sections()[i].crc) << r.sections[i].name;
    EXPECT_EQ(crcs[i], geom::crc32c_portable(r.sections[i].data(), r.sections[i].size()));
  }
}

// More parts than one writev takes (1024 iovecs): the batches join up.
TEST(WriteBaked, ManyPartsInBatches) {
  std::vector<std::vector<unsigned char>> chunks;
  std::vector<geom::FilePart> parts;
  std::vector<unsigned char> expected;
  for (int i = 0; i < 2500; ++i) {
    chunks.push_back(random_bytes(size_t(i % 13), uint32_t(i)));
    expected.insert(expected.end(), chunks.back().begin(), chunks.back().end());
  }
  for (const auto& c : chunks) parts.push_back({c.data(), c.size()});
  const std::string path = ::testing::TempDir() + "parts" + std::to_string(::getpid());
  std::string error;
  ASSERT_TRUE(geom::write_file_atomically(path, parts.data(), parts.size(), error)) << error;
  EXPECT_EQ(read_file(path), expected);
  std::remove(path.c_str());
}
