// geombake bake as a build step a studio can trust (docs/build-step.md), run
// as a child process on real files:
//   - inputs are never written: -r, --depfile, info -o and every output are
//     checked against every input and every file an input reads, however the
//     path is spelled (`..`, `./`, a symlink, a hard link), and against each
//     other, before any work: `Error:`, exit 2, nothing written;
//   - an unwritable folder of -r, --depfile or the outputs is refused before
//     any input is baked;
//   - no stale output: a failed input's earlier output is removed and its
//     depfile line still names what it read; --prune removes the .gbake files
//     no input of the run maps to, and nothing else;
//   - Make as well as Ninja: --depfile-target, warnings for names they
//     misread; the default -j from the CPU affinity; a directory walk bakes
//     the archives it finds; an OBJ without a face is an error; --list -.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "cli_run.h"
#include "geom/import.h"
#include "scratch.h"

namespace fs = std::filesystem;

namespace {

const std::string kData = GEOM_TEST_DATA;
const std::string kBox = kData + "/draco/Box/glTF/Box.gltf";

fs::path scratch(const std::string& tag) { return testfs::case_dir("geom_step", tag); }

void write(const fs::path& p, const std::string& text) { testfs::write_text(p, text); }

const char* kCube =
    "OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A file's bytes and modification time, to see that nothing touched it.
struct Snapshot {
  std::string bytes;
  struct timespec mtime {};
  explicit Snapshot(const fs::path& p) : bytes(cli::slurp(p)) {
    struct stat st {};
    ::stat(p.c_str(), &st);
    mtime = st.st_mtim;
  }
  bool operator==(const Snapshot& o) const {
    return bytes == o.bytes && mtime.tv_sec == o.mtime.tv_sec && mtime.tv_nsec == o.mtime.tv_nsec;
  }
};

// The Box glTF and its external buffer, copied to `dir`.
void copy_box(const fs::path& dir) {
  fs::copy_file(kBox, dir / "Box.gltf");
  fs::copy_file(kData + "/draco/Box/glTF/Box0.bin", dir / "Box0.bin");
}

}  // namespace

// Every way of naming an input as a file geombake writes is refused before
// any work: exit 2, an `Error:` line, the input's bytes and mtime untouched,
// no output made.
TEST(BuildStep, InputsAreNeverWritten) {
  const fs::path d = scratch("inputs");
  write(d / "a.off", kCube);
  write(d / "sub" / "b.off", kCube);
  copy_box(d);
  fs::create_directory_symlink(d / "sub", d / "linkdir");
  fs::create_symlink(d / "sub" / "b.off", d / "link.json");
  fs::create_hard_link(d / "sub" / "b.off", d / "hard.json");
  const std::string a = (d / "a.off").string(), b = (d / "sub" / "b.off").string();
  // Spellings of sub/b.off: as given, with `..` and `.`, through a symlinked
  // folder, a symlink to it, a hard link to it, relative to the working folder.
  const std::vector<std::string> spellings = {
      b,
      (d / "sub" / ".." / "sub" / "." / "b.off").string(),
      (d / "linkdir" / "b.off").string(),
      (d / "link.json").string(),
      (d / "hard.json").string(),
      (fs::relative(d / "sub", fs::current_path()) / ".." / "sub" / "b.off").string()};
  std::vector<std::vector<std::string>> cases;
  for (const std::string& s : spellings) {
    // b.off an input of the run.
    cases.push_back({"bake", a, b, "-o", (d / "out").string(), "-r", s});
    cases.push_back({"bake", a, b, "-o", (d / "out").string(), "--depfile", s});
    cases.push_back({"bake", b, "-o", s});
    cases.push_back({"info", a, b, "-o", s});
    if (s == (d / "hard.json").string()) continue;  // replacing a hard link's name leaves b.off's bytes alone
    // b.off a mesh file this run does not read: still never replaced.
    cases.push_back({"bake", a, "-o", (d / "out").string(), "-r", s});
    cases.push_back({"bake", a, "-o", (d / "out").string(), "--depfile", s});
    cases.push_back({"bake", a, "-o", s});
    cases.push_back({"info", a, "-o", s});
  }
  // A file a glTF input reads (its external buffer), and outputs that are each other.
  cases.push_back({"bake", (d / "Box.gltf").string(), "-o", (d / "out").string(), "-r", (d / "Box0.bin").string()});
  cases.push_back({"bake", (d / "Box.gltf").string(), "-o", (d / "Box0.bin").string()});
  cases.push_back({"info", (d / "Box.gltf").string(), "-o", (d / "Box0.bin").string()});
  cases.push_back({"bake", a, "-o", (d / "x.gbake").string(), "-r", (d / "x.gbake").string()});
  cases.push_back(
      {"bake", a, "-o", (d / "out").string(), "-r", (d / "r.txt").string(), "--depfile", (d / "." / "r.txt").string()});
  cases.push_back({"bake", a, "-o", (d / "out/").string(), "--depfile", (d / "out" / "a.off.gbake").string()});
  const Snapshot box(d / "Box0.bin"), before(d / "sub" / "b.off");
  for (const auto& args : cases) {
    std::string line;
    for (const std::string& s : args) line += s + " ";
    const cli::Run r = cli::run(args, d / "log", 60);
    EXPECT_EQ(r.exit_code, 2) << line << "\n" << cli::describe(r);
    EXPECT_TRUE(has(r.err, "Error: ") && has(r.err, "refused")) << line << "\n" << r.err;
    EXPECT_TRUE(Snapshot(d / "sub" / "b.off") == before) << line;
    EXPECT_TRUE(Snapshot(d / "Box0.bin") == box) << line;
    EXPECT_FALSE(fs::exists(d / "out")) << line;
    EXPECT_FALSE(fs::exists(d / "x.gbake")) << line;
    EXPECT_FALSE(fs::exists(d / "r.txt")) << line;
    EXPECT_TRUE(r.out.empty()) << line << "\n" << r.out;
  }
}

