// Bad-input sweep of the geombake CLI: every hostile input gets "Error: FILE:
// cause", a non-zero exit and no output, never a crash, a hang or silence.
//
// The law, checked on every input below by running the real binary
// (`geombake bake FILE -o DIR/out.gbake --json`) as a child process:
//   - it ends by itself (no hang: killed after 60 s), with no signal, no
//     sanitizer report on stderr, and exit status 0 (loaded and baked) or 1
//     (refused);
//   - refused: stderr holds `Error: FILE: what is wrong`, naming the very file
//     given, and the output directory is left empty (no output, no temporary);
//   - loaded: no `Error:` line, and the output directory holds exactly the
//     output file;
//   - within a second of CPU time (user + system: robust on a loaded machine;
//     x4 under sanitizers) and 512 MB of peak memory (a header claiming
//     billions of elements must not allocate them).
// Inputs: every glTF/GLB of the glTF-Validator test data; the broken files of
// assimp-testmodels (invalid/, the broken glTF2 folders) and every file of
// openscad-testing-data's STL/AMF/3MF test data; every file of the Draco test
// data; hostile files written here (NaN and infinite coordinates, indices out
// of range, absurd counts, broken framing) in every format, each of which must
// be refused with a message saying what is wrong. Truncations of real files (every
// length for small files, a thousand spread lengths for larger ones) go
// through one batch run each (`geombake bake --list`), which must bake the
// loadable ones and refuse the rest with one `Error:` line each, and count
// both in its summary.
// Non-fatal geometry problems (degenerate faces, non-manifold edges) load:
// a warning and a count in the report, never an error.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"
#include "geom/import.h"

namespace fs = std::filesystem;

namespace {

const std::string kData = GEOM_TEST_DATA;
const std::string kAssimp = "/usr/share/assimp/models";
const std::string kOpenscad = "/usr/share/openscad";
const double kCpuLimit = 1.0 * cli::kSanitizerFactor;
const long kRssLimitKb = long(512 * 1024 * (cli::kSanitizerFactor > 1 ? 2 : 1));

// This process's scratch folder is removed when the process ends.
struct ScratchCleanup {
  ~ScratchCleanup() {
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("geom_sweep_" + std::to_string(::getpid())), ec);
  }
} scratch_cleanup;

fs::path scratch_root() {
  static fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("geom_sweep_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

fs::path fresh_dir(const std::string& tag) {
  static int counter = 0;
  fs::path d = scratch_root() / (tag + std::to_string(counter++));
  fs::create_directories(d);
  return d;
}

enum class Expect { LoadsOrRefused, Refused, Loads };

struct Tally {
  int loaded = 0, refused = 0;
};

// Runs the law on one input; returns the run.
cli::Run check_input(const std::string& file, Expect expect, Tally& tally, const std::string& why = "") {
  fs::path work = fresh_dir("run");
  fs::path out_dir = work / "out";
  fs::create_directories(out_dir);
  const std::string output = (out_dir / "out.gbake").string();
  cli::Run r = cli::run({"bake", file, "-o", output, "--json"}, work / "log");
  SCOPED_TRACE(file + (why.empty() ? "" : " (" + why + ")") + ": " + cli::describe(r));
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.signal, 0);
  EXPECT_FALSE(cli::sanitizer_report(r.err));
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1);
  EXPECT_LE(r.cpu_seconds, kCpuLimit);
  EXPECT_LE(r.max_rss_kb, kRssLimitKb);
  const std::string prefix = "Error: " + file + ": ";
  const size_t at = r.err.find(prefix);
  const std::vector<std::string> left = cli::listing(out_dir);
  if (r.exit_code == 1) {
    ++tally.refused;
    EXPECT_NE(at, std::string::npos) << "no `Error: FILE: ` line";
    if (at != std::string::npos) {
      const size_t end = r.err.find('\n', at);
      EXPECT_GT((end == std::string::npos ? r.err.size() : end) - at, prefix.size() + 3) << "says what is wrong";
    }
    EXPECT_TRUE(left.empty()) << "left behind: " << (left.empty() ? "" : left[0]);
    EXPECT_NE(expect, Expect::Loads);
  } else if (r.exit_code == 0) {
    ++tally.loaded;
    EXPECT_EQ(r.err.find("Error:"), std::string::npos);
    EXPECT_EQ(left, std::vector<std::string>{"out.gbake"});
    EXPECT_NE(expect, Expect::Refused);
  }
  return r;
}

