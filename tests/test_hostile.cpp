// Hostile input and faults, run against the geombake binary of this
// build as a child process: every case gets a clean `Error: FILE: cause` (or a
// correct bake), the other inputs of the batch still bake, nothing but
// finished outputs is left in the output folder, and nothing outside what the
// user named is read. Each case is cheap: the 100 GB file is sparse, the pk3
// bomb claims more than it holds, the million glTF nodes are ~10 MB of JSON.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

struct ScratchCleanup {
  ~ScratchCleanup() {
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("geom_hostile_" + std::to_string(::getpid())), ec);
  }
} scratch_cleanup;

fs::path scratch(const std::string& tag) {
  fs::path d = fs::temp_directory_path() / ("geom_hostile_" + std::to_string(::getpid())) / tag;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream f(p, std::ios::binary);
  f << bytes;
}

// A closed cube in OFF: 8 vertices, 12 triangles.
const char* kCube =
    "OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";

// An n x n grid of quads as OBJ (2 n^2 triangles).
std::string grid_obj(int n) {
  std::string s;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) s += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 1, d = c + 1;
      s += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\nf " + std::to_string(a) +
           " " + std::to_string(d) + " " + std::to_string(c) + "\n";
    }
  return s;
}

// A glTF of one triangle (a data URI) whose buffer is `uri` instead when given.
std::string triangle_gltf(const std::string& uri = "", const std::string& extra = "") {
  const std::string data = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  return "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"" + (uri.empty() ? data : uri) +
         "\",\"byteLength\":36}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,"
         "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}],\"meshes\":[{"
         "\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]" +
         extra + "}";
}
// The 36 bytes of that triangle, for an external buffer.
std::string triangle_bytes() {
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(v), sizeof v);
}

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

// Names in `dir` that are not finished outputs (*.gbake): temporary files.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> bad;
  for (const std::string& n : cli::listing(dir))
    if (n.size() < 6 || n.compare(n.size() - 6, 6, ".gbake") != 0) bad.push_back(n);
  return bad;
}

// Starts geombake with ARGS (output to /dev/null) and `env` added; its pid.
pid_t spawn(const std::vector<std::string>& args, const std::vector<std::string>& env = {}) {
  std::vector<std::string> argv_s = {cli::geombake_path()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv, envp;
  for (std::string& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_s(env);
  for (char** e = environ; *e; ++e) env_s.push_back(*e);
  for (std::string& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

}  // namespace

// A FIFO, a device and a directory are refused by name before they are opened
// (opening a FIFO blocks until a writer comes, so bake, info and inspect would
// hang on one); the other inputs bake.
TEST(Hostile, FifoDeviceAndDirectoryRefusedByName) {
  const fs::path d = scratch("fifo");
  ASSERT_EQ(::mkfifo((d / "pipe.obj").c_str(), 0644), 0);
  ASSERT_EQ(::mkfifo((d / "pipe.gbake").c_str(), 0644), 0);
  fs::create_directories(d / "dir.obj");
  write(d / "cube.off", kCube);
  cli::Run r = cli::run(
      {"bake", (d / "pipe.obj").string(), "/dev/zero", (d / "cube.off").string(), "-o", (d / "out").string()}, d, 20);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "Error: " + (d / "pipe.obj").string() + ": a FIFO, not a regular file")) << r.err;
  EXPECT_TRUE(has(r.err, "Error: /dev/zero: a character device, not a regular file")) << r.err;
  EXPECT_TRUE(fs::is_regular_file(d / "out" / "cube.off.gbake"));
  r = cli::run({"info", (d / "pipe.obj").string()}, d, 20);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "a FIFO, not a regular file")) << r.err;
  r = cli::run({"inspect", (d / "pipe.gbake").string()}, d, 20);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "not a regular file")) << r.err;
  r = cli::run({"inspect", (d / "dir.obj").string()}, d, 20);  // a directory (a named input dir is expanded)
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "dir.obj: not a regular file")) << r.err;
  // A FIFO inside a directory input is skipped with a word (geombake/tree.h), never opened.
  fs::create_directories(d / "in");
  ASSERT_EQ(::mkfifo((d / "in" / "pipe.stl").c_str(), 0644), 0);
  write(d / "in" / "cube.off", kCube);
  r = cli::run({"bake", (d / "in").string(), "-o", (d / "out2").string()}, d, 20);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "pipe.stl: not a regular file, skipped")) << r.err;
  EXPECT_TRUE(fs::is_regular_file(d / "out2" / "cube.off.gbake"));
}

