// Tests of the baked container (geom/baked_reader.h, geom/baked_writer.h), the
// bake pipeline (geom/bake.h) and `geombake bake` / `geombake inspect`.
//
// Laws: what is written reads back as the same buffers, each equal to what its
// library stage makes; the reader refuses every truncation and every single
// flipped byte of a real baked file, and foreign files, with a clear message;
// bakes are byte-identical run after run and whatever the thread count; a
// failed bake leaves no file, and the other inputs of the run still get baked.
// clang-format off
#include "geom/baked_reader.h"  // first, so that it is seen to compile alone
// clang-format on

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cli/file.h"
#include "geom/adjacency.h"
#include "geom/atomic_file.h"
#include "geom/bake.h"
#include "geom/baked_file.h"
#include "geom/baked_reader.h"
#include "geom/baked_writer.h"
#include "geom/extrude.h"
#include "geom/face_planes.h"
#include "geom/focus.h"
#include "geom/pipeline.h"
#include "geom/report.h"
#include "geom/shadow_volume.h"
#include "geom/weld.h"

using geom::BakedSection;
using geom::baked::Format;
using geom::baked::Reader;
using geom::baked::SectionType;

namespace {

std::string temp_dir(const std::string& tag) {
  std::string d = std::string(GEOM_BINARY_DIR) + "/test_baked_tmp/" + tag;
  std::string cmd = "rm -rf '" + d + "' && mkdir -p '" + d + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return d;
}

std::vector<std::string> list_dir(const std::string& dir) {
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* e = readdir(d))
      if (std::strcmp(e->d_name, ".") && std::strcmp(e->d_name, "..")) names.push_back(e->d_name);
    closedir(d);
  }
  return names;
}

bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

// A few sections of every format, with awkward sizes (not multiples of the alignment).
std::vector<BakedSection> sample_sections(std::mt19937& rng, int n) {
  std::vector<BakedSection> out;
  std::uniform_int_distribution<int> len(0, 70);
  for (int i = 0; i < n; ++i) {
    int kind = i % 4;
    if (kind == 0) {
      std::vector<float> v(3 * size_t(len(rng)));
      for (float& x : v) x = std::uniform_real_distribution<float>(-1e6f, 1e6f)(rng);
      out.push_back(geom::make_baked_section(SectionType::Positions, Format::F32x3, 12, "pos" + std::to_string(i), v));
    } else if (kind == 1) {
      std::vector<uint32_t> v(size_t(len(rng)));
      for (uint32_t& x : v) x = rng();
      out.push_back(geom::make_baked_section(SectionType::Indices, Format::U32, 4, "idx" + std::to_string(i), v, i));
    } else if (kind == 2) {
      std::string text = "{\"n\": " + std::to_string(rng() % 1000) + "}";
      std::vector<char> v(text.begin(), text.end());
      out.push_back(geom::make_baked_section(SectionType::TopologyReport, Format::Utf8, 1, "json", v));
    } else {
      std::vector<uint32_t> v(7 * size_t(len(rng)));
      for (uint32_t& x : v) x = rng();
      out.push_back(geom::make_baked_section(SectionType::EsmQuads, Format::Record, 28, "rec", v));
    }
  }
  return out;
}

void expect_same(const std::vector<BakedSection>& written, const Reader& r) {
  ASSERT_EQ(r.sections().size(), written.size());
  for (size_t i = 0; i < written.size(); ++i) {
    const auto& w = written[i];
    const auto& s = r.sections()[i];
    EXPECT_EQ(s.type, w.type);
    EXPECT_EQ(s.format, w.format);
    EXPECT_EQ(s.stride, w.stride);
    EXPECT_EQ(s.item, w.item);
    EXPECT_EQ(s.count, w.count);
    EXPECT_EQ(std::string(s.name), w.name);
    ASSERT_EQ(s.size, w.size());
    EXPECT_EQ(s.offset % r.alignment(), 0u);
    EXPECT_TRUE(w.size() == 0 || std::memcmp(s.data, w.data(), w.size()) == 0);
  }
}

}  // namespace

TEST(Crc32c, KnownValues) {
  // RFC 3720 (iSCSI) B.4 test vectors and the common check value.
  EXPECT_EQ(geom::baked::crc32c("123456789", 9), 0xE3069283u);
  std::vector<unsigned char> zeros(32, 0), ones(32, 0xff), inc(32), dec(32);
  for (int i = 0; i < 32; ++i) inc[i] = uint8_t(i), dec[i] = uint8_t(31 - i);
  EXPECT_EQ(geom::baked::crc32c(zeros.data(), 32), 0x8A9136AAu);
  EXPECT_EQ(geom::baked::crc32c(ones.data(), 32), 0x62A8AB43u);
  EXPECT_EQ(geom::baked::crc32c(inc.data(), 32), 0x46DD794Eu);
  EXPECT_EQ(geom::baked::crc32c(dec.data(), 32), 0x113FDB5Cu);
  EXPECT_EQ(geom::baked::crc32c(nullptr, 0), 0u);
}

TEST(Crc32c, IncrementalEqualsWhole) {
  std::mt19937 rng(7);
  std::vector<unsigned char> data(1000);
  for (auto& b : data) b = uint8_t(rng());
  uint32_t whole = geom::baked::crc32c(data.data(), data.size());
  for (size_t cut = 0; cut <= data.size(); cut += 37) {
    uint32_t c = geom::baked::crc32c(data.data(), cut);
    EXPECT_EQ(geom::baked::crc32c(data.data() + cut, data.size() - cut, c), whole) << cut;
  }
}

TEST(BakedContainer, RoundTripRandomSections) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    auto sections = sample_sections(rng, trial % 9);
    std::vector<unsigned char> bytes;
    std::string error;
    uint32_t alignment = 16u << (trial % 4);
    ASSERT_TRUE(geom::serialize_baked(sections, bytes, error, alignment)) << error;
    Reader r;
    ASSERT_TRUE(r.open(bytes.data(), bytes.size())) << r.error();
    EXPECT_EQ(r.alignment(), alignment);
    EXPECT_EQ(r.file_size(), bytes.size());
    expect_same(sections, r);
    // The layout is a pure function of the sections.
    std::vector<unsigned char> again;
    ASSERT_TRUE(geom::serialize_baked(sections, again, error, alignment));
    EXPECT_EQ(again, bytes);
  }
}

//   An empty container: header only, no section.
TEST(BakedContainer, EmptyContainer) {
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked({}, bytes, error)) << error;
  EXPECT_EQ(bytes.size(), geom::baked::kHeaderSize);
  Reader r;
  ASSERT_TRUE(r.open(bytes.data(), bytes.size())) << r.error();
  EXPECT_TRUE(r.sections().empty());
  EXPECT_EQ(r.find(SectionType::Positions), nullptr);
}

TEST(BakedContainer, ZeroCopyTypedView) {
  std::vector<float> xyz = {0, 1, 2, 3, 4, 5};
  std::vector<BakedSection> s = {geom::make_baked_section(SectionType::Positions, Format::F32x3, 12, "p", xyz)};
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(s, bytes, error));
  Reader r;
  ASSERT_TRUE(r.open(bytes.data(), bytes.size()));
  const auto* p = r.find(SectionType::Positions);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->data, bytes.data() + p->offset);  // a view, not a copy
  struct P3 {
    float x, y, z;
  };
  const P3* v = p->as<P3>();
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v[1].y, 4.0f);
  EXPECT_EQ(p->as<uint32_t>(), nullptr);  // wrong size for the stride
}

