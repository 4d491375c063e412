// geombake bake as a build step, run as a child process on real files:
//   - trees: a directory walks recursively, outputs mirror it under -o DIR with
//     the input's extension kept (equal base names in two folders, pig.off and
//     pig.stl side by side never collide), a symlink loop and what else is
//     skipped said in warnings, -o a folder whenever the input is one;
//   - hermetic bytes: one file baked through three spellings of its path from
//     two working directories gives the same bytes, with no path of the machine;
//   - manners: -jN as -j N, --version, -q, warnings as each input finishes, the
//     progress line cut to the terminal's width (under a pseudo-terminal), an
//     unchanged output left untouched unless --force, the -r report of the run.
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"
#include "geom/version.h"
#include "scratch.h"

namespace fs = std::filesystem;

namespace {

const std::string kData = GEOM_TEST_DATA;
const std::string kAssimp = "/usr/share/assimp/models";

fs::path scratch(const std::string& tag) { return testfs::case_dir("geom_tree", tag); }

void copy(const std::string& from, const fs::path& to) {
  fs::create_directories(to.parent_path());
  fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

// Every file under `dir`, as paths relative to it, sorted.
std::vector<std::string> tree(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(fs::relative(e.path(), dir).generic_string());
  std::sort(files.begin(), files.end());
  return files;
}

// `cd DIR && geombake ARGS` through the shell; the exit status.
int geombake_in(const fs::path& dir, const std::string& args) {
  const std::string cmd = "cd '" + dir.string() + "' && '" + cli::geombake_path() + "' " + args + " 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// geombake ARGS on a pseudo-terminal `columns` wide: everything it wrote there.
std::string on_terminal(std::vector<std::string> args, unsigned short columns, int& status) {
  args.insert(args.begin(), cli::geombake_path());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  winsize ws{};
  ws.ws_col = columns;
  ws.ws_row = 24;
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, &ws);
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::string seen;
  char buf[4096];
  for (ssize_t n; pid > 0 && (n = read(master, buf, sizeof buf)) > 0;) seen.append(buf, size_t(n));
  status = -1;
  if (pid > 0) waitpid(pid, &status, 0), close(master);
  return seen;
}

}  // namespace

TEST(BakeTree, DirectoryWalksRecursivelyAndOutputsMirrorIt) {
  const fs::path work = scratch("mirror"), in = work / "in";
  copy(kAssimp + "/OFF/Cube.off", in / "a" / "pig.off");
  copy(kAssimp + "/OFF/Wuson.off", in / "b" / "deep" / "pig.off");  // equal base name, another folder
  copy(kAssimp + "/STL/Spider_ascii.stl", in / "a" / "pig.stl");    // equal stem, another format
  copy(kData + "/draco/Duck/glTF/Duck.gltf", in / "duck" / "Duck.gltf");
  copy(kData + "/draco/Duck/glTF/Duck0.bin", in / "duck" / "Duck0.bin");
  std::ofstream(in / "duck" / "notes.txt") << "not a mesh\n";
  fs::create_directory_symlink("..", in / "b" / "loop");  // in/b/loop -> in: a cycle
  cli::Run r = cli::run({"bake", in.string(), "-o", (work / "out").string(), "-j2"}, work / "log");
  SCOPED_TRACE(cli::describe(r));
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(tree(work / "out"), (std::vector<std::string>{"a/pig.off.gbake", "a/pig.stl.gbake", "b/deep/pig.off.gbake",
                                                          "duck/Duck.gltf.gbake"}));
  EXPECT_NE(r.err.find("Warning: " + (in / "b" / "loop").string() + ": a directory already walked"), std::string::npos);
  EXPECT_NE(r.err.find("Warning: " + in.string() + ": 2 files of no mesh format skipped (1 .bin, 1 .txt)"),
            std::string::npos);
  EXPECT_NE(r.err.find("4 baked, 0 failed of 4 inputs"), std::string::npos);
  // Outputs are those of the files baked alone.
  const std::string alone = (work / "alone.gbake").string();
  ASSERT_EQ(cli::run({"bake", (in / "b" / "deep" / "pig.off").string(), "-o", alone}, work / "log2").exit_code, 0);
  EXPECT_NE(cli::slurp(alone), cli::slurp(work / "out" / "a" / "pig.off.gbake"));
  // A file named alone stores its base name, a file found in a tree its path there.
  EXPECT_NE(cli::slurp(work / "out" / "b" / "deep" / "pig.off.gbake").find("b/deep/pig.off"), std::string::npos);
  EXPECT_NE(cli::slurp(alone).find("\"pig.off\""), std::string::npos);
  // geombake info walks a directory the same way.
  cli::Run info = cli::run({"info", "--json", in.string()}, work / "log3");
  EXPECT_EQ(info.exit_code, 0) << cli::describe(info);
  EXPECT_EQ(std::count(info.out.begin(), info.out.end(), '\n'), 4) << info.out;
  EXPECT_NE(info.out.find((in / "b" / "deep" / "pig.off").string()), std::string::npos) << info.out;
}

TEST(BakeTree, OutputIsAFolderWheneverTheInputIsOne) {
  const fs::path work = scratch("folder");
  copy(kData + "/draco/cube_att.obj", work / "one" / "cube.obj");
  cli::Run r = cli::run({"bake", (work / "one").string(), "-o", (work / "out").string()}, work / "log");
  ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
  ASSERT_TRUE(fs::is_directory(work / "out"));
  EXPECT_EQ(tree(work / "out"), std::vector<std::string>{"cube.obj.gbake"});
  // Several inputs: a folder too, relative paths mirrored; a directory of no mesh is an error.
  fs::create_directories(work / "empty");
  EXPECT_EQ(geombake_in(work, "bake one/cube.obj ./one/../one/cube.obj -o out2"), 1);  // same output twice
  EXPECT_EQ(geombake_in(work, "bake one/cube.obj -o out3/"), 0);
  EXPECT_EQ(tree(work / "out3"), std::vector<std::string>{"one/cube.obj.gbake"});
  r = cli::run({"bake", (work / "empty").string(), "-o", (work / "out4").string()}, work / "log2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("Error: no input file (no mesh file in the inputs given)"), std::string::npos) << r.err;
}

// An output depends only on the input's bytes and the flags.
TEST(BakeTree, HermeticBytesWhateverThePathSpelling) {
  const fs::path work = scratch("hermetic"), data = work / "data", other = work / "elsewhere";
  copy(kData + "/draco/Duck/glTF/Duck.gltf", data / "duck.gltf");
  copy(kData + "/draco/Duck/glTF/Duck0.bin", data / "Duck0.bin");
  copy(kAssimp + "/STL/Spider_ascii.stl", data / "spider.stl");  // warnings stored in its report
  fs::create_directories(other);
  for (const std::string file : {"duck.gltf", "spider.stl"}) {
    SCOPED_TRACE(file);
    const std::string abs = (data / file).string();
    struct Way {
      fs::path cwd;
      std::string path;
    };
    const std::vector<Way> ways = {
        {work, "data/" + file},     {work, abs}, {work, "./data/" + file}, {data, file}, {data, "./" + file},
        {other, "../data/" + file}, {other, abs}};
    std::string first;
    for (size_t i = 0; i < ways.size(); ++i) {
      const std::string out = (work / ("o" + std::to_string(i) + ".gbake")).string();
      ASSERT_EQ(geombake_in(ways[i].cwd, "bake '" + ways[i].path + "' --light 1,2,3,1 -o '" + out + "'"), 0)
          << ways[i].cwd << " " << ways[i].path;
      const std::string bytes = cli::slurp(out);
      ASSERT_GT(bytes.size(), 64u);
      EXPECT_EQ(bytes.find(work.string()), std::string::npos) << "an absolute path in the output";
      if (i == 0) first = bytes;
      EXPECT_TRUE(bytes == first) << "from " << ways[i].cwd << " as " << ways[i].path;
    }
  }
}

TEST(BakeTree, JobsVersionAndQuiet) {
  const fs::path work = scratch("manners");
  const std::string spider = kAssimp + "/STL/Spider_ascii.stl", cube = kData + "/draco/cube_att.obj";
  cli::Run a = cli::run({"bake", "-j2", spider, cube, "-o", (work / "a").string()}, work / "log1");
  cli::Run b = cli::run({"bake", "-j", "2", spider, cube, "-o", (work / "b").string()}, work / "log2");
  ASSERT_EQ(a.exit_code, 0) << cli::describe(a);
  ASSERT_EQ(b.exit_code, 0) << cli::describe(b);
  EXPECT_NE(a.err.find("with 2 threads"), std::string::npos) << a.err;
  EXPECT_EQ(cli::slurp(work / "a" / "Spider_ascii.stl.gbake"), cli::slurp(work / "b" / "Spider_ascii.stl.gbake"));
  EXPECT_EQ(cli::run({"bake", "-jx", cube, "-o", (work / "c").string()}, work / "log3").exit_code, 2);
  // --version, and the version in the usage banner.
  cli::Run v = cli::run({"--version"}, work / "log4");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out, std::string("geombake ") + GEOM_VERSION + "\n");
  cli::Run usage = cli::run({}, work / "log5");
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(usage.err.rfind(std::string("geombake ") + GEOM_VERSION + "\n", 0), 0u) << usage.err;
  // -q: errors only. The spider warns (collapsed triangles); a missing file is an error.
  EXPECT_NE(a.err.find("Warning: " + spider + ": "), std::string::npos) << a.err;
  for (const char* q : {"-q", "--quiet"}) {
    cli::Run quiet =
        cli::run({"bake", q, spider, (work / "missing.obj").string(), "-o", (work / "q").string()}, work / "log6");
    EXPECT_EQ(quiet.exit_code, 1);
    EXPECT_EQ(quiet.err.rfind("Error: " + (work / "missing.obj").string() + ": cannot open", 0), 0u) << quiet.err;
    EXPECT_EQ(std::count(quiet.err.begin(), quiet.err.end(), '\n'), 1) << quiet.err;
    EXPECT_TRUE(fs::exists(work / "q" / "Spider_ascii.stl.gbake"));
  }
}

// On a terminal: a warning shows when its input is done, before the next one
// ends; every progress line fits the terminal's 40 columns.
TEST(BakeTree, WarningsAsTheyHappenAndProgressCutToTheTerminal) {
  const fs::path work = scratch("pty");
  const fs::path deep = work / "a folder with a long name that a 40-column terminal cannot show";
  copy(kAssimp + "/STL/Spider_ascii.stl", deep / "spider.stl");
  copy(kAssimp + "/OFF/Wuson.off", deep / "wuson.off");
  int status = 0;
  const std::string seen = on_terminal(
      {"bake", "-j", "1", (deep / "spider.stl").string(), (deep / "wuson.off").string(), "-o", (work / "out").string()},
      40, status);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << seen;
  const size_t warning = seen.find("Warning: " + (deep / "spider.stl").string());
  const size_t second = seen.find("[2/2]");
  ASSERT_NE(warning, std::string::npos) << seen;
  ASSERT_NE(second, std::string::npos) << seen;
  EXPECT_LT(warning, second) << "the warning waited for the end of the run:\n" << seen;
  size_t lines = 0;
  for (size_t at = 0; (at = seen.find('[', at)) != std::string::npos; ++at) {
    const size_t end = seen.find_first_of("\r\n", at);
    const std::string line = seen.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (line.size() < 2 || !std::isdigit(static_cast<unsigned char>(line[1]))) continue;
    ++lines;
    EXPECT_LT(line.size(), 40u) << line;
    EXPECT_NE(line.find("..."), std::string::npos) << line;
  }
  EXPECT_EQ(lines, 2u) << seen;
}

TEST(BakeTree, UnchangedOutputsKeepTheirMtimeUnlessForced) {
  const fs::path work = scratch("mtime");
  const std::string cube = kData + "/draco/cube_att.obj";
  const fs::path out = work / "cube.gbake";
  ASSERT_EQ(cli::run({"bake", cube, "-o", out.string()}, work / "log").exit_code, 0);
  const auto old = fs::last_write_time(out) - std::chrono::hours(1);
  fs::last_write_time(out, old);
  cli::Run again = cli::run({"bake", cube, "-o", out.string(), "-v"}, work / "log");
  ASSERT_EQ(again.exit_code, 0);
  EXPECT_TRUE(fs::last_write_time(out) == old) << "rewritten though its bytes are the same";
  EXPECT_NE(again.out.find("(unchanged, left untouched)"), std::string::npos) << again.out;
  EXPECT_EQ(cli::run({"bake", cube, "-o", out.string(), "--force"}, work / "log").exit_code, 0);
  EXPECT_TRUE(fs::last_write_time(out) > old) << "--force left it";
  // Other flags, other bytes: rewritten.
  fs::last_write_time(out, old);
  const std::string before = cli::slurp(out);
  EXPECT_EQ(cli::run({"bake", cube, "-o", out.string(), "--no-esm"}, work / "log").exit_code, 0);
  EXPECT_TRUE(fs::last_write_time(out) > old);
  EXPECT_NE(cli::slurp(out), before);
}

TEST(BakeTree, ReportFileOfTheWholeRun) {
  const fs::path work = scratch("report");
  const std::string cube = kData + "/draco/cube_att.obj", missing = (work / "missing.ply").string();
  const fs::path report = work / "run.json";
  cli::Run r = cli::run({"bake", cube, missing, "-o", (work / "out").string(), "-r", report.string()}, work / "log");
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  const nlohmann::json j = nlohmann::json::parse(cli::slurp(report), nullptr, false);
  ASSERT_TRUE(j.is_object()) << cli::slurp(report);
  EXPECT_EQ(j["geombake"], GEOM_VERSION);
  EXPECT_EQ(j["inputs"], 2);
  EXPECT_EQ(j["baked"], 1);
  EXPECT_EQ(j["failed"], 1);
  ASSERT_EQ(j["results"].size(), 2u);
  EXPECT_EQ(j["results"][0]["input"], cube);
  EXPECT_EQ(j["results"][0]["ok"], true);
  EXPECT_EQ(j["results"][0]["written"], true);
  EXPECT_EQ(j["results"][0]["output"], (work / "out" / "cube_att.obj.gbake").string());
  EXPECT_GT(j["results"][0]["topology"]["triangles"].get<int>(), 0);
  EXPECT_EQ(j["results"][1]["ok"], false);
  EXPECT_EQ(j["results"][1]["error"].get<std::string>().rfind(missing + ": ", 0), 0u) << j["results"][1];
  EXPECT_EQ(j["results"][1]["error_kind"], "not_found") << j["results"][1];
  // Again: the good one is unchanged now.
  r = cli::run({"bake", cube, "-o", (work / "out").string() + "/", "-r", report.string()}, work / "log");
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  const nlohmann::json k = nlohmann::json::parse(cli::slurp(report), nullptr, false);
  EXPECT_EQ(k["unchanged"], 1);
  EXPECT_EQ(k["results"][0]["written"], false);
}