// A 100 GB sparse file (more than this machine's memory) is refused before any
// allocation; the other inputs bake (an uncaught bad_alloc would abort the
// whole batch). A huge file that is not a baked file costs inspect 64 bytes.
TEST(Hostile, SparseFileLargerThanMemory) {
  const fs::path d = scratch("sparse");
  const uint64_t memory = uint64_t(::sysconf(_SC_PHYS_PAGES)) * uint64_t(::sysconf(_SC_PAGESIZE));
  const uint64_t size = std::max<uint64_t>(uint64_t(100) << 30, 2 * memory);
  std::ofstream(d / "big.obj").close();
  fs::resize_file(d / "big.obj", size);
  std::ofstream(d / "big.gbake").close();  // 8 GB: under the reader's 16 GiB limit, refused by its magic
  fs::resize_file(d / "big.gbake", uint64_t(8) << 30);
  write(d / "cube.off", kCube);
  cli::Run r = cli::run(
      {"bake", (d / "big.obj").string(), (d / "cube.off").string(), "-o", (d / "out").string(), "-j", "2"}, d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "big.obj: file is " + std::to_string(size) + " bytes, more than this machine's memory"))
      << r.err;
  EXPECT_TRUE(fs::is_regular_file(d / "out" / "cube.off.gbake"));
  EXPECT_LT(r.max_rss_kb, 200 * 1024 * cli::kSanitizerFactor);
  r = cli::run({"info", (d / "big.obj").string(), (d / "cube.off").string()}, d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.out, "triangles   12")) << r.out;
  r = cli::run({"inspect", (d / "big.gbake").string()}, d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "bad magic")) << r.err;
  EXPECT_LT(r.wall_seconds, 10);
}

// Archives: a truncated .pk3 is that input's error and the batch goes on; a
// member whose header claims gigabytes it does not hold (a pk3 bomb) costs
// only what is there; under --max-memory a claim over the limit is refused
// before it is read; and 20,000 members cost linear time.
TEST(Hostile, ArchivesBadBombedAndLarge) {
  const fs::path d = scratch("pk3");
  write(d / "cube.off", kCube);
  write(d / "trunc.pk3", "PK\x03\x04 truncated");
  // A real archive of one map member (4 MB of zeros), then its sizes patched to claim 3.75 GiB.
  const fs::path bomb = d / "bomb.pk3";
  {
    int err = 0;
    zip_t* z = zip_open(bomb.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    ASSERT_NE(z, nullptr);
    static std::string zeros(4 << 20, '\0');
    zip_source_t* src = zip_source_buffer(z, zeros.data(), zeros.size(), 0);
    ASSERT_GE(zip_file_add(z, "maps/bomb.bsp", src, 0), 0);
    ASSERT_EQ(zip_close(z), 0);
  }
  std::string bytes = cli::slurp(bomb);
  size_t patched = 0;
  for (size_t at = 0; (at = bytes.find(std::string("\x00\x00\x40\x00", 4), at)) != std::string::npos; at += 4) {
    bytes.replace(at, 4, std::string("\x00\x00\x00\xf0", 4));  // 4 MiB -> 0xf0000000 bytes
    ++patched;
  }
  ASSERT_EQ(patched, 2u);  // the local header and the central directory
  write(bomb, bytes);
  cli::Run r = cli::run(
      {"bake", (d / "trunc.pk3").string(), bomb.string(), (d / "cube.off").string(), "-o", (d / "out").string()}, d,
      60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "Error: " + (d / "trunc.pk3").string() + ": ")) << r.err;
  EXPECT_TRUE(has(r.err, "bomb.pk3:maps/bomb.bsp: cannot read member")) << r.err;
  EXPECT_TRUE(fs::is_regular_file(d / "out" / "cube.off.gbake")) << r.err;
  EXPECT_LT(r.max_rss_kb, 400 * 1024 * cli::kSanitizerFactor) << cli::describe(r);
  r = cli::run({"bake", bomb.string(), "-o", (d / "out").string(), "--max-memory", "64M"}, d, 60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "member 'maps/bomb.bsp' is 4026531840 bytes, over the limit of 67108864")) << r.err;

  const fs::path many = d / "many.pk3";
  {
    int err = 0;
    zip_t* z = zip_open(many.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    ASSERT_NE(z, nullptr);
    for (int i = 0; i < 20000; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "maps/m%05d.bsp", i);
      zip_source_t* src = zip_source_buffer(z, "IBSP", 4, 0);
      ASSERT_GE(zip_file_add(z, name, src, 0), 0);
      zip_set_file_compression(z, zip_uint64_t(i), ZIP_CM_STORE, 0);
    }
    ASSERT_EQ(zip_close(z), 0);
  }
  r = cli::run({"bake", many.string(), "-o", (d / "many").string(), "-j", "2"}, d, 120);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "0 baked, 20000 failed of 20000 inputs")) << r.err.substr(r.err.size() - 300);
  EXPECT_LT(r.cpu_seconds, 15 * cli::kSanitizerFactor) << cli::describe(r);  // O(N^2) took minutes
}