// An unwritable folder of -r, --depfile or -o FILE is refused before any
// input is read: exit 2, no output.
TEST(BuildStep, UnwritableFoldersRefusedFirst) {
  const fs::path d = scratch("folders");
  write(d / "a.off", kCube);
  write(d / "file.txt", "not a folder\n");
  const std::string a = (d / "a.off").string(), out = (d / "out").string();
  const std::vector<std::vector<std::string>> cases = {
      {"bake", a, "-o", out + "/", "-r", (d / "missing" / "r.json").string()},
      {"bake", a, "-o", out + "/", "--depfile", (d / "file.txt" / "a.d").string()},
      {"bake", a, "-o", out + "/", "-r", "/proc/geombake-report.json"},
      {"bake", a, "-o", out + "/", "--depfile", "/proc/self/geombake.d"},
      {"bake", a, "-o", "/proc/a.gbake"},
      {"bake", a, "-o", "/proc/baked/"},
  };
  for (const auto& args : cases) {
    const std::string line = args.back();
    const cli::Run r = cli::run(args, d / "log", 60);
    EXPECT_EQ(r.exit_code, 2) << line << "\n" << cli::describe(r);
    EXPECT_TRUE(has(r.err, "Error: ") && has(r.err, "nothing baked")) << line << "\n" << r.err;
    EXPECT_FALSE(fs::exists(d / "out")) << line;
  }
}

// A failed input leaves no output of an earlier run, and its depfile line
// still names what it read, so Make and Ninja retry it; the other inputs'
// outputs stay. Over random corruptions of a glTF's external buffer and of an
// OFF file.
TEST(BuildStep, FailedInputLeavesNoStaleOutput) {
  const fs::path d = scratch("stale");
  copy_box(d);
  write(d / "cube.off", kCube);
  write(d / "other.off", kCube);
  const std::string bin = cli::slurp(d / "Box0.bin");
  std::mt19937 rng(7);
  for (int round = 0; round < 12; ++round) {
    write(d / "Box0.bin", bin);
    write(d / "cube.off", kCube);
    const std::vector<std::string> args = {"bake",
                                           (d / "Box.gltf").string(),
                                           (d / "cube.off").string(),
                                           (d / "other.off").string(),
                                           "-o",
                                           (d / "out").string(),
                                           "--depfile",
                                           (d / "out.d").string(),
                                           "-j",
                                           "2"};
    cli::Run r = cli::run(args, d / "log", 60);
    ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
    ASSERT_TRUE(fs::exists(d / "out" / "Box.gltf.gbake"));
    // Truncate the buffer, or break the OFF's face count, at a random place.
    const bool gltf = round % 2 == 0;
    if (gltf)
      write(d / "Box0.bin", bin.substr(0, std::uniform_int_distribution<size_t>(0, bin.size() - 1)(rng)));
    else
      write(d / "cube.off", std::string(kCube).substr(0, std::uniform_int_distribution<size_t>(4, 60)(rng)));
    r = cli::run(args, d / "log", 60);
    EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
    const std::string failed = gltf ? "Box.gltf.gbake" : "cube.off.gbake";
    EXPECT_FALSE(fs::exists(d / "out" / failed)) << "round " << round << ": a stale output stays\n" << r.err;
    EXPECT_TRUE(fs::exists(d / "out" / "other.off.gbake"));
    EXPECT_TRUE(fs::exists(d / "out" / (gltf ? "cube.off.gbake" : "Box.gltf.gbake")));
    const std::string dep = cli::slurp(d / "out.d");
    if (gltf)
      EXPECT_TRUE(has(dep, (d / "out" / failed).string() + ": " + (d / "Box.gltf").string() + " " +
                               (d / "Box0.bin").string() + "\n"))
          << dep;
    else
      EXPECT_TRUE(has(dep, (d / "out" / failed).string() + ": " + (d / "cube.off").string() + "\n")) << dep;
    EXPECT_TRUE(has(dep, (d / "out" / "other.off.gbake").string() + ": ")) << dep;
  }
}