TEST(BakedContainer, WriterRefusesInconsistentSections) {
  std::vector<unsigned char> bytes;
  std::string error;
  BakedSection s;
  s.type = SectionType::Indices;
  s.format = Format::U32;
  s.stride = 4;
  s.count = 2;
  s.bytes.resize(4);  // should be 8
  s.name = "idx";
  EXPECT_FALSE(geom::serialize_baked({s}, bytes, error));
  EXPECT_NE(error.find("count 2"), std::string::npos) << error;
  s.bytes.resize(8);
  s.stride = 8;  // not the stride of u32
  EXPECT_FALSE(geom::serialize_baked({s}, bytes, error));
  s.stride = 4;
  s.name = "a_name_that_is_too_long";
  EXPECT_FALSE(geom::serialize_baked({s}, bytes, error));
  EXPECT_NE(error.find("name"), std::string::npos) << error;
  s.name = "tab\there";
  EXPECT_FALSE(geom::serialize_baked({s}, bytes, error));
  s.name = "ok";
  EXPECT_FALSE(geom::serialize_baked({s}, bytes, error, 24));  // alignment not a power of two
  EXPECT_FALSE(geom::serialize_baked({s}, bytes, error, 8));   // under 16
  EXPECT_TRUE(geom::serialize_baked({s}, bytes, error)) << error;
}

// Every truncation and every single flipped byte of a container is refused;
// flipping a byte back makes it valid again (the test is not vacuous).
TEST(BakedContainer, RefusesEveryTruncationAndFlippedByte) {
  std::mt19937 rng(3);
  auto sections = sample_sections(rng, 6);
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(sections, bytes, error)) << error;
  Reader r;
  ASSERT_TRUE(r.open(bytes.data(), bytes.size()));
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::vector<unsigned char> cut(bytes.begin(), bytes.begin() + n);
    ASSERT_FALSE(r.open(cut.data(), cut.size())) << "truncated to " << n;
    EXPECT_FALSE(r.error().empty());
  }
  std::vector<unsigned char> longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(r.open(longer.data(), longer.size()));
  EXPECT_NE(r.error().find("after the end"), std::string::npos) << r.error();
  for (size_t i = 0; i < bytes.size(); ++i) {
    for (unsigned char mask : {0x01, 0x80, 0xff}) {
      bytes[i] ^= mask;
      ASSERT_FALSE(r.open(bytes.data(), bytes.size())) << "byte " << i << " ^ " << int(mask);
      bytes[i] ^= mask;
    }
  }
  EXPECT_TRUE(r.open(bytes.data(), bytes.size())) << r.error();
}

TEST(BakedContainer, ClearErrors) {
  std::vector<float> xyz(30, 1.0f);
  std::vector<BakedSection> s = {geom::make_baked_section(SectionType::Positions, Format::F32x3, 12, "positions", xyz)};
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(s, bytes, error));
  Reader r;
  auto refused = [&](std::vector<unsigned char> b, const char* words) {
    EXPECT_FALSE(r.open(b.data(), b.size()));
    EXPECT_NE(r.error().find(words), std::string::npos) << "'" << r.error() << "' lacks '" << words << "'";
  };
  refused({}, "empty");
  refused(std::vector<unsigned char>(bytes.begin(), bytes.begin() + 20), "truncated");
  refused(std::vector<unsigned char>(bytes.begin(), bytes.end() - 1), "truncated");
  std::string gltf = "{\"asset\":{\"version\":\"2.0\"}}";
  refused(std::vector<unsigned char>(gltf.begin(), gltf.end()), "not a geombake baked file");
  ASSERT_EQ(bytes.size(), 128u + 120u);  // header, one entry, 10 positions
  auto b = bytes;
  b[200] ^= 1;
  refused(b, "section 0 'positions': checksum mismatch");
  b = bytes;
  b[60] ^= 1;
  refused(b, "header checksum");
  b = bytes;
  b[12] = 3;  // major version 3: newer than this reader's
  refused(b, "unsupported version 3.0: the file is newer than this reader's version 2.0");
  b = bytes;
  b[12] = 1, b[14] = 7;  // version 1.7: older (the format before the light records and the caster hull)
  refused(b, "unsupported version 1.7: the file is older than this reader's version 2.0");
  b = bytes;
  b[12] = 0;
  refused(b, "unsupported version 0.0: the file is older");
  b = bytes;
  std::swap(b[8], b[11]);
  std::swap(b[9], b[10]);
  refused(b, "big-endian");
}

// A corrupt table whose checksum was recomputed (as a hostile writer would):
// the structural checks still refuse it, each with its own message.
TEST(BakedContainer, StructuralChecksBehindAValidChecksum) {
  std::vector<uint32_t> idx = {0, 1, 2, 2, 1, 3};
  std::vector<float> xyz(12, 0.5f);
  std::vector<BakedSection> s = {geom::make_baked_section(SectionType::Positions, Format::F32x3, 12, "positions", xyz),
                                 geom::make_baked_section(SectionType::Indices, Format::U32, 4, "indices", idx)};
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(s, bytes, error));
  auto reseal = [](std::vector<unsigned char>& b) {
    uint32_t n = std::min<uint32_t>(geom::baked::detail::load_u32(b.data() + 24), uint32_t((b.size() - 64) / 64));
    uint32_t crc = geom::baked::crc32c(b.data(), 60);
    crc = geom::baked::crc32c(b.data() + 64, size_t(n) * 64, crc);
    for (int i = 0; i < 4; ++i) b[60 + i] = uint8_t(crc >> (8 * i));
  };
  auto put64 = [](std::vector<unsigned char>& b, size_t at, uint64_t v) {
    for (int i = 0; i < 8; ++i) b[at + i] = uint8_t(v >> (8 * i));
  };
  Reader r;
  auto refused = [&](std::vector<unsigned char> b, const char* words) {
    reseal(b);
    EXPECT_FALSE(r.open(b.data(), b.size()));
    EXPECT_NE(r.error().find(words), std::string::npos) << "'" << r.error() << "' lacks '" << words << "'";
  };
  const size_t e0 = 64, e1 = 128;
  uint64_t off1 = geom::baked::detail::load_u64(bytes.data() + e1 + 24);
  auto b = bytes;
  put64(b, e1 + 16, 7);  // count 7 x 4 != 24 bytes
  refused(b, "is not count 7 x stride 4");
  b = bytes;
  put64(b, e1 + 24, off1 + 4);  // misaligned
  refused(b, "not aligned");
  b = bytes;
  put64(b, e1 + 24, 128);  // inside the table
  refused(b, "overlaps");
  b = bytes;
  put64(b, e0 + 24, off1);  // section 0 moved onto section 1
  refused(b, "");
  b = bytes;
  put64(b, e1 + 16, uint64_t(1) << 62);  // count * stride overflows
  refused(b, "is not count");
  b = bytes;
  put64(b, e1 + 32, uint64_t(1) << 40);  // claims a terabyte
  put64(b, e1 + 16, uint64_t(1) << 38);
  refused(b, "beyond the end");
  b = bytes;
  b[e1 + 4] = 99;  // unknown format
  refused(b, "unknown element format 99");
  b = bytes;
  std::memset(b.data() + e1 + 48, 'x', 16);  // name without NUL
  refused(b, "not NUL-terminated");
  b = bytes;
  b[24] = 0xff;  // section count 255: table beyond the end
  b[25] = 0xff;
  refused(b, "");
  b = bytes;
  b[28] = 24;  // alignment 24
  refused(b, "alignment");
  b = bytes;
  b[size_t(off1) - 1] = 1;  // a padding byte
  refused(b, "padding");
}