// Temporary files: a symlink planted at the output or under the temp prefix is
// never followed; a stale temp file (no writer holds its lock) is swept by
// the next run, one whose writer lives (lock held) or a symlink is not.
TEST(Hostile, PlantedSymlinksAndStaleTempFiles) {
  const fs::path d = scratch("symlink"), out = d / "out";
  fs::create_directories(out);
  write(d / "cube.off", kCube);
  write(d / "victim.txt", "precious");
  fs::create_symlink(d / "victim.txt", out / "cube.gbake");
  fs::create_symlink(d / "victim.txt", out / ".geomtmp-00000000deadbeef");
  write(out / ".geomtmp-0123456789abcdef", "left by a killed run");
  write(out / ".geomtmp-fedcba9876543210", "being written by a live run");
  const int held = ::open((out / ".geomtmp-fedcba9876543210").c_str(), O_RDONLY);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);
  cli::Run r = cli::run({"bake", (d / "cube.off").string(), "-o", (out / "cube.gbake").string()}, d, 30);
  ::close(held);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_EQ(cli::slurp(d / "victim.txt"), "precious");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(out / "cube.gbake")));
  EXPECT_FALSE(fs::exists(fs::symlink_status(out / ".geomtmp-0123456789abcdef")));  // swept
  EXPECT_TRUE(fs::exists(out / ".geomtmp-fedcba9876543210"));                       // its writer lives
  EXPECT_TRUE(fs::is_symlink(out / ".geomtmp-00000000deadbeef"));                   // not provably ours
}

// Writers of one output at once (separate processes, as in separate PID
// namespaces, where two writers can have the same pid): each publishes a
// complete file, and no temporary file is left.
TEST(Hostile, ConcurrentWritersNeverShareATempFile) {
  const fs::path d = scratch("concurrent"), out = d / "out";
  fs::create_directories(out);
  write(d / "grid.obj", grid_obj(120));
  const std::vector<std::string> args = {"bake", (d / "grid.obj").string(), "-o", (out / "grid.gbake").string()};
  for (int round = 0; round < 4; ++round) {
    std::vector<pid_t> pids;
    for (int k = 0; k < 3; ++k)
      pids.push_back(
          spawn(args, round % 2 ? std::vector<std::string>{"GEOM_NO_O_TMPFILE=1"} : std::vector<std::string>{}));
    for (pid_t pid : pids) {
      int status = 0;
      ::waitpid(pid, &status, 0);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "round " << round;
    }
    EXPECT_EQ(leftovers(out), std::vector<std::string>());
    const cli::Run check = cli::run({"inspect", (out / "grid.gbake").string()}, d / "log", 30);
    EXPECT_EQ(check.exit_code, 0) << cli::describe(check);
  }
}

