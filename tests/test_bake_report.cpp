// geombake's report as a pipeline consumes it (docs/build-step.md), run as a
// child process on real files:
//   - each failed input has an error_kind from the documented list, the kind
//     of what is wrong with it (one input per kind, all in one run);
//   - each input has its seconds, its SHA-256 and the files it read, each with
//     its SHA-256, equal to sha256sum's;
//   - info --json prints failed inputs too, with the same kinds;
//   - --stable-report gives the same bytes on a rerun that leaves every output
//     untouched, where the default report says "written" differently;
//   - --progress=plain prints at most one line per 5 s (and one at the first
//     finished input) when stderr is not a terminal.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"
#include "scratch.h"

namespace fs = std::filesystem;

namespace {

const std::string kData = GEOM_TEST_DATA;

fs::path scratch(const std::string& tag) { return testfs::case_dir("geom_report", tag); }

void write(const fs::path& p, const std::string& text) { testfs::write_text(p, text); }

const char* kCube =
    "OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";

// A sphere-like OFF mesh of about 2 * n * n triangles (a grid on a sphere).
std::string sphere_off(int n) {
  std::string v, f;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < n; ++j) {
      const double t = 3.14159265358979 * i / n, p = 2 * 3.14159265358979 * j / n;
      v += std::to_string(std::sin(t) * std::cos(p)) + " " + std::to_string(std::sin(t) * std::sin(p)) + " " +
           std::to_string(std::cos(t)) + "\n";
    }
  int faces = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j, b = i * n + (j + 1) % n, c = a + n, d = b + n;
      f += "3 " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(b) + "\n";
      f += "3 " + std::to_string(b) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
      faces += 2;
    }
  return "OFF\n" + std::to_string((n + 1) * n) + " " + std::to_string(faces) + " 0\n" + v + f;
}

// sha256sum's answer for `path`.
std::string sha256sum(const fs::path& path) {
  FILE* p = popen(("sha256sum '" + path.string() + "'").c_str(), "r");
  char buffer[65] = {};
  const size_t n = p ? std::fread(buffer, 1, 64, p) : 0;
  if (p) pclose(p);
  return std::string(buffer, n);
}

std::map<std::string, nlohmann::json> by_input(const nlohmann::json& results) {
  std::map<std::string, nlohmann::json> m;
  for (const auto& r : results) m[r["input"].get<std::string>()] = r;
  return m;
}

}  // namespace

