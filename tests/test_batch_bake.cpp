// Batch baking with the geombake CLI, run as a child
// process on real files of every format:
//   - outputs are byte-identical across runs and thread counts (-j 1, -j 2, -j 3),
//     and so is the --json report on stdout;
//   - a failing input among good ones: its `Error: FILE: ` line, no output for
//     it, the others baked, exit status 1, and the summary counts both;
//   - inputs from a list file (--list) and from a directory;
//   - the depfile: one `OUTPUT: DEPENDENCIES` rule per baked input, with a
//     glTF's external buffers and an archive member's archive, and real Ninja
//     and Make builds that rebake exactly when a dependency changes;
//   - the progress display: on stderr when it is a terminal (run under a
//     pseudo-terminal here), none when it is not;
//   - the limits: --max-triangles, --max-memory, --timeout, each refusing the
//     input concerned with a message naming the limit while the others bake.
#include <gtest/gtest.h>

#include <pty.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "fuzz_import.h"
#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

const std::string kData = GEOM_TEST_DATA;
const std::string kAssimp = "/usr/share/assimp/models";
const std::string kMaps = "/usr/share/games/openarena/baseoa/pak1-maps.pk3";
const std::string kPlayers = "/usr/share/games/openarena/baseoa/pak2-players.pk3";

// This process's scratch folder is removed when the process ends.
struct ScratchCleanup {
  ~ScratchCleanup() {
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("geom_batch_" + std::to_string(::getpid())), ec);
  }
} scratch_cleanup;