// kill -9 and SIGINT mid-write, with named temporary files (the fallback of
// systems without O_TMPFILE, forced): after SIGINT no temporary file is left;
// after kill -9 the next clean run sweeps what was left. Either way the
// folder then holds finished outputs only, and they are complete.
TEST(Hostile, KillAndSigintMidWriteThenACleanRun) {
  const fs::path d = scratch("kill"), out = d / "out";
  const bool sanitized = cli::kSanitizerFactor > 1;  // slower: fewer and smaller runs
  write(d / "grid.obj", grid_obj(sanitized ? 120 : 250));
  write(d / "cube.off", kCube);
  const std::vector<std::string> args = {
      "bake", (d / "grid.obj").string(), (d / "cube.off").string(), "-o", out.string(), "-j", "2"};
  const cli::Run clean = cli::run(args, d / "log", 60);
  ASSERT_EQ(clean.exit_code, 0) << cli::describe(clean);
  const std::string expected = cli::slurp(out / "grid.obj.gbake");
  int interrupted = 0;
  // The signal lands at a share of the clean run's own time, so that most runs
  // are cut short however fast or loaded this machine is.
  const double clean_ms = clean.wall_seconds * 1000.0;
  for (int sig : {SIGINT, SIGKILL}) {
    for (double share : sanitized ? std::vector<double>{0.02, 0.15, 0.35, 0.6}
                                  : std::vector<double>{0.01, 0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8}) {
      const int delay_ms = int(share * clean_ms);
      fs::remove_all(out);
      const pid_t pid = spawn(args, {"GEOM_NO_O_TMPFILE=1"});
      ASSERT_GT(pid, 0);
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      ::kill(pid, sig);
      int status = 0;
      ::waitpid(pid, &status, 0);
      if (WIFSIGNALED(status)) ++interrupted;
      if (sig == SIGINT && fs::exists(out))
        EXPECT_EQ(leftovers(out), std::vector<std::string>()) << "SIGINT after " << delay_ms << " ms";
      const cli::Run again = cli::run(args, d / "log", 60);
      EXPECT_EQ(again.exit_code, 0) << cli::describe(again);
      EXPECT_EQ(leftovers(out), std::vector<std::string>()) << "after signal " << sig << " at " << delay_ms << " ms";
      EXPECT_TRUE(cli::slurp(out / "grid.obj.gbake") == expected);
    }
  }
  EXPECT_GT(interrupted, sanitized ? 2 : 4);  // most runs were really cut short
}

// glTF external URIs stay in the asset's folder unless --allow-outside-uris;
// '+' is a '+' for reading and for the depfile alike.
TEST(Hostile, TraversalUrisAreConfined) {
  const fs::path d = scratch("uri"), asset = d / "assets" / "a";
  fs::create_directories(asset / "sub");
  write(d / "secret.bin", triangle_bytes());
  write(asset / "sub" / "x+y.bin", triangle_bytes());
  fs::create_symlink(d / "secret.bin", asset / "link.bin");
  write(asset / "up.gltf", triangle_gltf("../../secret.bin"));
  write(asset / "abs.gltf", triangle_gltf((d / "secret.bin").string()));
  write(asset / "link.gltf", triangle_gltf("link.bin"));
  write(asset / "file.gltf", triangle_gltf("file:///etc/passwd"));
  write(asset / "plus.gltf", triangle_gltf("sub/x+y.bin"));
  cli::Run r = cli::run({"bake", (asset / "up.gltf").string(), (asset / "abs.gltf").string(),
                         (asset / "link.gltf").string(), (asset / "file.gltf").string(), (asset / "plus.gltf").string(),
                         "-o", (d / "out").string(), "--depfile", (d / "deps.d").string()},
                        d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "up.gltf: buffer 0: '../../secret.bin' leads outside the asset's folder")) << r.err;
  EXPECT_TRUE(has(r.err, "abs.gltf: buffer 0: '" + (d / "secret.bin").string() + "' is an absolute path")) << r.err;
  EXPECT_TRUE(has(r.err, "link.gltf: buffer 0: 'link.bin' leads outside the asset's folder")) << r.err;
  EXPECT_TRUE(has(r.err, "file.gltf: buffer 0: 'file:///etc/passwd' is not a relative file reference")) << r.err;
  EXPECT_EQ(cli::listing(d / "out"), std::vector<std::string>{"plus.gltf.gbake"});
  EXPECT_TRUE(has(cli::slurp(d / "deps.d"), (asset / "sub" / "x+y.bin").string())) << cli::slurp(d / "deps.d");
  r = cli::run({"bake", "--allow-outside-uris", (asset / "up.gltf").string(), "-o", (d / "up.gbake").string()}, d, 30);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  r = cli::run({"info", (asset / "up.gltf").string()}, d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  // A glTF inside an archive has no folder: its external files are never looked up (in the working directory).
  const std::string gltf = triangle_gltf("secret.bin");
  int err = 0;
  zip_t* z = zip_open((d / "a.pk3").c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(z, nullptr);
  ASSERT_GE(zip_file_add(z, "m/t.gltf", zip_source_buffer(z, gltf.data(), gltf.size(), 0), 0), 0);
  ASSERT_EQ(zip_close(z), 0);
  r = cli::run({"info", (d / "a.pk3").string() + ":m/t.gltf"}, d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "'secret.bin' is an external file, but the asset has no folder")) << r.err;
}