TEST(BakedFileWrite, AtomicWriteAndReadBack) {
  std::string dir = temp_dir("atomic");
  std::mt19937 rng(5);
  auto sections = sample_sections(rng, 5);
  std::string path = dir + "/out.gbake", error;
  ASSERT_TRUE(geom::write_baked(path, sections, error)) << error;
  EXPECT_EQ(list_dir(dir), std::vector<std::string>{"out.gbake"});  // no temporary left
  geom::baked::File f;
  ASSERT_TRUE(f.load(path)) << f.error();
  expect_same(sections, f.reader());
  // Overwriting replaces the whole file.
  auto fewer = sample_sections(rng, 2);
  ASSERT_TRUE(geom::write_baked(path, fewer, error)) << error;
  ASSERT_TRUE(f.load(path)) << f.error();
  expect_same(fewer, f.reader());
  EXPECT_EQ(list_dir(dir).size(), 1u);
}

TEST(BakedFileWrite, FailedWriteLeavesNoFile) {
  std::string dir = temp_dir("failed");
  std::string error;
  std::vector<unsigned char> bytes(100, 1);
  EXPECT_FALSE(geom::write_file_atomically(dir + "/missing/sub/out.gbake", bytes.data(), bytes.size(), error));
  EXPECT_NE(error.find("cannot create"), std::string::npos) << error;
  // The destination is a directory: refused (never replaced), no temporary file left.
  ASSERT_EQ(::mkdir((dir + "/taken").c_str(), 0755), 0);
  EXPECT_FALSE(geom::write_file_atomically(dir + "/taken", bytes.data(), bytes.size(), error));
  EXPECT_NE(error.find("is a directory, not a regular file: not replaced"), std::string::npos) << error;
  EXPECT_EQ(list_dir(dir), std::vector<std::string>{"taken"});
  EXPECT_TRUE(list_dir(dir + "/taken").empty());
  // An inconsistent section: nothing is written.
  BakedSection s;
  s.count = 3;
  EXPECT_FALSE(geom::write_baked(dir + "/bad.gbake", {s}, error));
  EXPECT_FALSE(exists(dir + "/bad.gbake"));
  if (::geteuid() != 0) {  // root writes anywhere
    ASSERT_EQ(::mkdir((dir + "/ro").c_str(), 0555), 0);
    EXPECT_FALSE(geom::write_file_atomically(dir + "/ro/out.gbake", bytes.data(), bytes.size(), error));
    EXPECT_TRUE(list_dir(dir + "/ro").empty());
  }
  geom::baked::File f;
  EXPECT_FALSE(f.load(dir + "/nothing.gbake"));
  EXPECT_EQ(f.error(), dir + "/nothing.gbake: cannot open file");
  EXPECT_FALSE(f.load(dir));
  EXPECT_NE(f.error().find(dir + ": "), std::string::npos);
}

// ---- The bake pipeline (geom/bake.h) ---------------------------------------

namespace {

geom::Scene make_scene(std::vector<float> positions, std::vector<uint32_t> indices) {
  geom::Scene s;
  s.positions = std::move(positions);
  s.indices = std::move(indices);
  s.sources.resize(s.indices.size() / 3);
  s.files.push_back("test");
  return s;
}

// A tetrahedron whose faces do not share vertices (as UV seams leave it):
//
//        3
//       /|\          faces (outward, counter-clockwise seen from outside):
//      / | \           0 2 1, 0 1 3, 1 2 3, 2 0 3
//     /  |  \        12 source vertices, 4 after the weld, closed, genus 0
//    0---|---2
//     \  |  /
//      \ | /
//        1
geom::Scene seamed_tetrahedron() {
  const float c[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  std::vector<float> p;
  std::vector<uint32_t> idx;
  for (auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      idx.push_back(uint32_t(p.size() / 3));
      p.insert(p.end(), c[f[k]], c[f[k]] + 3);
    }
  return make_scene(p, idx);
}

// A random soup on a small lattice (so vertices repeat and weld), far from the
// origin when `offset` is large, with collapsed and duplicate triangles mixed in.
geom::Scene random_scene(std::mt19937& rng, float offset) {
  std::uniform_int_distribution<int> coord(0, 3), tris(0, 40);
  std::vector<float> p;
  std::vector<uint32_t> idx;
  int n = tris(rng);
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) {
      idx.push_back(uint32_t(p.size() / 3));
      for (int a = 0; a < 3; ++a) p.push_back(offset + 0.25f * float(coord(rng)));
    }
    if (rng() % 8 == 0) idx[idx.size() - 1] = idx[idx.size() - 2];                     // collapsed
    if (rng() % 8 == 0 && t > 0) idx.insert(idx.end(), idx.end() - 6, idx.end() - 3);  // duplicate
  }
  return make_scene(p, idx);
}

template <class T>
std::vector<T> values(const geom::baked::Section* s) {
  std::vector<T> v(s ? s->size / sizeof(T) : 0);
  if (s && s->size) std::memcpy(v.data(), s->data, s->size);
  return v;
}

// Equality of two arrays that reports the first difference, not a dump of both.
template <class T>
testing::AssertionResult same(const std::vector<T>& a, const std::vector<T>& b) {
  if (a == b) return testing::AssertionSuccess();
  size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  return testing::AssertionFailure() << "sizes " << a.size() << " and " << b.size() << ", first difference at " << i;
}

template <class T>
std::vector<unsigned char> bytes_of(const std::vector<T>& v) {
  const unsigned char* p = reinterpret_cast<const unsigned char*>(v.data());
  return std::vector<unsigned char>(p, p + v.size() * sizeof(T));
}

std::vector<unsigned char> bytes_of(const geom::baked::Section* s) {
  return s ? std::vector<unsigned char>(s->data, s->data + s->size) : std::vector<unsigned char>();
}

// Lights given as (x, y, z, w), as `--light` takes them.
std::vector<geom::Light> lights_of(const std::vector<std::array<double, 4>>& homogeneous) {
  std::vector<geom::Light> out;
  for (const auto& h : homogeneous) out.push_back(geom::light_from_homogeneous(h.data()));
  return out;
}