std::vector<std::string> files_under(const std::string& dir, const std::set<std::string>& extensions = {}) {
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (!it->is_regular_file()) continue;
    std::string ext = it->path().extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (extensions.empty() || extensions.count(ext)) files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string write_file(const std::string& name, const std::string& bytes) {
  fs::path dir = scratch_root() / "hostile";
  fs::create_directories(dir);
  fs::path p = dir / name;
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return p.string();
}

std::string read_file(const std::string& path) { return cli::slurp(path); }

template <class T>
void put(std::string& b, T v) {
  b.append(reinterpret_cast<const char*>(&v), sizeof v);
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string o;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
    o += k[(v >> 18) & 63];
    o += k[(v >> 12) & 63];
    o += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    o += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return o;
}

// A one-triangle glTF with an embedded buffer: 3 float positions then 3 uint32
// indices; `accessor_count` and `index_count` may lie.
std::string gltf_triangle(const float (&p)[9], const uint32_t (&idx)[3], const std::string& position_count = "3",
                          const std::string& index_count = "3", const std::string& byte_length = "48") {
  std::string bin;
  for (float f : p) put(bin, f);
  for (uint32_t i : idx) put(bin, i);
  return R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + byte_length +
         R"(,"uri":"data:application/octet-stream;base64,)" + base64(bin) +
         R"("}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" + position_count +
         R"(,"type":"VEC3"},{"bufferView":1,"componentType":5125,"count":)" + index_count +
         R"(,"type":"SCALAR"}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
         R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
}

std::string binary_stl(uint32_t claimed, const std::vector<float>& xyz9) {
  std::string b(80, ' ');
  put(b, claimed);
  for (size_t t = 0; t + 9 <= xyz9.size(); t += 9) {
    for (int k = 0; k < 3; ++k) put(b, 0.0f);
    for (size_t k = 0; k < 9; ++k) put(b, xyz9[t + k]);
    put(b, uint16_t(0));
  }
  return b;
}

}  // namespace

TEST(BadInputSweep, GeombakeIsBuilt) {
  ASSERT_TRUE(fs::exists(cli::geombake_path())) << cli::geombake_path();
}

// Every glTF and GLB of the glTF-Validator test data (372 files, most invalid).
TEST(BadInputSweep, GltfValidatorFiles) {
  const std::vector<std::string> files = files_under(kData + "/gltf-validator", {".gltf", ".glb"});
  ASSERT_GT(files.size(), 300u);
  Tally t;
  for (const std::string& f : files) check_input(f, Expect::LoadsOrRefused, t);
  std::printf("glTF-Validator: %d loaded, %d refused of %zu\n", t.loaded, t.refused, files.size());
  EXPECT_GT(t.loaded, 50);
  EXPECT_GT(t.refused, 50);
}

// assimp-testmodels' broken files: invalid/ (a 353-billion-vertex OFF header,
// empty files, bad OBJ indices, formats geombake does not read) and the broken
// glTF2 folders.
TEST(BadInputSweep, AssimpBrokenFiles) {
  Tally t;
  std::vector<std::string> files = files_under(kAssimp + "/invalid");
  ASSERT_GE(files.size(), 10u);
  for (const std::string& f : files) check_input(f, Expect::LoadsOrRefused, t);
  for (const char* dir : {"IndexOutOfRange", "MissingBin", "BoxWithInfinites-glTF-Binary", "RecursiveNodes",
                          "wrongTypes", "IncorrectVertexArrays", "TestNoRootNode", "SchemaFailures"})
    for (const std::string& f : files_under(kAssimp + "/glTF2/" + dir, {".gltf", ".glb"})) {
      // These three are broken in the geometry itself: they must be refused.
      const bool must_refuse = std::strstr(dir, "IndexOutOfRange") || std::strstr(dir, "Infinites") ||
                               std::strstr(dir, "RecursiveNodes");
      check_input(f, must_refuse ? Expect::Refused : Expect::LoadsOrRefused, t);
      files.push_back(f);
    }
  const std::string off = kAssimp + "/invalid/OutOfMemory.off";
  ASSERT_TRUE(fs::exists(off));
  check_input(off, Expect::Refused, t, "claims 353 billion vertices");
  std::printf("assimp broken: %d loaded, %d refused of %zu\n", t.loaded, t.refused, files.size() + 1);
  EXPECT_GT(t.refused, 10);
}