// Any file name: --json stays valid UTF-8 with the name kept losslessly
// (\udcXX per byte that is not UTF-8), the depfile escapes per Make's rules
// and a name it cannot express is an error, not a broken rule.
TEST(Hostile, NonUtf8AndSpecialNames) {
  const fs::path d = scratch("names");
  const std::string odd = "m\xff\xfe.off", special = "a b#c$d.off", newline = "new\nline.off";
  for (const std::string& n : {odd, special, newline}) write(d / n, kCube);
  cli::Run r = cli::run({"bake", "--json", (d / odd).string(), (d / special).string(), (d / newline).string(), "-o",
                         (d / "out").string(), "--depfile", (d / "deps.d").string(), "-r", (d / "run.json").string()},
                        d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);  // the newline name cannot be in a depfile
  EXPECT_TRUE(has(r.err, "a newline in its name")) << r.err;
  EXPECT_TRUE(has(r.out, "\"input\":\"" + (d / "m").string() + "\\udcff\\udcfe.off\"")) << r.out;
  EXPECT_TRUE(has(r.out, "\"input\":\"" + (d / "new").string() + "\\nline.off\"")) << r.out;
  for (unsigned char c : r.out) EXPECT_LT(c, 0x80);  // here all ASCII: valid UTF-8
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 3);
  EXPECT_TRUE(has(cli::slurp(d / "run.json"), "\\udcff\\udcfe.off")) << cli::slurp(d / "run.json");
  const std::string deps = cli::slurp(d / "deps.d");
  EXPECT_TRUE(has(deps, "a\\ b\\#c$$d.off")) << deps;
  r = cli::run({"info", "--json", (d / odd).string()}, d, 30);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_TRUE(has(r.out, "\"file\":\"" + (d / "m").string() + "\\udcff\\udcfe.off\"")) << r.out;
}