// --prune removes the .gbake files under -o DIR that no input of this run maps
// to (an input deleted since), and nothing else: not other files, not outputs
// of inputs that failed this time (already removed), not without --prune.
TEST(BuildStep, PruneRemovesOnlyUnclaimedOutputs) {
  const fs::path d = scratch("prune");
  for (const char* n : {"a.off", "b.off", "deep/c.off", "deep/er/d.off"}) write(d / "in" / n, kCube);
  const std::string in = (d / "in").string(), out = (d / "out").string();
  ASSERT_EQ(cli::run({"bake", in, "-o", out}, d / "log").exit_code, 0);
  write(d / "out" / "notes.txt", "kept\n");
  write(d / "out" / "deep" / "keep.gbake.txt", "kept\n");
  fs::remove(d / "in" / "b.off");
  fs::remove(d / "in" / "deep" / "er" / "d.off");
  cli::Run r = cli::run({"bake", in, "-o", out}, d / "log");
  ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_TRUE(fs::exists(d / "out" / "b.off.gbake"));  // opt-in only
  r = cli::run({"bake", in, "-o", out, "--prune", "-r", (d / "r.json").string()}, d / "log");
  ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_FALSE(fs::exists(d / "out" / "b.off.gbake"));
  EXPECT_FALSE(fs::exists(d / "out" / "deep" / "er" / "d.off.gbake"));
  for (const char* kept : {"a.off.gbake", "deep/c.off.gbake", "notes.txt", "deep/keep.gbake.txt"})
    EXPECT_TRUE(fs::exists(d / "out" / kept)) << kept;
  EXPECT_TRUE(has(cli::slurp(d / "r.json"), "/out/b.off.gbake")) << cli::slurp(d / "r.json");
}

// --depfile-target NAME (gcc's -MT): one rule, NAME: every file read, each
// once, failed inputs included (a stamp file then carries a glTF's .bin).
TEST(BuildStep, DepfileTarget) {
  const fs::path d = scratch("mt");
  copy_box(d);
  write(d / "cube.off", kCube);
  write(d / "bad.off", "OFF\n");
  const std::string stamp = (d / "assets stamp").string();
  const cli::Run r = cli::run({"bake", (d / "Box.gltf").string(), (d / "cube.off").string(), (d / "bad.off").string(),
                               (d / "cube.off").string(), "-o", (d / "out").string(), "--depfile", (d / "x.d").string(),
                               "--depfile-target", stamp},
                              d / "log");
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  const std::string dir = d.string();
  EXPECT_EQ(cli::slurp(d / "x.d"), dir + "/assets\\ stamp: " + dir + "/Box.gltf " + dir + "/Box0.bin " + dir +
                                       "/cube.off " + dir + "/bad.off\n");
  // Without --depfile it names nothing: a usage error.
  EXPECT_EQ(
      cli::run({"bake", (d / "cube.off").string(), "-o", (d / "c.gbake").string(), "--depfile-target", "s"}, d / "log")
          .exit_code,
      2);
}

// Names that Make or Ninja misread in a depfile get a warning naming who
// misreads them; the bake still succeeds and the depfile is written.
TEST(BuildStep, DepfileNameWarnings) {
  const fs::path d = scratch("hazard");
  const std::vector<std::pair<std::string, std::string>> names = {{"a:b.off", "':', which Make"},
                                                                  {"c;d.off", "';', which Make"},
                                                                  {"e%f.off", "'%', which Make"},
                                                                  {"g\th.off", "a tab, which Make and Ninja"}};
  std::vector<std::string> args = {"bake", "-o", (d / "out").string(), "--depfile", (d / "x.d").string()};
  for (const auto& [name, why] : names) {
    write(d / name, kCube);
    args.push_back((d / name).string());
  }
  write(d / "plain.off", kCube);
  args.push_back((d / "plain.off").string());
  const cli::Run r = cli::run(args, d / "log");
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  for (const auto& [name, why] : names) {
    EXPECT_TRUE(has(r.err, "Warning: --depfile: the name " + (d / name).string() + " holds " + why)) << r.err;
    EXPECT_TRUE(fs::exists(d / "out" / (name + ".gbake"))) << name;
  }
  EXPECT_FALSE(has(r.err, "plain.off holds")) << r.err;
  EXPECT_TRUE(has(cli::slurp(d / "x.d"), (d / "plain.off").string())) << cli::slurp(d / "x.d");
}