// openscad-testing-data: STL files that are broken (unparseable, too many
// vertices, invalid vertices, empty) or non-manifold, and AMF/3MF files (a
// type geombake does not read: refused by name).
TEST(BadInputSweep, OpenscadFiles) {
  std::vector<std::string> files = files_under(kOpenscad, {".stl", ".amf", ".3mf", ".off"});
  ASSERT_GE(files.size(), 20u) << "openscad-testing-data installed? (scripts/setup.sh)";
  Tally t;
  for (const std::string& f : files) {
    const bool ours = f.size() > 4 && (f.substr(f.size() - 4) == ".stl" || f.substr(f.size() - 4) == ".off");
    check_input(f, ours ? Expect::LoadsOrRefused : Expect::Refused, t);
  }
  std::printf("openscad: %d loaded, %d refused of %zu\n", t.loaded, t.refused, files.size());
  EXPECT_GT(t.loaded, 10);
}

// Every file of the Draco test data (.drc streams are not a geombake input:
// refused by name; OBJ/PLY edge cases load or are refused; Box glTFs load).
TEST(BadInputSweep, DracoDataFiles) {
  std::vector<std::string> files = files_under(kData + "/draco");
  ASSERT_GE(files.size(), 80u);
  Tally t;
  for (const std::string& f : files) {
    const bool drc = f.size() > 4 && f.substr(f.size() - 4) == ".drc";
    check_input(f, drc ? Expect::Refused : Expect::LoadsOrRefused, t);
  }
  std::printf("draco data: %d loaded, %d refused of %zu\n", t.loaded, t.refused, files.size());
}

// Non-fatal geometry problems load: degenerate faces and non-manifold edges
// are counted in the report (and named in a warning), never an error.
TEST(BadInputSweep, GeometryProblemsAreWarnings) {
  struct Case {
    std::string file, count, warning;
  };
  const std::vector<Case> cases = {
      {kData + "/draco/deg_faces.obj", "collapsed_triangles", "collapsed triangles"},
      {kData + "/draco/degenerate_mesh.obj", "collapsed_triangles", "collapsed triangles"},
      {kData + "/draco/non_manifold_wrap.obj", "non_manifold_edges", "non-manifold edges"},
      {"/usr/share/games/openarena/baseoa/pak1-maps.pk3:maps/oa_ctf2.bsp", "duplicate_triangles",
       "duplicate triangles"}};
  for (const Case& c : cases) {
    fs::path work = fresh_dir("warn");
    cli::Run text = cli::run({"bake", c.file, "-o", (work / "y.gbake").string()}, work / "log0");
    EXPECT_EQ(text.exit_code, 0) << cli::describe(text);
    const size_t w = text.err.find("Warning: " + c.file + ": ");
    ASSERT_NE(w, std::string::npos) << text.err;
    EXPECT_NE(text.err.find(c.warning, w), std::string::npos) << text.err;
    cli::Run r = cli::run({"bake", c.file, "-o", (work / "x.gbake").string(), "--json"}, work / "log");
    SCOPED_TRACE(c.file + ": " + cli::describe(r));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err.find("Error:"), std::string::npos);
    // "KEY":N with N > 0 in the JSON report.
    const std::string key = "\"" + c.count + "\":";
    size_t at = r.out.find(key);
    ASSERT_NE(at, std::string::npos) << r.out.substr(0, 500);
    EXPECT_GT(std::atoll(r.out.c_str() + at + key.size()), 0) << c.count;
    EXPECT_TRUE(fs::exists(work / "x.gbake"));
  }
}