// What is not a mesh is refused; an input that is its own output, and every
// bad -o, get a clear message.
TEST(Hostile, NotAMeshAndBadOutputs) {
  const fs::path d = scratch("notmesh");
  std::string noise;
  uint32_t x = 12345;
  for (int i = 0; i < 65536; ++i) noise += char((x = x * 1103515245u + 12345u) >> 24);
  write(d / "random.obj", noise);
  write(d / "hello.obj", "hello\n");
  write(d / "prims.gltf", "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":{}}]}");
  write(d / "cube.off", kCube);
  cli::Run r = cli::run({"bake", (d / "random.obj").string(), (d / "hello.obj").string(), (d / "prims.gltf").string(),
                         (d / "cube.off").string(), "-o", (d / "out").string()},
                        d, 30);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "random.obj: line ")) << r.err;
  EXPECT_TRUE(has(r.err, "hello.obj: line 1: 'hello' is not an OBJ statement, and the file has no face")) << r.err;
  EXPECT_TRUE(has(r.err, "prims.gltf: mesh 0: \"primitives\" is missing or not an array")) << r.err;
  EXPECT_EQ(cli::listing(d / "out"), std::vector<std::string>{"cube.off.gbake"});
  const std::string cube = cli::slurp(d / "cube.off");
  r = cli::run({"bake", (d / "cube.off").string(), "-o", (d / "cube.off").string()}, d, 30);
  EXPECT_EQ(r.exit_code, 2) << cli::describe(r);  // refused before any work, as every output that is an input
  EXPECT_TRUE(has(r.err, "cube.off: is its own output")) << r.err;
  EXPECT_EQ(cli::slurp(d / "cube.off"), cube);
  r = cli::run({"bake", (d / "cube.off").string(), "-o", ""}, d, 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "Error: -o: the output path is empty")) << r.err;
  r = cli::run({"bake", (d / "cube.off").string(), "-o", "/dev/null"}, d, 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "'/dev/null' exists and is not a regular file")) << r.err;
  r = cli::run({"bake", (d / "cube.off").string(), "-o", (d / "no" / "such" / "x.gbake").string()}, d, 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "does not exist")) << r.err;
  EXPECT_EQ(leftovers(d / "out"), std::vector<std::string>());
}

// A million glTF nodes bake in linear time: at this size anything worse than
// linear runs for minutes.
TEST(Hostile, MillionGltfNodes) {
  const fs::path d = scratch("nodes");
  const int n = cli::kSanitizerFactor > 1 ? 100000 : 1000000;
  std::string nodes = "{\"mesh\":0,\"children\":[1]}";
  for (int i = 1; i + 1 < n; ++i) nodes += ",{\"children\":[" + std::to_string(i + 1) + "]}";
  nodes += ",{\"mesh\":0,\"translation\":[0,0,1]}";
  write(d / "nodes.gltf", triangle_gltf("", ",\"nodes\":[" + nodes + "],\"scenes\":[{\"nodes\":[0]}],\"scene\":0"));
  cli::Run r = cli::run({"bake", (d / "nodes.gltf").string(), "-o", (d / "nodes.gbake").string()}, d, 120);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_LT(r.cpu_seconds, 30 * cli::kSanitizerFactor) << cli::describe(r);
  r = cli::run({"info", (d / "nodes.gltf").string(), "--timeout", "0.01"}, d, 60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "nodes.gltf: timed out after 0.01 s (--timeout)")) << r.err;
  EXPECT_LT(r.wall_seconds, 10 * cli::kSanitizerFactor);
}

namespace {

// A glTF that takes about a second to bake (a fifth of that under the
// sanitizers): one triangle instanced by 200,000 root nodes.
void write_slow_gltf(const fs::path& path) {
  const int n = cli::kSanitizerFactor > 1 ? 50000 : 200000;
  std::string nodes = "{\"mesh\":0}", roots = "0";
  for (int i = 1; i < n; ++i) {
    nodes += ",{\"mesh\":0,\"translation\":[" + std::to_string(i) + ",0,0]}";
    roots += "," + std::to_string(i);
  }
  write(path, triangle_gltf("", ",\"nodes\":[" + nodes + "],\"scenes\":[{\"nodes\":[" + roots + "]}]"));
}

}  // namespace