// One input per error kind, in one run: each gets its kind; the baked ones
// get none. The same inputs through info --json get the same kinds.
TEST(BakeReport, ErrorKinds) {
  const fs::path d = scratch("kinds");
  write(d / "in" / "ok.off", kCube);
  write(d / "in" / "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  write(d / "in" / "binary.off", "OFF BINARY\n");
  write(d / "in" / "big.off", sphere_off(30));
  write(d / "in" / "odd.xyz", "not a mesh\n");
  write(d / "in" / "gl.gltf",
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"missing.bin\",\"byteLength\":4}]}");
  fs::create_symlink("/dev/null", d / "in" / "device.off");
  write(d / "in" / "x.off", kCube);
  fs::create_directories(d / "out" / "x.off.gbake");  // a folder where its output would go
  const std::map<std::string, std::string> expected = {
      {"ok.off", ""},
      {"bad.off", "malformed"},
      {"binary.off", "unsupported"},
      {"big.off", "limit_triangles"},
      {"odd.xyz", "unsupported"},
      {"gl.gltf", "not_found"},
      {"device.off", "not_regular"},
      {"missing.off", "not_found"},
      {"x.off", "write_failed"},
  };
  std::vector<std::string> args = {
      "bake", "-o", (d / "out").string(), "--max-triangles", "1000", "-r", (d / "r.json").string(), "-j", "1"};
  for (const auto& [name, kind] : expected) args.push_back((d / "in" / name).string());
  const cli::Run r = cli::run(args, d / "log", 60);
  ASSERT_EQ(r.exit_code, 1) << cli::describe(r);
  const auto results = by_input(nlohmann::json::parse(cli::slurp(d / "r.json"))["results"]);
  for (const auto& [name, kind] : expected) {
    const nlohmann::json& j = results.at((d / "in" / name).string());
    EXPECT_EQ(j["ok"], kind.empty()) << name;
    if (!kind.empty()) EXPECT_EQ(j["error_kind"], kind) << name << ": " << j["error"];
    if (kind.empty()) EXPECT_FALSE(j.contains("error_kind")) << name;
  }
  // Memory and time, each on its own: the estimate over --max-memory, and a mesh over --timeout.
  write(d / "in" / "huge.off", sphere_off(200));
  for (const auto& [flag, value, kind] :
       {std::tuple<std::string, std::string, std::string>{"--max-memory", "64K", "limit_memory"},
        {"--timeout", "0.001", "timeout"}}) {
    const cli::Run m =
        cli::run({"bake", (d / "in" / "huge.off").string(), "-o", (d / "huge.gbake").string(), flag, value, "--json"},
                 d / "log", 60);
    EXPECT_EQ(m.exit_code, 1) << cli::describe(m);
    const nlohmann::json j = nlohmann::json::parse(m.out.substr(0, m.out.find('\n')));
    EXPECT_EQ(j["error_kind"], kind) << m.out;
  }
  // info --json: one object per input, failed ones included, with their kind.
  std::vector<std::string> info = {"info", "--json", "--max-triangles", "1000"};
  for (const char* name : {"ok.off", "bad.off", "binary.off", "big.off", "gl.gltf", "device.off", "missing.off"})
    info.push_back((d / "in" / name).string());
  const cli::Run i = cli::run(info, d / "log", 60);
  EXPECT_EQ(i.exit_code, 1) << cli::describe(i);
  std::vector<nlohmann::json> lines;
  for (size_t at = 0, nl; (nl = i.out.find('\n', at)) != std::string::npos; at = nl + 1)
    lines.push_back(nlohmann::json::parse(i.out.substr(at, nl - at)));
  ASSERT_EQ(lines.size(), 7u) << i.out;
  for (const nlohmann::json& j : lines) {
    const std::string name = fs::path(j["input"].get<std::string>()).filename().string();
    EXPECT_EQ(j["ok"], expected.at(name).empty()) << j.dump();
    if (!expected.at(name).empty()) {
      EXPECT_EQ(j["error_kind"], expected.at(name)) << j.dump();
      EXPECT_TRUE(j["error"].get<std::string>().find(name) != std::string::npos) << j.dump();
    } else {
      EXPECT_EQ(j["triangles"], 12) << j.dump();
    }
  }
}

// Each input's SHA-256 and the files it read, as sha256sum sees them; its
// seconds; the glTF's external buffer among what it read, failed inputs too.
TEST(BakeReport, HashesAndReads) {
  const fs::path d = scratch("hashes");
  fs::copy_file(kData + "/draco/Box/glTF/Box.gltf", d / "Box.gltf");
  fs::copy_file(kData + "/draco/Box/glTF/Box0.bin", d / "Box0.bin");
  write(d / "cube.off", kCube);
  write(d / "bad.off", "OFF\n1 1 0\n0 0 0\n3 0 1 2\n");
  const cli::Run r = cli::run({"bake", (d / "Box.gltf").string(), (d / "cube.off").string(), (d / "bad.off").string(),
                               "-o", (d / "out").string(), "--json"},
                              d / "log", 60);
  EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
  std::map<std::string, nlohmann::json> results;
  for (size_t at = 0, nl; (nl = r.out.find('\n', at)) != std::string::npos; at = nl + 1) {
    const nlohmann::json j = nlohmann::json::parse(r.out.substr(at, nl - at));
    results[fs::path(j["input"].get<std::string>()).filename().string()] = j;
  }
  ASSERT_EQ(results.size(), 3u) << r.out;
  const std::map<std::string, std::vector<std::string>> reads = {
      {"Box.gltf", {"Box.gltf", "Box0.bin"}}, {"cube.off", {"cube.off"}}, {"bad.off", {"bad.off"}}};
  for (const auto& [name, files] : reads) {
    const nlohmann::json& j = results[name];
    EXPECT_EQ(j["sha256"], sha256sum(d / name)) << name;
    ASSERT_EQ(j["reads"].size(), files.size()) << j.dump();
    for (size_t k = 0; k < files.size(); ++k) {
      EXPECT_EQ(j["reads"][k]["file"], (d / files[k]).string());
      EXPECT_EQ(j["reads"][k]["sha256"], sha256sum(d / files[k])) << files[k];
    }
    EXPECT_GE(j["seconds"].get<double>(), 0.0);
    EXPECT_LT(j["seconds"].get<double>(), r.wall_seconds);
  }
}

// A rerun whose outputs are all left untouched: --stable-report's bytes are
// the same, the default report's are not ("written" true, then false).
TEST(BakeReport, StableReportAcrossReruns) {
  const fs::path d = scratch("stable");
  write(d / "in" / "a.off", kCube);
  write(d / "in" / "b.off", sphere_off(12));
  write(d / "in" / "bad.off", "OFF\n");
  std::vector<std::string> reports;
  for (const bool stable : {true, false})
    for (int run = 0; run < 2; ++run) {
      fs::remove_all(d / "out" / std::to_string(stable));
      for (int again = 0; again < 1 + run; ++again) {
        std::vector<std::string> args = {
            "bake", (d / "in").string(),     "-o", (d / "out" / std::to_string(stable)).string(),
            "-r",   (d / "r.json").string(), "-j", std::to_string(1 + again)};
        if (stable) args.push_back("--stable-report");
        EXPECT_EQ(cli::run(args, d / "log", 60).exit_code, 1);
      }
      reports.push_back(cli::slurp(d / "r.json"));
    }
  EXPECT_EQ(reports[0], reports[1]);  // stable: a first run and a rerun that changed nothing
  EXPECT_EQ(reports[0].find("\"written\""), std::string::npos);
  EXPECT_EQ(reports[0].find("\"seconds\""), std::string::npos);
  EXPECT_NE(reports[2], reports[3]);
  EXPECT_NE(reports[3].find("\"written\": false"), std::string::npos) << reports[3];
}

// --progress=plain on a pipe: a line when the first input is done, then at
// most one every 5 s; none without the flag; none with -q.
TEST(BakeReport, PlainProgress) {
  const fs::path d = scratch("progress");
  for (int i = 0; i < 24; ++i) write(d / "in" / ("m" + std::to_string(i) + ".off"), sphere_off(20 + i));
  const std::vector<std::string> base = {"bake", (d / "in").string(), "-o", (d / "out").string(), "-j", "1", "--force"};
  auto lines = [](const std::string& err) {
    size_t n = 0;
    for (size_t at = 0; (at = err.find("inputs done (", at)) != std::string::npos; ++at) ++n;
    return n;
  };
  std::vector<std::string> plain = base;
  plain.push_back("--progress=plain");
  const cli::Run r = cli::run(plain, d / "log", 120);
  ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
  EXPECT_GE(lines(r.err), 1u) << r.err;
  EXPECT_LE(double(lines(r.err)), 1 + r.wall_seconds / 5) << r.err;
  EXPECT_NE(r.err.find("geombake bake: 1 of 24 inputs done (4%)"), std::string::npos) << r.err;
  EXPECT_EQ(lines(cli::run(base, d / "log", 120).err), 0u);
  plain.push_back("-q");
  EXPECT_EQ(cli::run(plain, d / "log", 120).err, "");
}