// Bakes `scene`, writes and reads back the container, and checks each section
// against the scene and against the library stage that makes it.
void check_baked(const geom::Scene& scene, const geom::BakeOptions& options, const std::string& name) {
  geom::BakeResult r = geom::bake_scene(scene, name, options);
  ASSERT_TRUE(r.ok) << r.error;
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(r.sections, bytes, error)) << error;
  Reader rd;
  ASSERT_TRUE(rd.open(bytes.data(), bytes.size())) << rd.error();
  expect_same(r.sections, rd);

  // The stages, run here on their own.
  const size_t tc = scene.triangle_count();
  const geom::PipelineOptions& po = options.pipeline;
  geom::WeldResult w = geom::weld(geom::positions_of(scene.positions.data(), scene.vertex_count()),
                                  scene.indices.data(), scene.indices.size(), po.weld_tolerance);
  const geom::PositionSpan welded = geom::positions_of(w.positions.data(), w.vertex_count());
  geom::Topology topo = geom::build_topology(welded, w.indices.data(), tc, {po.coplanar_degrees});
  std::vector<geom::Light> lights = options.scene_lights ? scene.lights : std::vector<geom::Light>();
  lights.insert(lights.end(), options.lights.begin(), options.lights.end());
  const bool silhouette = po.esm || po.volume || po.adjacency || !lights.empty();

  const auto* pos = rd.find(SectionType::Positions);
  const auto* idx = rd.find(SectionType::Indices);
  const auto* remap = rd.find(SectionType::WeldRemap);
  const auto* planes = rd.find(SectionType::FacePlanes);
  const auto* topology = rd.find(SectionType::TopologyReport);
  EXPECT_EQ(pos != nullptr, options.positions);
  EXPECT_EQ(idx != nullptr, options.indices);
  EXPECT_EQ(remap != nullptr, options.weld_remap);
  EXPECT_EQ(planes != nullptr, po.face_planes);
  EXPECT_EQ(topology != nullptr, options.topology_report);
  EXPECT_EQ(rd.find(SectionType::Frame) != nullptr, po.esm || po.volume || !lights.empty());
  EXPECT_EQ(rd.find(SectionType::SilhouetteReport) != nullptr, silhouette);
  EXPECT_EQ(rd.find(SectionType::EsmQuads) != nullptr, po.esm);
  EXPECT_EQ(rd.find(SectionType::EsmPlanes) != nullptr, po.esm);
  EXPECT_EQ(rd.find(SectionType::VolumeSides) != nullptr, po.volume);
  EXPECT_EQ(rd.find(SectionType::VolumeCaps) != nullptr, po.volume);
  EXPECT_EQ(rd.find(SectionType::VolumePlanes) != nullptr, po.volume);
  EXPECT_EQ(rd.find(SectionType::AdjacencyIndices) != nullptr, po.adjacency);
  EXPECT_EQ(rd.find(SectionType::Lights) != nullptr, !lights.empty());
  EXPECT_EQ(rd.find(SectionType::LightParams) != nullptr, !lights.empty());
  EXPECT_EQ(rd.find(SectionType::LightNames) != nullptr, !lights.empty());
  EXPECT_EQ(rd.find(SectionType::CasterHull) != nullptr, options.caster_hull != nullptr);
  if (const auto* hull = rd.find(SectionType::CasterHull)) {
    // The hull of the welded positions, as the focus computes it: every
    // position inside every plane (within float rounding), unit normals.
    std::vector<double> expected;
    geom::focus_caster_hull(welded, expected);
    EXPECT_EQ(hull->format, Format::F64x4);
    EXPECT_TRUE(same(values<double>(hull), expected));
    for (size_t i = 0; i + 3 < expected.size(); i += 4) {
      EXPECT_NEAR(std::hypot(expected[i], expected[i + 1], expected[i + 2]), 1.0, 1e-9);
      for (size_t v = 0; v < w.vertex_count(); ++v) {
        const float* q = &w.positions[3 * v];
        const double scale = 1 + std::fabs(q[0]) + std::fabs(q[1]) + std::fabs(q[2]);
        EXPECT_GE(expected[i] * q[0] + expected[i + 1] * q[1] + expected[i + 2] * q[2] + expected[i + 3], -1e-9 * scale)
            << "position " << v << " outside hull plane " << i / 4;
      }
    }
  }
  if (const auto* params = rd.find(SectionType::LightParams)) {
    // Each light whole, its name in light_names, fields of other types zero.
    ASSERT_EQ(params->count, lights.size());
    ASSERT_EQ(params->stride, sizeof(geom::LightRecord));
    const auto* names = rd.find(SectionType::LightNames);
    ASSERT_NE(names, nullptr);
    std::string all_names;
    for (size_t i = 0; i < lights.size(); ++i) {
      geom::LightRecord l;
      std::memcpy(&l, params->data + i * sizeof l, sizeof l);
      const geom::Light& e = lights[i];
      const size_t from_scene = lights.size() - options.lights.size();
      const std::string name =
          i >= from_scene && e.name.empty() ? "--light " + std::to_string(i - from_scene + 1) : e.name;
      EXPECT_EQ(l.name_offset, all_names.size()) << "light " << i;
      EXPECT_EQ(std::string(reinterpret_cast<const char*>(names->data) + l.name_offset, l.name_size), name);
      all_names += name;
      EXPECT_EQ(l.type, uint32_t(e.type));
      EXPECT_EQ(l.reserved, 0u);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(l.position[k], e.type == geom::LightType::Directional ? 0 : e.position[k]);
        EXPECT_EQ(l.direction[k], e.type == geom::LightType::Point ? 0 : e.direction[k]);
        EXPECT_EQ(l.color[k], double(e.color[k]));
      }
      EXPECT_EQ(l.range, e.type == geom::LightType::Directional ? 0 : e.range);
      EXPECT_EQ(l.inner_cone_angle, e.type == geom::LightType::Spot ? e.inner_cone : 0);
      EXPECT_EQ(l.outer_cone_angle, e.type == geom::LightType::Spot ? e.outer_cone : 0);
      EXPECT_EQ(l.intensity, double(e.intensity));
    }
    EXPECT_EQ(names->size, all_names.size());
  }
  if (pos) {
    EXPECT_EQ(pos->format, Format::F32x3);
    EXPECT_TRUE(same(values<float>(pos), w.positions));
  }
  if (idx) {
    EXPECT_EQ(idx->count, 3 * tc);
    EXPECT_TRUE(same(values<uint32_t>(idx), w.indices));
  }
  if (remap) {
    auto m = values<uint32_t>(remap);
    ASSERT_EQ(m.size(), scene.vertex_count());
    for (size_t v = 0; v < m.size(); ++v) {  // every source vertex lands on a welded vertex at its position
      ASSERT_LT(m[v], w.vertex_count());
      if (po.weld_tolerance == 0)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(w.positions[3 * m[v] + k], scene.positions[3 * v + k]);
    }
    for (size_t i = 0; i < scene.indices.size(); ++i) EXPECT_EQ(m[scene.indices[i]], w.indices[i]);
  }
  geom::FacePlanes fp =
      geom::compute_face_planes(welded, w.indices.data(), tc, topo, {po.coplanar_degrees, po.coplanar_distance});
  if (planes) {
    // Each face's stored plane, moved to input coordinates: unit normal by the
    // right-hand rule, the face's vertices on it (within the coplanar grouping's
    // tolerance, relative to the bounds diagonal, plus float rounding).
    auto pl = values<float>(planes);
    ASSERT_EQ(pl.size(), 4 * tc);
    for (size_t t = 0; t < tc; ++t) {
      const float* n = &pl[4 * t];
      double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
      if (fp.face_plane[t] == geom::FacePlanes::kNone) {
        EXPECT_EQ(len, 0.0) << "degenerate triangle " << t;
        EXPECT_EQ(n[3], 0.0f);
        continue;
      }
      const float* a = &w.positions[3 * size_t(w.indices[3 * t])];
      const float* b = &w.positions[3 * size_t(w.indices[3 * t + 1])];
      const float* c = &w.positions[3 * size_t(w.indices[3 * t + 2])];
      double u[3], v[3];
      for (int k = 0; k < 3; ++k) u[k] = double(b[k]) - a[k], v[k] = double(c[k]) - a[k];
      double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      EXPECT_NEAR(len, 1.0, 1e-6) << "triangle " << t;
      EXPECT_GT(cr[0] * n[0] + cr[1] * n[1] + cr[2] * n[2], 0.0) << "right-hand rule, triangle " << t;
      double scale = 1.0 + std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]);
      double tolerance = 2 * po.coplanar_distance * fp.diagonal + 1e-6 * scale;
      for (const float* q : {a, b, c})
        EXPECT_NEAR(double(n[0]) * q[0] + double(n[1]) * q[1] + double(n[2]) * q[2] + n[3], 0.0, tolerance)
            << "vertex on the plane, triangle " << t;
    }
  }
  if (topology) {
    geom::Report expected;
    expected.file = name;
    geom::analyze(scene, po, expected);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(topology->data), topology->size), geom::report_json(expected));
  }
  if (!silhouette) return;
  if (rd.find(SectionType::Frame))
    EXPECT_TRUE(same(values<double>(rd.find(SectionType::Frame)), std::vector<double>(fp.origin, fp.origin + 3)));
  const auto* report = rd.find(SectionType::SilhouetteReport);
  ASSERT_NE(report, nullptr);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(report->data), report->size), r.silhouette);
  if (po.esm) {
    geom::EsmQuads esm = geom::build_esm_quads(welded, w.indices.data(), tc, topo, fp, po.esm_options);
    EXPECT_EQ(rd.find(SectionType::EsmQuads)->stride, 36u);
    EXPECT_TRUE(same(bytes_of(rd.find(SectionType::EsmQuads)), bytes_of(esm.quads)));
    EXPECT_TRUE(same(bytes_of(rd.find(SectionType::EsmPlanes)), bytes_of(esm.planes)));
  }
  geom::ShadowVolume volume = geom::build_shadow_volume(welded, w.indices.data(), tc, topo, fp, po.volume_options);
  if (po.volume) {
    EXPECT_EQ(rd.find(SectionType::VolumeSides)->stride, 32u);
    EXPECT_EQ(rd.find(SectionType::VolumeCaps)->stride, 40u);
    EXPECT_TRUE(same(bytes_of(rd.find(SectionType::VolumeSides)), bytes_of(volume.sides)));
    EXPECT_TRUE(same(bytes_of(rd.find(SectionType::VolumeCaps)), bytes_of(volume.caps)));
    EXPECT_TRUE(same(bytes_of(rd.find(SectionType::VolumePlanes)), bytes_of(volume.planes)));
  }
  if (po.adjacency) {
    std::vector<uint32_t> adj(geom::adjacency_index_count(tc));
    ASSERT_TRUE(geom::build_adjacency(adj.data(), w.indices.data(), tc, w.vertex_count()));
    EXPECT_TRUE(same(values<uint32_t>(rd.find(SectionType::AdjacencyIndices)), adj));
  }
  if (!lights.empty()) {
    auto table = values<double>(rd.find(SectionType::Lights));
    ASSERT_EQ(table.size(), 4 * lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
      double h[4];
      geom::light_homogeneous(lights[i], h);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(table[4 * i + k], h[k]);
      float local[4];
      geom::to_local_light(fp.origin, h, local);
      geom::ShadowVolume lv = geom::build_light_volume(volume, local);
      EXPECT_TRUE(same(bytes_of(rd.find(SectionType::LightSides, uint32_t(i))), bytes_of(lv.sides))) << "light " << i;
      EXPECT_TRUE(same(bytes_of(rd.find(SectionType::LightCaps, uint32_t(i))), bytes_of(lv.caps))) << "light " << i;
      EXPECT_TRUE(same(bytes_of(rd.find(SectionType::LightPlanes, uint32_t(i))), bytes_of(lv.planes))) << "light " << i;
    }
    EXPECT_EQ(rd.find(SectionType::LightSides, uint32_t(lights.size())), nullptr);
  }
}

}  // namespace