// Work abandoned by --timeout really stops (its next allocation throws, it
// unwinds) instead of running on beside the inputs still baking: with enough
// quick inputs after it to outlast it, the run costs the quick inputs plus a
// fraction of the slow one, not both whole; nothing crashes while it unwinds.
TEST(Hostile, TimedOutWorkIsStopped) {
  const fs::path d = scratch("abandon");
  write_slow_gltf(d / "slow.gltf");
  write(d / "q0.obj", grid_obj(100));
  const cli::Run slow =
      cli::run({"bake", (d / "slow.gltf").string(), "-o", (d / "slow.gbake").string()}, d / "l1", 120);
  ASSERT_EQ(slow.exit_code, 0) << cli::describe(slow);
  const cli::Run one = cli::run({"bake", (d / "q0.obj").string(), "-o", (d / "q0.gbake").string()}, d / "l2", 120);
  ASSERT_EQ(one.exit_code, 0) << cli::describe(one);
  // Enough quick inputs to take twice the slow one's time.
  const int quick = std::clamp(int(2 * slow.cpu_seconds / std::max(one.cpu_seconds, 1e-3)), 4, 150);
  std::vector<std::string> args = {"bake", "-j", "1", "-o", (d / "q1").string()};
  for (int i = 0; i < quick; ++i) {
    const fs::path q = d / ("q" + std::to_string(i) + ".obj");
    if (i) fs::copy_file(d / "q0.obj", q);
    args.push_back(q.string());
  }
  // A limit far under the slow input's time, far over a quick one's (under load or a sanitizer too):
  // a fifth of the slow input, which on a loaded 2-core machine left a quick input (~10 ms alone)
  // more than 30x its own time before a stall could make it time out (at a twentieth, one did).
  const double limit = std::max(0.2 * slow.wall_seconds, 3 * one.wall_seconds);
  ASSERT_LT(limit, 0.4 * slow.wall_seconds) << "slow " << slow.wall_seconds << " s, quick " << one.wall_seconds << " s";
  std::vector<std::string> with_slow = args;
  with_slow.insert(with_slow.begin() + 5, (d / "slow.gltf").string());
  with_slow.insert(with_slow.end(), {"--timeout", std::to_string(limit)});
  // Work left running would add the whole slow input (1.0); stopped work adds the fifth it ran
  // before its limit plus its unwinding. CPU time is noisy where the machine is loaded (a thread
  // that shares its core or its caches runs slower): the quick inputs alone and with the slow
  // one are run back to back, and the pair is tried again, up to three times, where the
  // difference is over the bar; work left running is over it on every try.
  const double kept = cli::kSanitizerFactor > 1 ? 0.7 : 0.6;
  std::string why;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const std::string tag = std::to_string(attempt);
    args[4] = (d / ("alone" + tag)).string();  // fresh folders: every output written each time
    with_slow[4] = (d / ("both" + tag)).string();
    const cli::Run alone = cli::run(args, d / ("l3" + tag), 300);
    ASSERT_EQ(alone.exit_code, 0) << cli::describe(alone);
    const cli::Run both = cli::run(with_slow, d / ("l4" + tag), 300);
    EXPECT_EQ(both.exit_code, 1) << cli::describe(both);
    EXPECT_TRUE(has(both.err, "slow.gltf: timed out after")) << both.err;
    EXPECT_EQ(cli::listing(d / ("both" + tag)).size(), size_t(quick)) << both.err.substr(0, 2000);
    const double extra = both.cpu_seconds - alone.cpu_seconds;
    why += "try " + tag + ": " + std::to_string(extra) + " s more with the slow input (" +
           std::to_string(both.wall_seconds) + " s wall); ";
    if (extra < kept * slow.cpu_seconds) break;
    if (attempt == 2)
      ADD_FAILURE() << why << "slow alone " << slow.cpu_seconds << " s CPU (" << slow.wall_seconds << " s wall), "
                    << quick << " quick alone " << alone.cpu_seconds << " s CPU, limit " << limit << " s";
  }
}

// Wherever --timeout lands in an input's work (a destructor that allocates
// included: nlohmann::json's does, and may not throw), the run ends as the
// contract says: exit 1, the input named as timed out, the other input baked,
// never a signal. Limits spread over the slow input's whole time.
TEST(Hostile, TimeoutAnywhereEndsCleanly) {
  const fs::path d = scratch("anywhere");
  write_slow_gltf(d / "slow.gltf");
  write(d / "quick.obj", grid_obj(4));
  const cli::Run slow = cli::run({"bake", (d / "slow.gltf").string(), "-o", (d / "slow.gbake").string()}, d, 120);
  ASSERT_EQ(slow.exit_code, 0) << cli::describe(slow);
  const int kLimits = cli::kSanitizerFactor > 1 ? 8 : 16;
  for (int i = 0; i < kLimits; ++i) {
    const double limit = slow.wall_seconds * (0.05 + 0.9 * i / (kLimits - 1));
    const fs::path out = d / ("o" + std::to_string(i));
    const cli::Run r = cli::run({"bake", "-j", "1", "-o", out.string(), (d / "slow.gltf").string(),
                                 (d / "quick.obj").string(), "--timeout", std::to_string(limit)},
                                d, 120);
    if (r.exit_code == 0) continue;  // the machine ran it faster than alone: nothing timed out
    EXPECT_EQ(r.exit_code, 1) << "limit " << limit << " s: " << cli::describe(r);
    EXPECT_TRUE(has(r.err, "slow.gltf: timed out after")) << r.err;
    EXPECT_FALSE(has(r.err, "terminate")) << r.err;
    EXPECT_EQ(cli::listing(out).size(), 1u) << r.err;  // the quick input's output alone
  }
}