fs::path scratch(const std::string& tag) {
  static const fs::path root = [] {
    fs::path d = fs::temp_directory_path() / ("geom_batch_" + std::to_string(::getpid()));
    fs::remove_all(d);
    return d;
  }();
  fs::path d = root / tag;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Real inputs of every format (and both glTF containers, Draco, an external
// buffer, an archive member).
std::vector<std::string> real_inputs() {
  return {kData + "/draco/cube_att.obj",
          kData + "/draco/test_nm.obj",
          kData + "/draco/Box.ply",
          kAssimp + "/OFF/Wuson.off",
          kAssimp + "/STL/Spider_binary.stl",
          kAssimp + "/STL/Spider_ascii.stl",
          kData + "/draco/Box/glTF_Binary/Box_Draco.glb",
          kData + "/draco/Duck/glTF/Duck.gltf",
          kAssimp + "/glTF2/BoxTextured-glTF/BoxTextured.gltf",
          kPlayers + ":models/players/gargoyle/head.md3",
          kMaps + ":maps/oa_ctf2.bsp"};
}

std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> m;
  for (const std::string& name : cli::listing(dir)) m[name] = cli::slurp(dir / name);
  return m;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(BatchBake, ByteIdenticalAcrossRunsAndThreadCounts) {
  const std::vector<std::string> inputs = real_inputs();
  std::map<std::string, std::string> first;
  std::string first_json;
  for (const char* j : {"1", "2", "3", "2"}) {
    static int run = 0;
    fs::path work = scratch("det" + std::to_string(run++));
    // --stable-report: without the per-input seconds, which no two runs share.
    std::vector<std::string> args = {"bake", "-j", j, "--json", "--stable-report", "-o", (work / "out").string()};
    args.insert(args.end(), inputs.begin(), inputs.end());
    cli::Run r = cli::run(args, work / "log", 300);
    ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
    EXPECT_FALSE(cli::sanitizer_report(r.err));
    // The report names the output paths: compare it with this run's folder named WORK.
    std::string json = r.out;
    for (size_t at; (at = json.find(work.string())) != std::string::npos;) json.replace(at, work.string().size(), "WORK");
    std::map<std::string, std::string> now = contents(work / "out");
    ASSERT_EQ(now.size(), inputs.size()) << "-j " << j;
    for (const auto& [name, bytes] : now) EXPECT_GT(bytes.size(), 64u) << name;
    if (first.empty()) {
      first = now;
      first_json = json;
      continue;
    }
    for (const auto& [name, bytes] : first) EXPECT_TRUE(now[name] == bytes) << name << " differs at -j " << j;
    EXPECT_TRUE(json == first_json) << "--json report differs at -j " << j;
  }
  EXPECT_EQ(count_of(first_json, "\"ok\":true"), inputs.size());
}

// A failing input among good ones: the others are baked, exit status 1.
TEST(BatchBake, FailingInputsAmongGoodOnes) {
  fs::path work = scratch("failing");
  const std::string nan_obj = (work / "nan.obj").string(), missing = (work / "missing.ply").string();
  std::ofstream(nan_obj) << "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n";
  const std::string good1 = kData + "/draco/cube_att.obj", good2 = kAssimp + "/OFF/Wuson.off";
  cli::Run r = cli::run({"bake", good1, nan_obj, good2, missing, "-j", "2", "-o", (work / "out").string()},
                        work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Error: " + nan_obj + ": "), std::string::npos);
  EXPECT_NE(r.err.find("Error: " + missing + ": cannot open"), std::string::npos);
  EXPECT_EQ(count_of(r.err, "Error: "), 2u);
  EXPECT_EQ(cli::listing(work / "out"), (std::vector<std::string>{"Wuson.off.gbake", "cube_att.obj.gbake"}));
  // The summary: baked and failed counts, on the last line of stderr.
  EXPECT_NE(r.err.find("2 baked, 2 failed of 4 inputs"), std::string::npos);
  // Not a terminal here: no progress display.
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  EXPECT_EQ(r.err.find("\033["), std::string::npos);
}

// Inputs from a list file (blank lines and # comments skipped) and a directory.
TEST(BatchBake, ListFileAndDirectory) {
  fs::path work = scratch("list");
  fs::create_directories(work / "dir");
  fs::copy_file(kData + "/draco/cube_att.obj", work / "dir" / "a.obj");
  fs::copy_file(kData + "/draco/Box.ply", work / "dir" / "b.ply");
  std::ofstream(work / "dir" / "notes.txt") << "not a mesh\n";
  std::ofstream(work / "list.txt") << "# inputs\n" << kAssimp + "/OFF/Cube.off\n\n  " << kData + "/draco/test_nm.obj  \n";
  cli::Run r = cli::run({"bake", "--list", (work / "list.txt").string(), (work / "dir").string(), "-o",
                         (work / "out").string()},
                        work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(cli::listing(work / "out"),
            (std::vector<std::string>{"Cube.off.gbake", "a.obj.gbake", "b.ply.gbake", "test_nm.obj.gbake"}));
  EXPECT_NE(r.err.find("4 baked, 0 failed of 4 inputs"), std::string::npos);
  // An unreadable list file is a usage error naming it.
  r = cli::run({"bake", "--list", (work / "nope.txt").string(), "-o", (work / "out2").string()}, work / "log2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("Error: " + (work / "nope.txt").string() + ": "), std::string::npos) << r.err;
}

// The depfile names, for each output, the files it was made from.
TEST(BatchBake, DepfileContent) {
  fs::path work = scratch("depfile");
  const std::string gltf = kAssimp + "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  const std::string bin = kAssimp + "/glTF2/BoxTextured-glTF/BoxTextured0.bin";
  const std::string member = kPlayers + ":models/players/gargoyle/head.md3";
  fs::create_directories(work / "in dir");
  fs::copy_file(kData + "/draco/cube_att.obj", work / "in dir" / "a b.obj");
  const std::string spaced = (work / "in dir" / "a b.obj").string();
  const std::string out = (work / "out").string(), dep = (work / "bake.d").string();
  cli::Run r = cli::run({"bake", gltf, member, spaced, "-o", out, "--depfile", dep}, work / "log");
  ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
  const std::string d = cli::slurp(dep);
  auto esc = [](std::string s) {
    std::string o;
    for (char c : s) o += c == ' ' ? std::string("\\ ") : std::string(1, c);
    return o;
  };
  EXPECT_NE(d.find(out + "/BoxTextured.gltf.gbake: " + gltf + " " + bin + "\n"), std::string::npos) << d;
  EXPECT_NE(d.find(out + "/head.md3.gbake: " + kPlayers + "\n"), std::string::npos) << d;
  EXPECT_NE(d.find(out + "/a\\ b.obj.gbake: " + esc(spaced) + "\n"), std::string::npos) << d;
  EXPECT_EQ(count_of(d, "\n"), 3u) << d;
}

// Real build systems read the depfile: Ninja and Make rebake exactly when an
// input or a glTF's external buffer changes, and not otherwise.
TEST(BatchBake, NinjaAndMakeRebuildFromTheDepfile) {
  fs::path work = scratch("buildsys");
  fs::create_directories(work / "src");
  for (const char* f : {"BoxTextured.gltf", "BoxTextured0.bin"})
    fs::copy_file(kAssimp + "/glTF2/BoxTextured-glTF/" + f, work / "src" / f);
  const std::string geombake = cli::geombake_path();
  std::ofstream(work / "build.ninja") << "rule bake\n  command = " << geombake
                                      << " bake $in -o $out --depfile $out.d\n  depfile = $out.d\n  deps = gcc\n"
                                      << "build box.gbake: bake src/BoxTextured.gltf\n";
  std::ofstream(work / "Makefile") << "box_make.gbake: src/BoxTextured.gltf\n\t" << geombake
                                   << " bake $< -o $@ --depfile $@.d\n-include box_make.gbake.d\n";
  auto sh = [&](const std::string& cmd) {
    const std::string full = "cd '" + work.string() + "' && " + cmd + " > out.txt 2>&1";
    int rc = std::system(full.c_str());
    return std::make_pair(rc, cli::slurp(work / "out.txt"));
  };
  ASSERT_EQ(std::system("command -v ninja >/dev/null && command -v make >/dev/null"), 0) << "no ninja/make (scripts/setup.sh)";
  auto [rc, log] = sh("ninja && make");
  ASSERT_EQ(rc, 0) << log;
  ASSERT_TRUE(fs::exists(work / "box.gbake") && fs::exists(work / "box_make.gbake")) << log;
  std::tie(rc, log) = sh("ninja -n");
  EXPECT_NE(log.find("no work to do"), std::string::npos) << log;
  std::tie(rc, log) = sh("make -q");
  EXPECT_EQ(rc, 0) << "make thinks box_make.gbake is stale: " << log;
  // Touch the external buffer (one second later than everything else).
  const auto later = fs::last_write_time(work / "box.gbake") + std::chrono::seconds(2);
  fs::last_write_time(work / "src" / "BoxTextured0.bin", later);
  std::tie(rc, log) = sh("ninja -n");
  EXPECT_NE(log.find("[1/1]"), std::string::npos) << log;
  std::tie(rc, log) = sh("make -q");
  EXPECT_NE(rc, 0) << "make missed the changed buffer";
}

// The progress display appears on a terminal (a pseudo-terminal here).
TEST(BatchBake, ProgressOnATerminal) {
  fs::path work = scratch("pty");
  std::vector<std::string> args = {cli::geombake_path(), "bake", "-j", "2", "-o", (work / "out").string(),
                                   kData + "/draco/cube_att.obj", kData + "/draco/Box.ply", kAssimp + "/OFF/Cube.off"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int master = -1;
  pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::string seen;
  char buf[4096];
  for (;;) {
    ssize_t n = read(master, buf, sizeof buf);
    if (n <= 0) break;  // EIO once the child has closed the terminal
    seen.append(buf, size_t(n));
  }
  int status = 0;
  waitpid(pid, &status, 0);
  close(master);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << seen;
  EXPECT_NE(seen.find("[3/3]"), std::string::npos) << seen;
  EXPECT_NE(seen.find("\r\033[K"), std::string::npos) << seen;
  EXPECT_NE(seen.find("3 baked, 0 failed of 3 inputs"), std::string::npos) << seen;
}

// --max-triangles: inputs over it are refused, the others baked.
TEST(BatchBake, MaxTriangles) {
  fs::path work = scratch("maxtri");
  const std::string small = kData + "/draco/cube_att.obj", big = kAssimp + "/OFF/Wuson.off";
  cli::Run r = cli::run({"bake", small, big, "--max-triangles", "100", "-o", (work / "out").string()}, work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Error: " + big + ": "), std::string::npos);
  EXPECT_NE(r.err.find("over the limit of 100"), std::string::npos);
  EXPECT_EQ(cli::listing(work / "out"), std::vector<std::string>{"cube_att.obj.gbake"});
}

// --max-memory: the file, the import's claims and the bake's estimate must
// fit; the message gives the limit in bytes.
TEST(BatchBake, MaxMemory) {
  fs::path work = scratch("maxmem");
  const std::string small = kData + "/draco/cube_att.obj", big = kAssimp + "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  cli::Run r = cli::run({"bake", small, big, "--max-memory", "3M", "-o", (work / "out").string()}, work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Error: " + big + ": "), std::string::npos);
  EXPECT_NE(r.err.find("over the limit of 3145728"), std::string::npos);
  EXPECT_EQ(cli::listing(work / "out"), std::vector<std::string>{"cube_att.obj.gbake"});
  // A file over the limit by its size alone.
  r = cli::run({"bake", big, "--max-memory", "100K", "-o", (work / "one.gbake").string()}, work / "log2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("over the limit of 102400"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(work / "one.gbake"));
  // Enough memory: baked.
  r = cli::run({"bake", big, "--max-memory", "1G", "-o", (work / "two.gbake").string()}, work / "log3");
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  // Malformed values are usage errors.
  for (const char* bad : {"-1", "12Q", "", "1e3", "0", "999999999999999G", "5MB"}) {
    r = cli::run({"bake", small, "--max-memory", bad, "-o", (work / "x.gbake").string()}, work / "log4");
    EXPECT_EQ(r.exit_code, 2) << bad;
  }
}

// --max-memory counts the casters' hull (about 96 bytes per vertex: copies of
// the positions and CGAL's working memory) beside the per-triangle cost. A
// mesh of 2 triangles and 80,000 vertices is refused by the estimate, at
// once and naming the hull, under a limit that --no-caster-hull (no hull
// made) bakes under.
TEST(BatchBake, MaxMemoryCountsTheCasterHull) {
  fs::path work = scratch("maxmem_hull");
  const fs::path mesh = work / "scattered.obj";
  {
    std::ofstream f(mesh);
    for (int i = 0; i < 80000; ++i) f << "v " << i % 211 << ' ' << i % 97 << ' ' << i << '\n';
    f << "f 1 2 3\nf 1 3 4\n";
  }
  cli::Run r = cli::run({"bake", mesh.string(), "--max-memory", "6M", "-o", (work / "a.gbake").string()}, work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Error: " + mesh.string() + ": baking 2 triangles and the hull of 80000 vertices needs about "),
            std::string::npos);
  EXPECT_NE(r.err.find("over the limit of 6291456 (--max-memory)"), std::string::npos);
  EXPECT_FALSE(fs::exists(work / "a.gbake"));
  r = cli::run({"bake", mesh.string(), "--no-caster-hull", "--max-memory", "6M", "-o", (work / "b.gbake").string()},
               work / "log2");
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_TRUE(fs::exists(work / "b.gbake"));
}

// --timeout: an input that takes longer is refused with a message naming the
// limit and leaves no output; the others are baked.
TEST(BatchBake, Timeout) {
  fs::path work = scratch("timeout");
  const std::string small = kData + "/draco/cube_att.obj";
  const std::string slow = kMaps + ":maps/oa_ctf2.bsp";  // ~100k triangles: far more than a millisecond
  cli::Run r = cli::run({"bake", small, slow, "--timeout", "0.001", "-j", "1", "-o", (work / "out").string()},
                        work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Error: " + slow + ": timed out after 0.001 s (--timeout)"), std::string::npos);
  const std::vector<std::string> left = cli::listing(work / "out");
  EXPECT_EQ(std::count(left.begin(), left.end(), "oa_ctf2.bsp.gbake"), 0);
  // A generous limit bakes both.
  r = cli::run({"bake", small, slow, "--timeout", "300", "-o", (work / "out2").string()}, work / "log2");
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_EQ(cli::listing(work / "out2"), (std::vector<std::string>{"cube_att.obj.gbake", "oa_ctf2.bsp.gbake"}));
}

// A CPU bomb found by fuzz/fuzz_draco: 393 bytes whose texture-coordinate
// prediction data claims 1.3 billion orientations, which Debian's libdraco looped
// over for about 30 s. libgeom/src/draco_guard.cpp bounds the count by the
// corners, so the bake refuses it at once, with no --timeout, naming the count,
// while the other input is baked.
TEST(BatchBake, DracoBombIsRefusedAtOnce) {
  fs::path work = scratch("bomb");
  const std::string drc =
      cli::slurp(fs::path(GEOM_SOURCE_DIR) / "tests/fuzz_regressions/draco/texcoord_orientations.drc");
  ASSERT_EQ(drc.size(), 393u);
  const std::vector<uint8_t> glb = geom_fuzz::draco_glb(reinterpret_cast<const uint8_t*>(drc.data()), drc.size());
  const std::string bomb = (work / "bomb.glb").string(), good = kData + "/draco/cube_att.obj";
  std::ofstream(bomb, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
  cli::Run r = cli::run({"bake", bomb, good, "-j", "2", "-o", (work / "out").string()}, work / "log");
  SCOPED_TRACE(cli::describe(r));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Error: " + bomb +
                       ": mesh 0 primitive 0: Draco data in bufferView 0 cannot be decoded: "
                       "its texture-coordinate prediction claims 1329807698 orientations for 36 corners"),
            std::string::npos);
  EXPECT_EQ(cli::listing(work / "out"), std::vector<std::string>{"cube_att.obj.gbake"});
  EXPECT_LT(r.cpu_seconds, 1.0 * cli::kSanitizerFactor);
}