TEST(Bake, SeamedTetrahedron) {
  geom::Scene s = seamed_tetrahedron();
  check_baked(s, {}, "tetra");
  geom::BakeResult r = geom::bake_scene(s, "tetra");
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.report.stats.vertices, 4u);
  EXPECT_TRUE(r.report.stats.closed);
  EXPECT_EQ(r.report.stats.euler_characteristic, 2);
  std::vector<std::string> names;
  for (const auto& sec : r.sections) names.push_back(sec.name);
  EXPECT_EQ(names, (std::vector<std::string>{"positions", "indices", "weld_remap", "face_planes", "topology", "frame",
                                             "esm_quads", "esm_planes", "volume_sides", "volume_caps", "volume_planes",
                                             "adjacency", "silhouette"}));
  ASSERT_EQ(r.sections.size(), 13u);
  EXPECT_EQ(r.sections[0].count, 4u);   // welded positions
  EXPECT_EQ(r.sections[1].count, 12u);  // indices
  EXPECT_EQ(r.sections[2].count, 12u);  // remap
  // Face 0 (0 2 1) lies in z = 0 and faces -z.
  std::vector<float> plane(4);
  std::memcpy(plane.data(), r.sections[3].data(), 16);
  EXPECT_EQ(plane, (std::vector<float>{0, 0, -1, 0}));
  EXPECT_EQ(r.sections[11].count, 24u);  // 6 adjacency indices per triangle
}

TEST(Bake, EmptyScene) {
  geom::Scene s = make_scene({}, {});
  check_baked(s, {}, "empty");
}

TEST(Bake, EveryFlagCombination) {
  geom::Scene s = seamed_tetrahedron();
  s.lights.resize(1);  // a point light above the tetrahedron
  s.lights[0].position[2] = 3;
  for (int mask = 0; mask < 512; ++mask) {
    geom::BakeOptions o;
    o.positions = mask & 1;
    o.indices = mask & 2;
    o.weld_remap = mask & 4;
    o.pipeline.face_planes = mask & 8;
    o.topology_report = mask & 16;
    o.pipeline.esm = mask & 32;
    o.pipeline.volume = mask & 64;
    o.pipeline.adjacency = mask & 128;
    o.scene_lights = mask & 256;
    if (mask % 3 == 0) o.caster_hull = geom::focus_caster_hull;
    check_baked(s, o, "tetra");
    if (HasFatalFailure()) return;
  }
}

TEST(Bake, LightsGiven) {
  geom::Scene s = seamed_tetrahedron();
  geom::BakeOptions o;
  o.lights = lights_of({{2, 3, 4, 1}, {0, 0, 1, 0}, {-1, -1, -1, 1}});
  check_baked(s, o, "tetra");
  geom::BakeResult r = geom::bake_scene(s, "tetra", o);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_NE(r.silhouette.find("\"name\":\"--light 3\""), std::string::npos) << r.silhouette;
  o.lights = lights_of({{0, 0, 0, 0}});
  r = geom::bake_scene(s, "tetra", o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error, "tetra: light '--light 1' is not a usable (x, y, z, w): non-finite or all zero");
  EXPECT_EQ(r.code, geom::ErrorCode::NonFinite);
  o.lights = lights_of({{1, std::nan(""), 0, 1}});
  r = geom::bake_scene(s, "tetra", o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.code, geom::ErrorCode::NonFinite);
  // bake_file: the import's refusal with its code, an unwritable output as Io.
  r = geom::bake_file("/nonexistent/mesh.obj", "/nonexistent/out.gbake");
  EXPECT_EQ(r.code, geom::ErrorCode::Io) << r.error;
}

// Scene lights of every type with random parameters (KHR_lights_punctual's
// fields, names with UTF-8 and empty ones) beside `--light` ones: the
// light_params and light_names sections hold each whole.
TEST(Bake, LightsKeptWhole) {
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> u(-10, 10), a(0, 1.5);
  const std::vector<std::string> names = {"sun", "", "lampe \xc3\xa0 p\xc3\xa9trole", "spot.001", ""};
  for (int trial = 0; trial < 40; ++trial) {
    geom::Scene s = seamed_tetrahedron();
    for (int i = 0; i < 1 + trial % 5; ++i) {
      geom::Light l;
      l.type = geom::LightType(rng() % 3);
      l.name = names[size_t(rng() % names.size())];
      for (int k = 0; k < 3; ++k) l.position[k] = u(rng), l.direction[k] = u(rng), l.color[k] = float(a(rng));
      l.position[2] = 20 + std::fabs(l.position[2]);  // off the tetrahedron
      l.range = rng() % 2 ? 0 : 5 + std::fabs(u(rng));
      l.inner_cone = 0.5 * a(rng), l.outer_cone = l.inner_cone + 0.1;
      l.intensity = float(100 * a(rng));
      s.lights.push_back(l);
    }
    geom::BakeOptions o;
    o.lights = lights_of({{1, 2, 30, 1}});
    o.caster_hull = trial % 2 ? geom::focus_caster_hull : nullptr;
    check_baked(s, o, "lights " + std::to_string(trial));
    if (HasFatalFailure()) return;
  }
}