// --max-memory bounds what is really allocated, not an estimate from the
// triangle count: an OBJ of 2M vertices and one face is refused while it is
// imported; an MD3 whose surfaces share their triangles to claim millions is
// refused from its header counts, under --max-triangles too.
TEST(Hostile, MaxMemoryIsARealBound) {
  const fs::path d = scratch("memory");
  std::string obj;
  for (int i = 0; i < 2000000; ++i) obj += "v 1 2 3\n";
  obj += "f 1 2 3\n";
  write(d / "verts.obj", obj);
  write(d / "cube.off", kCube);
  cli::Run r = cli::run({"bake", (d / "verts.obj").string(), (d / "cube.off").string(), "-o", (d / "out").string(),
                         "--max-memory", "20M"},
                        d, 60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "verts.obj: needs more memory than allowed, over the limit of 20971520 (--max-memory)"))
      << r.err;
  EXPECT_TRUE(fs::is_regular_file(d / "out" / "cube.off.gbake"));
  r = cli::run({"bake", (d / "verts.obj").string(), "-o", (d / "v.gbake").string(), "--max-memory", "200M"}, d, 60);
  EXPECT_EQ(r.exit_code, 0) << cli::describe(r);

  // MD3: 4,000 surface headers share one block of 10,000 triangles (zeros:
  // vertex 0 three times) and 3 vertices: 40M triangles from half a megabyte.
  auto u32 = [](std::string& s, size_t at, uint32_t v) { std::memcpy(&s[at], &v, 4); };
  const int surfaces = 4000, triangles = 10000;
  const size_t data = 108 + 108 * size_t(surfaces);
  std::string md3(data + 12 * size_t(triangles) + 3 * 8, '\0');
  std::memcpy(&md3[0], "IDP3", 4);
  u32(md3, 4, 15);
  u32(md3, 76, 1);         // frames
  u32(md3, 84, surfaces);  // surfaces
  u32(md3, 100, 108);      // surface offset
  u32(md3, 104, uint32_t(md3.size()));
  for (int s = 0; s < surfaces; ++s) {
    const size_t at = 108 + 108 * size_t(s);
    std::memcpy(&md3[at], "IDP3", 4);
    u32(md3, at + 72, 1);                                      // frames
    u32(md3, at + 80, 3);                                      // vertices
    u32(md3, at + 84, triangles);                              // triangles
    u32(md3, at + 88, uint32_t(data - at));                    // the shared triangles
    u32(md3, at + 100, uint32_t(data + 12 * triangles - at));  // the shared vertices
    u32(md3, at + 104, 108);                                   // the next surface
  }
  write(d / "claims.md3", md3);
  r = cli::run({"bake", (d / "claims.md3").string(), "-o", (d / "m.gbake").string(), "--max-triangles", "1000000"}, d,
               60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "the surfaces claim 40000000 triangles, over the limit of 1000000")) << r.err;
  r = cli::run({"bake", (d / "claims.md3").string(), "-o", (d / "m.gbake").string(), "--max-memory", "100M"}, d, 60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  EXPECT_TRUE(has(r.err, "the surfaces claim 40000000 triangles and 12000 vertices")) << r.err;
  EXPECT_LT(r.max_rss_kb, 150 * 1024 * cli::kSanitizerFactor) << cli::describe(r);
}
