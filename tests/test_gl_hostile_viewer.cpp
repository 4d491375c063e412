// geomview held to the baker's bar on hostile input: every case below ends
// with `Error: ...` on stderr and a non-zero exit (2 for bad usage, 1 for bad
// input or a failed run), quickly, with no crash (no signal, no exit 134), no
// hang, and nothing written: no PNG, no folder, no temporary file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "geom/bake.h"
#include "geom/baked_writer.h"
#include "viewer_run.h"

namespace {

namespace fs = std::filesystem;
using viewertest::geomview;
using viewertest::Scratch;
using viewertest::ViewerRun;

std::string q(const std::string& s) { return "'" + s + "'"; }

// A failed run: the exit code, an Error: line naming `names`, nothing in the
// scratch folder but the inputs (`keep`) and the captured output.
void expect_refused(const Scratch& s, const ViewerRun& r, int code, const std::string& names,
                    const std::vector<std::string>& keep = {}) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_NE(r.err.find("Error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << "the error names " << names << ": " << r.err;
  EXPECT_EQ(r.err.find("terminate called"), std::string::npos) << r.err;
  for (const auto& e : fs::directory_iterator(s.dir)) {
    const std::string name = e.path().filename().string();
    if (name == "stdout.txt" || name == "stderr.txt" || std::find(keep.begin(), keep.end(), name) != keep.end())
      continue;
    ADD_FAILURE() << "left behind: " << name;
  }
}

struct Hostile : ::testing::Test {
  Scratch s{"hostile"};
  std::string obj = s / "scene.obj", png = s / "x.png";
  void SetUp() override { std::ofstream(obj) << viewertest::kScene; }
  ViewerRun view(const std::string& flags, const std::string& wrapper = "") {
    return geomview(s, q(obj) + " --size 64x48 -o " + q(png) + " " + flags, wrapper);
  }
};

// Numbers parsed whole, in range, integers where integers are meant; the flag named.
TEST_F(Hostile, NumbersAreStrict) {
  const std::pair<const char*, const char*> cases[] = {
      {"--frames 1e3", "--frames"},
      {"--shadow-map-size 4294968320", "--shadow-map-size"},
      {"--shadow-map-size 1024abc", "--shadow-map-size"},
      {"--light-radius abc", "--light-radius"},
      {"--light-radius -1", "--light-radius"},
      {"--technique ''", "--technique"},
      {"--technique ssm,", "--technique"},
      {"--compare ssm,,pcf", "--compare"},
      {"--size 64x48x", "--size"},
      {"--size ' 64x48'", "--size"},
  };
  for (const auto& [flags, name] : cases) {
    SCOPED_TRACE(flags);
    expect_refused(s, view(flags), 2, name, {"scene.obj"});
  }
}

// Lights and cameras beyond what the float pipeline and Embree hold, or that
// cannot give an image: refused by name before any work.
TEST_F(Hostile, LightsAndCamerasWithinTheLimits) {
  const std::pair<const char*, const char*> cases[] = {
      {"--light 2e18,0,0,1 --error", "--light"},
      {"--light 1e20,1e20,0,0", "--light"},
      {"--light 0,0,0,0", "--light"},
      {"--eye 1e19,1,1 --far 1e30 --error", "camera"},
      {"--near 1e-7 --far 100", "24-bit depth"},
      {"--eye 0,5,0 --target 0,0,0 --up 0,1,0", "parallel"},
      {"--eye 1e15,0,0 --target 1000000000000001,0,0", "camera"},
  };
  for (const auto& [flags, name] : cases) {
    SCOPED_TRACE(flags);
    expect_refused(s, view(std::string(viewertest::kSceneView) + " " + flags), 1, name, {"scene.obj"});
  }
}

// A glTF light at 1e30 (finite as a double, past Embree's limit) and at 1e39
// (past a float's): the file and its light named.
TEST_F(Hostile, SceneLightsWithinTheLimits) {
  std::ifstream in(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
  const std::string gltf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "\"point_light\",\n   \"translation\": [\n    1.0,";
  ASSERT_NE(gltf.find(from), std::string::npos);
  for (const char* at : {"1e30", "1e39"}) {
    std::string text = gltf;
    text.replace(text.find(from), from.size(), std::string("\"point_light\", \"translation\": [") + at + ",");
    std::ofstream(s / "far.gltf") << text;
    const ViewerRun r = geomview(s, q(s / "far.gltf") + " --error -o " + q(png) + " --size 64x48");
    SCOPED_TRACE(at);
    expect_refused(s, r, 1, "far.gltf: light 0", {"scene.obj", "far.gltf"});
  }
}

// A baked file intact as a container whose floats are not: refused, naming the
// file and the section.
TEST_F(Hostile, BakedFloatsAreValidated) {
  geom::Scene scene;
  std::vector<float> p;
  std::vector<uint32_t> i;
  viewertest::parse_obj(viewertest::kScene, p, i);
  scene.positions = p, scene.indices = i;
  scene.sources.resize(scene.triangle_count());
  scene.lights.resize(1);
  scene.lights[0].position[1] = 5;
  const geom::BakeResult bake = geom::bake_scene(scene, "scene");
  ASSERT_TRUE(bake.ok) << bake.error;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [type, value] :
       {std::make_pair(geom::baked::SectionType::Lights, nan), std::make_pair(geom::baked::SectionType::Lights, 0.0),
        std::make_pair(geom::baked::SectionType::Positions, nan),
        std::make_pair(geom::baked::SectionType::Positions, 1e30),
        std::make_pair(geom::baked::SectionType::Frame, nan)}) {
    std::vector<geom::BakedSection> sections = bake.sections;
    bool found = false;
    for (geom::BakedSection& sec : sections) {
      if (sec.type != type) continue;
      std::vector<unsigned char> bytes(sec.data(), sec.data() + sec.size());
      if (sec.format == geom::baked::Format::F32x3) {
        const float f = float(value);
        std::memcpy(&bytes[0], &f, 4);
      } else {  // f64: a light set to (v, v, v, v), the frame's origin x to v
        for (int k = 0; k < (type == geom::baked::SectionType::Lights ? 4 : 1); ++k)
          std::memcpy(&bytes[8 * k], &value, 8);
      }
      sec.bytes = bytes, sec.view = nullptr, sec.view_size = 0, sec.keep.reset();
      found = true;
    }
    ASSERT_TRUE(found) << geom::baked::type_name(type);
    std::string error;
    ASSERT_TRUE(geom::write_baked(s / "bad.gbake", sections, error)) << error;
    SCOPED_TRACE(std::string(geom::baked::type_name(type)) + " " + std::to_string(value));
    const ViewerRun r = geomview(s, q(s / "bad.gbake") + " --technique sv -o " + q(png) + " --size 64x48");
    expect_refused(s, r, 1, std::string("bad.gbake: section "), {"scene.obj", "bad.gbake"});
    EXPECT_NE(r.err.find(std::string("(") + geom::baked::type_name(type) + ")"), std::string::npos) << r.err;
  }
}

// Files opened as geombake opens them: a baked header over a 64 GiB sparse
// tail is refused before it is read; FIFOs and devices refused by name, as
// inputs, shader files and outputs, never waited on.
TEST_F(Hostile, FilesAreOpenedSafely) {
  {
    std::vector<unsigned char> head(64, 0);
    std::memcpy(head.data(), geom::baked::kMagic, 8);
    const uint64_t size = uint64_t(64) << 30;
    for (int k = 0; k < 8; ++k) head[32 + k] = uint8_t(size >> (8 * k));
    testfs::write_all(s / "sparse.gbake", head);
    ASSERT_EQ(::truncate((s / "sparse.gbake").c_str(), off_t(size)), 0);
    const ViewerRun r = geomview(s, q(s / "sparse.gbake") + " -o " + q(png), "timeout 60");
    expect_refused(s, r, 1, "sparse.gbake", {"scene.obj", "sparse.gbake"});
  }
  fs::remove(s / "sparse.gbake");
  ASSERT_EQ(::mkfifo((s / "fifo").c_str(), 0600), 0);
  expect_refused(s, geomview(s, q(s / "fifo") + " -o " + q(png), "timeout 30"), 1, "fifo", {"scene.obj", "fifo"});
  expect_refused(s, geomview(s, q(obj) + " -o " + q(s / "fifo"), "timeout 30"), 2, "fifo", {"scene.obj", "fifo"});
  expect_refused(s, geomview(s, q(obj) + " -o /dev/full", "timeout 30"), 2, "/dev/full", {"scene.obj", "fifo"});
  // Shader folders whose every file is a FIFO, or a link to /dev/zero.
  for (const char* kind : {"fifos", "zeros"}) {
    const fs::path dir = s.dir / kind;
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(GEOM_SHADER_DIR)) {
      const fs::path to = dir / e.path().filename();
      if (std::string(kind) == "fifos")
        ASSERT_EQ(::mkfifo(to.c_str(), 0600), 0);
      else
        fs::create_symlink("/dev/zero", to);
    }
    const ViewerRun r = geomview(s, q(obj) + " --shaders " + q(dir.string()) + " -o " + q(png), "timeout 30");
    SCOPED_TRACE(kind);
    expect_refused(s, r, 1, "not a regular file", {"scene.obj", "fifo", "fifos", "zeros"});
  }
}

// A full disk (a file size limit with SIGXFSZ ignored, so writes fail with
// EFBIG): an error, and no truncated PNG or temporary file left.
TEST_F(Hostile, AFailedWriteLeavesNothing) {
  const ViewerRun r = geomview(s, q(obj) + " -o " + q(png) + " --size 640x480", "trap '' XFSZ; ulimit -f 8;");
  expect_refused(s, r, 1, "x.png", {"scene.obj"});
}

// Several techniques into a folder where a later one fails (its shader is
// missing): no folder and no earlier PNG left behind.
TEST_F(Hostile, ALaterTechniqueFailingLeavesNoFolder) {
  const fs::path shaders = s.dir / "shaders";
  fs::create_directories(shaders);
  for (const auto& e : fs::directory_iterator(GEOM_SHADER_DIR))
    if (e.path().filename().string().rfind("cube_distance", 0) != 0)
      fs::copy_file(e.path(), shaders / e.path().filename());
  const ViewerRun r =
      geomview(s, q(obj) + " " + viewertest::kSceneView + " --technique ssm,cube --size 64x48 --shaders " +
                      q(shaders.string()) + " -o " + q((s.dir / "out" / "deeper").string()));
  expect_refused(s, r, 1, "cube_distance", {"scene.obj", "shaders"});
}

// Sizes over what GL can draw or the memory can hold: refused before any work.
TEST_F(Hostile, SizesAreCheckedBeforeWork) {
  const ViewerRun grid = geomview(s, q(obj) + " --compare all --size 16384x16384 -o " + q(png), "timeout 60");
  expect_refused(s, grid, 1, "compare grid", {"scene.obj"});
  const ViewerRun big =
      geomview(s, q(obj) + " --size 16384x16384 --shadow-map-size 16 -o " + q(png), "ulimit -v 8000000; timeout 60");
  expect_refused(s, big, 1, "memory", {"scene.obj"});
}

// --script and --screenshot need a window: without one, an error, no file.
TEST_F(Hostile, ScriptWithoutAWindowIsAnError) {
  const ViewerRun a = geomview(s, q(obj) + " --window --script q --screenshot " + q(png), "env -u DISPLAY timeout 60");
  expect_refused(s, a, 1, "needs a window", {"scene.obj"});
  const ViewerRun b = geomview(s, q(obj) + " --script q -o " + q(png));
  expect_refused(s, b, 2, "--script", {"scene.obj"});
}

}  // namespace