TEST(Bake, RandomScenesRoundTrip) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 150; ++trial) {
    float offset = trial % 3 == 0 ? 0.0f : trial % 3 == 1 ? 1000.0f : -65536.0f;
    geom::Scene s = random_scene(rng, offset);
    geom::BakeOptions o;
    if (trial % 5 == 0) o.pipeline.weld_tolerance = 0.3f;
    if (trial % 2 == 0) o.caster_hull = geom::focus_caster_hull;
    check_baked(s, o, "random " + std::to_string(trial));
    if (HasFatalFailure()) return;
  }
}

// Byte-identical bakes, run after run and from several threads at once.
TEST(Bake, Deterministic) {
  std::mt19937 rng(13);
  std::vector<geom::Scene> scenes;
  for (int i = 0; i < 8; ++i) scenes.push_back(random_scene(rng, 10.0f * i));
  scenes.push_back(seamed_tetrahedron());
  auto bake_bytes = [](const geom::Scene& s) {
    std::vector<unsigned char> bytes;
    std::string error;
    geom::BakeResult r = geom::bake_scene(s, "same name");
    EXPECT_TRUE(r.ok && geom::serialize_baked(r.sections, bytes, error)) << r.error << error;
    return bytes;
  };
  std::vector<std::vector<unsigned char>> first(scenes.size());
  for (size_t i = 0; i < scenes.size(); ++i) first[i] = bake_bytes(scenes[i]);
  std::vector<std::vector<unsigned char>> threaded(scenes.size());
  std::vector<std::thread> pool;
  for (size_t i = 0; i < scenes.size(); ++i) pool.emplace_back([&, i] { threaded[i] = bake_bytes(scenes[i]); });
  for (auto& t : pool) t.join();
  for (size_t i = 0; i < scenes.size(); ++i) {
    EXPECT_TRUE(bake_bytes(scenes[i]) == first[i]) << i;
    EXPECT_TRUE(threaded[i] == first[i]) << i;
  }
}

// The bake that frees the scene's triangles once welded (geombake's) gives the
// same bytes as the one that leaves the scene alone, for every flag set and
// with lights; the scene keeps its lights, warnings and counts.
TEST(Bake, MovedSceneBakesTheSame) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 40; ++trial) {
    geom::Scene s = trial == 0 ? seamed_tetrahedron() : random_scene(rng, trial % 2 ? 0.0f : 300.0f);
    s.lights.resize(trial % 3);
    for (size_t i = 0; i < s.lights.size(); ++i) s.lights[i].position[1] = 2.0 + double(i);
    s.warnings = {"a warning"};
    s.source_counts = {{"polygon.faces", 3}};
    geom::BakeOptions o;
    o.pipeline.esm = trial % 2;
    o.pipeline.adjacency = trial % 5 != 1;
    o.pipeline.volume = trial % 4 != 2;
    o.lights = lights_of({{1, 2, 3, 1}});
    if (trial % 7 == 3) o.pipeline.weld_tolerance = 0.3f;
    const geom::BakeResult kept = geom::bake_scene(s, "scene", o);
    geom::Scene moved = s;
    const geom::BakeResult freed = geom::bake_scene(std::move(moved), "scene", o);
    ASSERT_TRUE(kept.ok && freed.ok) << kept.error << freed.error;
    std::vector<unsigned char> a, b;
    std::string error;
    ASSERT_TRUE(geom::serialize_baked(kept.sections, a, error) && geom::serialize_baked(freed.sections, b, error));
    EXPECT_TRUE(same(a, b)) << "trial " << trial;
    EXPECT_EQ(geom::report_json(kept.report), geom::report_json(freed.report));
    EXPECT_EQ(kept.silhouette, freed.silhouette);
    EXPECT_TRUE(moved.positions.empty() && moved.indices.empty() && moved.sources.empty()) << "trial " << trial;
    EXPECT_EQ(moved.lights.size(), s.lights.size());
    EXPECT_EQ(moved.warnings, s.warnings);
    EXPECT_EQ(moved.source_counts, s.source_counts);
  }
}

// ---- Real files, and the geombake CLI ---------------------------------------

namespace {

const std::string kBoxObj = "/usr/share/assimp/models/OBJ/box.obj";
const std::string kDracoBox = std::string(GEOM_TEST_DATA) + "/draco/Box/glTF/Box.gltf";

std::vector<unsigned char> read_bytes(const std::string& path) {
  std::vector<unsigned char> bytes;
  std::string error;
  EXPECT_TRUE(cli::read_file(path, bytes, error)) << path << ": " << error;
  return bytes;
}

void write_text(const std::string& path, const std::string& text) {
  FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr) << path;
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

struct CliRun {
  int status = -1;
  std::string out, err;
};

// Runs geombake with `args` (already shell-quoted), capturing stdout and stderr.
CliRun geombake(const std::string& dir, const std::string& args) {
  CliRun r;
  std::string out = dir + "/stdout.txt", err = dir + "/stderr.txt";
  int rc = std::system((std::string(GEOMBAKE_EXE) + " " + args + " >'" + out + "' 2>'" + err + "'").c_str());
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  auto slurp = [](const std::string& p) {
    std::vector<unsigned char> b;
    std::string e;
    cli::read_file(p, b, e);
    ::unlink(p.c_str());
    return std::string(b.begin(), b.end());
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// The tetrahedron of seamed_tetrahedron() as OBJ text, moved by `dx`.
std::string tetra_obj(float dx) {
  std::string s;
  const float c[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto& v : c)
    s += "v " + std::to_string(v[0] + dx) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  return s + "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
}

}  // namespace

// A real file, baked through the library: it reads back as the buffers of its
// scene, and every truncation and every flipped byte of it is refused.
TEST(BakeRealFile, BoxObjRoundTripTruncationsAndFlips) {
  std::string dir = temp_dir("real");
  std::string out = dir + "/box.gbake";
  geom::BakeResult r = geom::bake_file(kBoxObj, out);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.report.stats.triangles, 12u);
  EXPECT_EQ(r.report.stats.vertices, 8u);
  EXPECT_TRUE(r.report.stats.closed);
  geom::ImportResult imported = geom::import_file(kBoxObj);
  ASSERT_TRUE(imported.ok) << imported.error;
  check_baked(imported.scene, {}, kBoxObj);

  std::vector<unsigned char> bytes = read_bytes(out);
  Reader rd;
  ASSERT_TRUE(rd.open(bytes.data(), bytes.size())) << rd.error();
  expect_same(r.sections, rd);
  for (size_t n = 0; n < bytes.size(); ++n)
    ASSERT_FALSE(rd.open(bytes.data(), n)) << "truncated to " << n;  // a prefix of the same buffer
  for (size_t i = 0; i < bytes.size(); ++i)
    for (unsigned char mask : {0x01, 0x10, 0x80}) {
      bytes[i] ^= mask;
      ASSERT_FALSE(rd.open(bytes.data(), bytes.size())) << "byte " << i << " ^ " << int(mask);
      EXPECT_FALSE(rd.error().empty());
      bytes[i] ^= mask;
    }
  ASSERT_TRUE(rd.open(bytes.data(), bytes.size())) << rd.error();
}

TEST(BakeRealFile, DracoBoxGltf) {
  std::string dir = temp_dir("draco");
  geom::BakeResult r = geom::bake_file(kDracoBox, dir + "/Box.gbake");
  ASSERT_TRUE(r.ok) << r.error;
  geom::ImportResult imported = geom::import_file(kDracoBox);
  ASSERT_TRUE(imported.ok) << imported.error;
  EXPECT_EQ(r.report.stats.triangles, 12u);
  check_baked(imported.scene, {}, kDracoBox);
  geom::baked::File f;
  ASSERT_TRUE(f.load(dir + "/Box.gbake")) << f.error();
  EXPECT_EQ(f.reader().find(SectionType::Indices)->count, 36u);
}

// The library's bake_file and `geombake bake` of one input write the same
// bytes: both store the input's base name (no path of the machine), and the
// importer's warnings with it; a name the caller gives is stored instead.
TEST(BakeRealFile, LibraryBakeIsTheCliBake) {
  const std::string dir = temp_dir("libcli");
  write_text(dir + "/warned.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nl 1 2\nf 1 2 3\nf 1 3 4\n");  // a line: a warning
  const std::vector<std::string> inputs = {
      kBoxObj, kDracoBox, std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf", dir + "/warned.obj"};
  for (size_t i = 0; i < inputs.size(); ++i) {
    SCOPED_TRACE(inputs[i]);
    const std::string lib = dir + "/lib" + std::to_string(i) + ".gbake",
                      cli = dir + "/cli" + std::to_string(i) + ".gbake";
    geom::BakeOptions as_cli;  // geombake bake's defaults: the caster hull by geom::focus
    as_cli.caster_hull = geom::focus_caster_hull;
    const geom::BakeResult r = geom::bake_file(inputs[i], lib, as_cli);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.report.file, geom::stored_name(inputs[i]));
    const CliRun run = geombake(dir, "bake -q '" + inputs[i] + "' -o '" + cli + "'");
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(read_bytes(lib), read_bytes(cli));
  }
  const std::string named = dir + "/named.gbake";
  const geom::BakeResult r = geom::bake_file(kBoxObj, named, {}, {}, "asset/box.obj");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.report.file, "asset/box.obj");
  EXPECT_EQ(geom::stored_name("/a/b/pig.off"), "pig.off");
  EXPECT_EQ(geom::stored_name("pig.off"), "pig.off");
  EXPECT_EQ(geom::stored_name("/x/Maps.PK3:maps/q3dm1.bsp"), "Maps.PK3:maps/q3dm1.bsp");
}