// The default -j is the CPUs the process may use: under `taskset -c 0`, one.
TEST(BuildStep, DefaultThreadsFollowAffinity) {
  const fs::path d = scratch("affinity");
  for (int i = 0; i < 4; ++i) write(d / "in" / ("m" + std::to_string(i) + ".off"), kCube);
  const std::string cmd = "taskset -c 0 '" + cli::geombake_path() + "' bake '" + (d / "in").string() + "' -o '" +
                          (d / "out").string() + "' 2>'" + (d / "err.txt").string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_TRUE(has(cli::slurp(d / "err.txt"), " with 1 thread\n")) << cli::slurp(d / "err.txt");
  const cli::Run r = cli::run({"bake", (d / "in").string(), "-o", (d / "out").string(), "-j", "3"}, d / "log");
  EXPECT_TRUE(has(r.err, " with 3 threads\n")) << r.err;
}

// A directory walk bakes a .pk3 it finds as a .pk3 argument is baked: each
// map, under the archive's path in the tree.
TEST(BuildStep, DirectoryWalkBakesArchives) {
  const fs::path d = scratch("pk3");
  std::vector<unsigned char> map;
  std::string error;
  ASSERT_TRUE(
      geom::read_archive_member("/usr/share/games/openarena/baseoa/pak1-maps.pk3", "maps/oa_ctf2.bsp", map, 0, error))
      << error;
  fs::create_directories(d / "in" / "sub");
  int err = 0;
  zip_t* z = zip_open((d / "in" / "sub" / "maps.pk3").c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(z, nullptr);
  ASSERT_GE(zip_file_add(z, "maps/small.bsp", zip_source_buffer(z, map.data(), map.size(), 0), 0), 0);
  ASSERT_EQ(zip_close(z), 0);
  write(d / "in" / "cube.off", kCube);
  const cli::Run r = cli::run({"bake", (d / "in").string(), "-o", (d / "out").string()}, d / "log", 120);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_FALSE(has(r.err, "no mesh format skipped")) << r.err;  // the archive is not skipped
  EXPECT_TRUE(fs::exists(d / "out" / "cube.off.gbake"));
  EXPECT_TRUE(fs::exists(d / "out" / "sub" / "maps.pk3" / "maps" / "small.bsp.gbake")) << r.err;
  const cli::Run i = cli::run({"info", (d / "in").string()}, d / "log", 120);
  EXPECT_EQ(i.exit_code, 0) << cli::describe(i);
  EXPECT_TRUE(has(i.out, "maps.pk3:maps/small.bsp")) << i.out;
}

// An input without a face (an empty OBJ, one of vertices or lines only) is an
// error of the bake, as an empty OFF, PLY or STL is: nothing to bake.
TEST(BuildStep, ObjWithoutFaceIsAnError) {
  const fs::path d = scratch("obj");
  const std::vector<std::string> texts = {"", "# nothing\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "v 0 0 0\nv 1 0 0\nl 1 2\n",
                                          "v 0 0 0\nv 1 0 0\nf 1 2\n"};
  for (size_t k = 0; k < texts.size(); ++k) {
    const fs::path p = d / ("m" + std::to_string(k) + ".obj");
    write(p, texts[k]);
    const cli::Run r = cli::run({"bake", p.string(), "-o", (d / "x.gbake").string()}, d / "log");
    EXPECT_EQ(r.exit_code, 1) << k << ": " << cli::describe(r);
    EXPECT_TRUE(has(r.err, "Error: " + p.string() + ": no face")) << r.err;
    EXPECT_FALSE(fs::exists(d / "x.gbake"));
  }
  for (const char* other : {"e.off", "e.ply", "e.stl"}) {
    write(d / other, "");
    EXPECT_EQ(cli::run({"bake", (d / other).string(), "-o", (d / "x.gbake").string()}, d / "log").exit_code, 1);
  }
}

// --list - reads the inputs from standard input.
TEST(BuildStep, ListFromStandardInput) {
  const fs::path d = scratch("stdin");
  write(d / "a.off", kCube);
  write(d / "b.off", kCube);
  const std::string cmd = "printf '" + (d / "a.off").string() + "\\n# a comment\\n\\n" + (d / "b.off").string() +
                          "\\n' | '" + cli::geombake_path() + "' bake --list - -o '" + (d / "out").string() +
                          "' 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(cli::listing(d / "out"), (std::vector<std::string>{"a.off.gbake", "b.off.gbake"}));
}