// Hostile files written here, one per kind of damage and format: each must be
// refused with a message that says what is wrong (the key words checked).
TEST(BadInputSweep, HostileFilesAreRefused) {
  const float nan = std::nanf(""), inf = INFINITY;
  struct Case {
    std::string name, bytes, words;  // words: a fragment the message must hold
  };
  const float good[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float with_nan[9] = {0, 0, 0, 1, nan, 0, 0, 1, 0};
  const float with_inf[9] = {0, 0, 0, 1, 0, 0, 0, inf, 0};
  std::string bsp_huge_lump = "IBSP";
  put(bsp_huge_lump, int32_t(46));
  for (int l = 0; l < 17; ++l) put(bsp_huge_lump, int32_t(144)), put(bsp_huge_lump, int32_t(l == 13 ? 0x7fffff00 : 0));
  std::string md3_huge = "IDP3";
  put(md3_huge, int32_t(15));
  md3_huge += std::string(64, 0);  // name
  put(md3_huge, int32_t(0));       // flags
  for (int32_t v : {0x7fffffff, 0, 0x7fffffff, 0, 0, 0, 0, 0}) put(md3_huge, v);  // frames, tags, surfaces, skins, offsets
  std::string glb_huge = "glTF";
  put(glb_huge, uint32_t(2)), put(glb_huge, uint32_t(0xfffffff0)), put(glb_huge, uint32_t(0xffffffe0));
  glb_huge += "JSON{}  ";
  const std::vector<Case> cases = {
      {"nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "finite"},
      {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n", "finite"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n", "99"},
      {"negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -9 1 2\n", "-9"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n", "finite"},
      {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "5"},
      {"billions.off", "OFF\n353000000000 1 0\n0 0 0\n", "353000000000"},
      {"nan.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n",
       "finite"},
      {"range.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
       "7"},
      {"billions.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\n" + std::string(24, '\0'),
       "4000000000"},
      {"nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\nendloop\n"
                  "endfacet\nendsolid x\n",
       "finite"},
      {"nanbin.stl", binary_stl(1, {0, 0, 0, 1, 0, 0, 0, nan, 0}), "finite"},
      {"billions.stl", binary_stl(0xffffffffu, {0, 0, 0, 1, 0, 0, 0, 1, 0}), "4294967295"},
      {"nan.gltf", gltf_triangle(with_nan, {0, 1, 2}), "finite"},
      {"inf.gltf", gltf_triangle(with_inf, {0, 1, 2}), "finite"},
      {"range.gltf", gltf_triangle(good, {0, 1, 3}), "3"},
      {"billions.gltf", gltf_triangle(good, {0, 1, 2}, "4000000000"), "4000000000"},
      {"hugebuffer.gltf", gltf_triangle(good, {0, 1, 2}, "3", "3", "1000000000000"), "1000000000000"},
      {"huge.glb", glb_huge, "4294967280"},
      {"hugelump.bsp", bsp_huge_lump, "faces"},
      {"huge.md3", md3_huge, ""},
      {"cycle.gltf",
       R"({"asset":{"version":"2.0"},"nodes":[{"children":[1]},{"children":[0]}],"scenes":[{"nodes":[0]}],"scene":0})",
       "node"},
  };
  Tally t;
  for (const Case& c : cases) {
    const std::string path = write_file(c.name, c.bytes);
    cli::Run r = check_input(path, Expect::Refused, t, c.name);
    const std::string prefix = "Error: " + path + ": ";
    const size_t at = r.err.find(prefix);
    ASSERT_NE(at, std::string::npos);
    const std::string message = r.err.substr(at, r.err.find('\n', at) - at);
    EXPECT_NE(message.find(c.words), std::string::npos) << message;
    std::printf("%-16s %s\n", c.name.c_str(), message.substr(prefix.size()).c_str());
  }
  EXPECT_EQ(t.refused, int(cases.size()));
}

// Truncations of real files of every format, each set baked in one batch run
// from a list file (`--list`): the loadable prefixes are baked, every other one
// is refused by its own `Error: FILE: ` line, no output is left for them, the
// exit status is 1, and the run takes under a second of CPU per input.
TEST(BadInputSweep, TruncationsInBatch) {
  std::map<std::string, std::string> sources = {
      {"cube_att.obj", read_file(kData + "/draco/cube_att.obj")},
      {"Box.ply", read_file(kData + "/draco/Box.ply")},
      {"Cube.off", read_file(kAssimp + "/OFF/Cube.off")},
      {"triangle.stl", read_file(kAssimp + "/STL/triangle.stl")},
      {"Spider_binary.stl", read_file(kAssimp + "/STL/Spider_binary.stl")},
      {"Box.glb", read_file(kData + "/draco/Box/glTF_Binary/Box.glb")},
      {"Box_Draco.glb", read_file(kData + "/draco/Box/glTF_Binary/Box_Draco.glb")},
      {"BoxTextured.gltf", read_file(kAssimp + "/glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf")},
  };
  std::vector<unsigned char> md3;
  std::string error;
  if (geom::read_archive_member("/usr/share/games/openarena/baseoa/pak2-players.pk3",
                                        "models/players/gargoyle/head_2.md3", md3, 0, error))
    sources["head_2.md3"] = std::string(md3.begin(), md3.end());
  for (const auto& [name, bytes] : sources) {
    SCOPED_TRACE(name);
    ASSERT_GT(bytes.size(), 100u);
    fs::path work = fresh_dir("trunc");
    fs::path in_dir = work / "in", out_dir = work / "out";
    fs::create_directories(in_dir);
    // Every length up to 2 KB, then about a thousand spread over the rest.
    std::vector<size_t> lengths;
    const size_t step = bytes.size() <= 2048 ? 1 : std::max<size_t>(1, (bytes.size() - 2048) / 1000);
    for (size_t n = 0; n < bytes.size(); n += n < 2048 ? 1 : step) lengths.push_back(n);
    std::string list;
    const std::string stem = name.substr(0, name.find('.')), ext = name.substr(name.find('.'));
    std::vector<std::string> inputs;
    for (size_t n : lengths) {
      fs::path p = in_dir / (stem + "_" + std::to_string(n) + ext);
      std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(n));
      inputs.push_back(p.string());
      list += p.string() + "\n";
    }
    std::ofstream(work / "list.txt") << list;
    cli::Run r = cli::run({"bake", "--list", (work / "list.txt").string(), "-o", out_dir.string(), "-j", "2",
                           "--timeout", "20"},
                          work / "log", 600);
    SCOPED_TRACE(cli::describe(r));
    EXPECT_FALSE(r.timed_out);
    EXPECT_EQ(r.signal, 0);
    EXPECT_FALSE(cli::sanitizer_report(r.err));
    EXPECT_LE(r.cpu_seconds, kCpuLimit * double(inputs.size()) / 10);
    const std::vector<std::string> outputs = cli::listing(out_dir);
    const std::set<std::string> out_set(outputs.begin(), outputs.end());
    size_t refused = 0;
    for (const std::string& in : inputs) {
      const std::string out_name = fs::path(in).filename().string() + ".gbake";
      const bool error_line = r.err.find("Error: " + in + ": ") != std::string::npos;
      const bool baked = out_set.count(out_name) > 0;
      EXPECT_NE(error_line, baked) << in;  // exactly one of the two
      refused += error_line;
    }
    EXPECT_EQ(outputs.size() + refused, inputs.size()) << "stray files in the output directory";
    EXPECT_EQ(r.exit_code, refused ? 1 : 0);
    EXPECT_NE(r.err.find(std::to_string(outputs.size()) + " baked, " + std::to_string(refused) + " failed of " +
                         std::to_string(inputs.size()) + " inputs"),
              std::string::npos);
    std::printf("%-18s %zu truncations: %zu baked, %zu refused, %.2f s CPU\n", name.c_str(), inputs.size(),
                outputs.size(), refused, r.cpu_seconds);
  }
}