TEST(BakeRealFile, FailedBakeLeavesNoFile) {
  std::string dir = temp_dir("failedbake");
  write_text(dir + "/bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");  // vertex 9 does not exist
  write_text(dir + "/not_a_dir", "x");
  geom::BakeResult r = geom::bake_file(dir + "/bad.obj", dir + "/bad.gbake");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.rfind(dir + "/bad.obj: ", 0), 0u) << r.error;
  r = geom::bake_file(dir + "/missing.obj", dir + "/missing.gbake");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.rfind(dir + "/missing.obj: ", 0), 0u) << r.error;
  r = geom::bake_file(kBoxObj, dir + "/not_a_dir/box.gbake");  // the output's directory is a file
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("cannot write"), std::string::npos) << r.error;
  auto names = list_dir(dir);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"bad.obj", "not_a_dir"}));
}

TEST(GeombakeCli, SeveralInputsOneFailing) {
  std::string dir = temp_dir("cli");
  write_text(dir + "/a.obj", tetra_obj(0));
  write_text(dir + "/b.obj", "v 0 0 0\nf 1 2 3\n");  // out of range
  write_text(dir + "/c.obj", tetra_obj(5));
  CliRun r = geombake(dir, "bake '" + dir + "/a.obj' '" + dir + "/b.obj' '" + dir + "/c.obj' -o '" + dir + "/out'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("Error: " + dir + "/b.obj: "), std::string::npos) << r.err;
  auto names = list_dir(dir + "/out");
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"a.obj.gbake", "c.obj.gbake"}));
  CliRun ok = geombake(dir, "inspect '" + dir + "/out/a.obj.gbake' '" + dir + "/out/c.obj.gbake'");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("all checksums verified"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("volume_sides"), std::string::npos) << ok.out;
  // Two inputs with one output name: the second is refused, the first baked.
  ASSERT_EQ(::mkdir((dir + "/sub").c_str(), 0755), 0);
  write_text(dir + "/sub/a.obj", tetra_obj(1));
  CliRun dup = geombake(dir, "bake '" + dir + "/a.obj' '" + dir + "/sub/a.obj' -o '" + dir + "/dup'");
  EXPECT_EQ(dup.status, 1);
  EXPECT_NE(dup.err.find("Error: " + dir + "/sub/a.obj: its output " + dir + "/dup/a.obj.gbake is also the output of " +
                         dir + "/a.obj"),
            std::string::npos)
      << dup.err;
  EXPECT_EQ(list_dir(dir + "/dup"), std::vector<std::string>{"a.obj.gbake"});
  // Bad arguments: exit 2.
  EXPECT_EQ(geombake(dir, "bake '" + dir + "/a.obj'").status, 2);  // no -o
  EXPECT_EQ(geombake(dir, "bake --frobnicate '" + dir + "/a.obj' -o x").status, 2);
  EXPECT_EQ(geombake(dir, "bake --light 1,2,3 '" + dir + "/a.obj' -o x").status, 2);
  EXPECT_FALSE(exists(dir + "/x"));
}

TEST(GeombakeCli, DeterministicAcrossRunsAndThreads) {
  std::string dir = temp_dir("cli_det");
  std::string inputs;
  for (int i = 0; i < 6; ++i) {
    write_text(dir + "/m" + std::to_string(i) + ".obj", tetra_obj(float(i)));
    inputs += " '" + dir + "/m" + std::to_string(i) + ".obj'";
  }
  inputs += " '" + kBoxObj + "'";
  for (const char* run : {"-j 1 -o one", "-j 4 -o four", "-j 4 -o again"}) {
    CliRun r = geombake(dir, "bake" + inputs + " " + std::string(run, 8) + "'" + dir + "/" + (run + 8) + "'");
    ASSERT_EQ(r.status, 0) << run << ": " << r.err;
  }
  auto names = list_dir(dir + "/one");
  EXPECT_EQ(names.size(), 7u);
  for (const std::string& n : names) {
    auto a = read_bytes(dir + "/one/" + n);
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(same(a, read_bytes(dir + "/four/" + n))) << n;
    EXPECT_TRUE(same(a, read_bytes(dir + "/again/" + n))) << n;
  }
}

TEST(GeombakeCli, FlagsJsonDepfileAndInspect) {
  std::string dir = temp_dir("cli_flags");
  write_text(dir + "/t.obj", tetra_obj(0));
  CliRun r =
      geombake(dir, "bake --no-esm --no-adjacency --no-remap --light 0,0,5,1 --light 1,1,1,0 --json --depfile '" + dir +
                        "/t.d' '" + dir + "/t.obj' -o '" + dir + "/t.gbake'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"ok\":true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"section_bytes\":"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"name\":\"light_sides\""), std::string::npos) << r.out;
  auto dep = read_bytes(dir + "/t.d");
  EXPECT_EQ(std::string(dep.begin(), dep.end()), dir + "/t.gbake: " + dir + "/t.obj\n");
  geom::baked::File f;
  ASSERT_TRUE(f.load(dir + "/t.gbake")) << f.error();
  const Reader& rd = f.reader();
  EXPECT_EQ(rd.find(SectionType::EsmQuads), nullptr);
  EXPECT_EQ(rd.find(SectionType::AdjacencyIndices), nullptr);
  EXPECT_EQ(rd.find(SectionType::WeldRemap), nullptr);
  EXPECT_NE(rd.find(SectionType::VolumeSides), nullptr);
  EXPECT_NE(rd.find(SectionType::LightSides, 0), nullptr);
  EXPECT_NE(rd.find(SectionType::LightSides, 1), nullptr);
  EXPECT_EQ(values<double>(rd.find(SectionType::Lights)), (std::vector<double>{0, 0, 5, 1, 1, 1, 1, 0}));

  CliRun v = geombake(dir, "bake -v '" + dir + "/t.obj' -o '" + dir + "/v.gbake'");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_NE(v.out.find("esm_quads"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("bytes"), std::string::npos) << v.out;

  CliRun js = geombake(dir, "inspect --json '" + dir + "/t.gbake'");
  ASSERT_EQ(js.status, 0) << js.err;
  EXPECT_NE(js.out.find("\"name\":\"volume_caps\""), std::string::npos) << js.out;

  // A damaged copy: inspect names the file and the problem, exits 1.
  auto bytes = read_bytes(dir + "/t.gbake");
  bytes[bytes.size() - 3] ^= 0x40;
  write_text(dir + "/damaged.gbake", std::string(bytes.begin(), bytes.end()));
  CliRun bad = geombake(dir, "inspect '" + dir + "/t.gbake' '" + dir + "/damaged.gbake'");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("Error: " + dir + "/damaged.gbake: section "), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("checksum mismatch"), std::string::npos) << bad.err;
  // A foreign file.
  CliRun foreign = geombake(dir, "inspect '" + dir + "/t.obj'");
  EXPECT_EQ(foreign.status, 1);
  EXPECT_NE(foreign.err.find("not a geombake baked file"), std::string::npos) << foreign.err;
}

// A real game level (open, non-manifold), baked from inside its archive by the
// CLI: the container verifies, holds the buffers of the library's own bake, and
// a second run with another thread count gives the same bytes.
TEST(GeombakeCli, Quake3MapFromArchive) {
  const std::string map = "/usr/share/games/openarena/baseoa/pak1-maps.pk3:maps/oa_bases3cl.bsp";
  std::string dir = temp_dir("cli_q3");
  CliRun r = geombake(dir, "bake --light 0,0,1,0 '" + map + "' '" + kBoxObj + "' -o '" + dir + "/out' -j 2");
  ASSERT_EQ(r.status, 0) << r.err;
  CliRun again = geombake(dir, "bake --light 0,0,1,0 '" + map + "' '" + kBoxObj + "' -o '" + dir + "/again' -j 1");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_TRUE(read_bytes(dir + "/out/oa_bases3cl.bsp.gbake") == read_bytes(dir + "/again/oa_bases3cl.bsp.gbake"));
  EXPECT_TRUE(read_bytes(dir + "/out/box.obj.gbake") == read_bytes(dir + "/again/box.obj.gbake"));
  geom::ImportResult imported = geom::import_file(map);
  ASSERT_TRUE(imported.ok) << imported.error;
  geom::BakeOptions o;
  o.lights = lights_of({{0, 0, 1, 0}});
  o.caster_hull = geom::focus_caster_hull;  // as geombake bakes
  check_baked(imported.scene, o, map);
  geom::BakeResult baked =
      geom::bake_scene(imported.scene, "pak1-maps.pk3:maps/oa_bases3cl.bsp", o);  // the name stored
  ASSERT_TRUE(baked.ok) << baked.error;
  geom::baked::File f;
  ASSERT_TRUE(f.load(dir + "/out/oa_bases3cl.bsp.gbake")) << f.error();
  expect_same(baked.sections, f.reader());
  EXPECT_FALSE(baked.report.stats.closed);
}

// The bundled scene declares a point and a directional light (KHR_lights_punctual):
// each gets its exact volume, in the scene's order, unless --no-scene-lights.
TEST(BakeRealFile, SceneLightsOfTheDefaultScene) {
  const std::string path = std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf";
  geom::ImportResult imported = geom::import_file(path);
  ASSERT_TRUE(imported.ok) << imported.error;
  ASSERT_EQ(imported.scene.lights.size(), 2u);
  check_baked(imported.scene, {}, path);
  geom::BakeResult r = geom::bake_scene(imported.scene, path);
  ASSERT_TRUE(r.ok) << r.error;
  std::vector<unsigned char> bytes;
  std::string error;
  ASSERT_TRUE(geom::serialize_baked(r.sections, bytes, error)) << error;
  Reader rd;
  ASSERT_TRUE(rd.open(bytes.data(), bytes.size())) << rd.error();
  const std::vector<geom::Light>& expected = imported.scene.lights;
  auto table = values<double>(rd.find(SectionType::Lights));
  ASSERT_EQ(table.size(), 8u);
  for (size_t i = 0; i < 2; ++i) {
    double h[4];
    geom::light_homogeneous(expected[i], h);
    EXPECT_EQ(std::vector<double>(table.begin() + 4 * i, table.begin() + 4 * i + 4), std::vector<double>(h, h + 4));
    EXPECT_NE(r.silhouette.find("\"name\":\"" + expected[i].name + "\""), std::string::npos) << r.silhouette;
    EXPECT_GT(rd.find(SectionType::LightSides, uint32_t(i))->count, 0u);
  }
  geom::BakeOptions no_lights;
  no_lights.scene_lights = false;
  geom::BakeResult n = geom::bake_scene(imported.scene, path, no_lights);
  ASSERT_TRUE(n.ok) << n.error;
  for (const auto& s : n.sections) {
    EXPECT_NE(s.type, SectionType::Lights);
    EXPECT_NE(s.type, SectionType::LightSides);
  }
}

// The includes of `header` (libgeom/include/geom/...), in order.
std::vector<std::string> includes_of(const std::string& header) {
  std::vector<unsigned char> text = read_bytes(std::string(GEOM_SOURCE_DIR) + "/libgeom/include/geom/" + header);
  std::string src(text.begin(), text.end());
  std::vector<std::string> out;
  for (size_t at = src.find("#include"); at != std::string::npos; at = src.find("#include", at + 1)) {
    const size_t end = src.find('\n', at);
    out.push_back(src.substr(at + 9, end - at - 9));
  }
  return out;
}

// The reader is what an engine can take alone (geom::reader): baked_reader.h
// and baked_records.h include nothing but the C++ standard library, and none
// of it for files (no <filesystem>, no POSIX header: reading from memory needs
// none); this file includes the reader first, so it is seen to compile alone.
TEST(BakedReaderHeader, StandardLibraryOnly) {
  const std::vector<std::string> allowed = {"<cmath>",   "<cstddef>", "<cstdint>", "<cstdio>",
                                            "<cstring>", "<string>",  "<vector>"};
  for (const char* header : {"baked_reader.h", "baked_records.h"}) {
    const std::vector<std::string> included = includes_of(header);
    EXPECT_FALSE(included.empty()) << header;
    for (const std::string& what : included)
      EXPECT_NE(std::find(allowed.begin(), allowed.end(), what), allowed.end()) << header << " includes " << what;
  }
}

// Reading a file is the companion header's (geom/baked_file.h): the reader,
// the standard library, and POSIX headers only inside the block File::map() needs.
TEST(BakedReaderHeader, FileReadingApart) {
  std::vector<unsigned char> text = read_bytes(std::string(GEOM_SOURCE_DIR) + "/libgeom/include/geom/baked_file.h");
  const std::string src(text.begin(), text.end());
  const size_t posix_block = src.find("#if defined(__unix__) || defined(__APPLE__)");
  const size_t posix_end = src.find("#else", posix_block);
  ASSERT_NE(posix_block, std::string::npos);
  const std::vector<std::string> allowed = {
      "<cstdint>", "<cstdio>", "<cstring>", "<filesystem>", "<string>", "<vector>", "\"geom/baked_reader.h\""};
  const std::vector<std::string> posix = {"<fcntl.h>", "<sys/mman.h>", "<sys/stat.h>", "<unistd.h>"};
  size_t includes = 0;
  for (size_t at = src.find("#include"); at != std::string::npos; at = src.find("#include", at + 1)) {
    const size_t end = src.find('\n', at);
    const std::string what = src.substr(at + 9, end - at - 9);
    const bool in_block = at > posix_block && at < posix_end;
    const std::vector<std::string>& ok = in_block ? posix : allowed;
    EXPECT_NE(std::find(ok.begin(), ok.end(), what), ok.end()) << "includes " << what;
    ++includes;
  }
  EXPECT_EQ(includes, allowed.size() + posix.size());
}
