// geombench held to the baker's bar: bad usage (an unknown scene, an empty
// list, a number not whole or out of range) is exit 2 before anything runs;
// the whole plan (the light radius against every scene's light) is checked
// before a single measurement; the result files are written all or none.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "scratch.h"
#include "viewer_run.h"

namespace {

namespace fs = std::filesystem;

struct BenchRun {
  int exit_code = -1;
  std::string out, err;
};

BenchRun geombench(const testfs::Scratch& s, const std::string& args, const std::string& wrapper = "") {
  const std::string out = s / "stdout.txt", err = s / "stderr.txt";
  const std::string command =
      wrapper + " timeout 300 " + GEOMBENCH_EXE + " " + args + " >'" + out + "' 2>'" + err + "' </dev/null";
  const int status = std::system(command.c_str());
  BenchRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = viewertest::slurp(out), r.err = viewertest::slurp(err);
  return r;
}

TEST(HostileBench, BadUsageIsExitTwoBeforeAnyWork) {
  testfs::Scratch s("hostile_bench_usage");
  const std::pair<const char*, const char*> cases[] = {
      {"--scenes nosuch", "unknown scene 'nosuch'"},
      {"--scenes ''", "--scenes"},
      {"--scenes pipes,", "--scenes"},
      {"--sizes ,", "--sizes"},
      {"--sizes 256,1e3", "--sizes"},
      {"--sizes 4294967552", "--sizes"},
      {"--techniques ''", "--techniques"},
      {"--frames 1e3", "--frames"},
      {"--size 160x120x", "--size"},
      {"--light-radius abc", "--light-radius"},
      {"-o /dev/full", "/dev/full"},
  };
  for (const auto& [flags, names] : cases) {
    SCOPED_TRACE(flags);
    const BenchRun r = geombench(s, std::string("--quick --no-bake ") + flags);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("Error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("technique"), std::string::npos) << "measured before refusing: " << r.out;
  }
}

// A light radius that suits the point-light scene (pipes) but not the
// directional one after it (grazing: a radius is an angle under pi/2):
// refused before pipes is measured, the output folder never made.
TEST(HostileBench, ThePlanIsValidatedBeforeMeasuring) {
  testfs::Scratch s("hostile_bench_plan");
  const std::string dir = s / "out";
  const BenchRun r = geombench(s,
                               "--quick --no-bake --scenes pipes,grazing --techniques pcf-soft --sizes 256 "
                               "--light-radius 2 -o '" +
                                   dir + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("grazing"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("pipes:"), std::string::npos) << "pipes measured before the refusal: " << r.out;
  EXPECT_FALSE(fs::exists(dir));
}

// A full disk (a file size limit with SIGXFSZ ignored: writes fail with
// EFBIG) when the results are written: an error, and no partial result file,
// no temporary file, no folder left.
TEST(HostileBench, AFailedWriteLeavesNothing) {
  testfs::Scratch s("hostile_bench_write");
  const std::string dir = s / "out";
  const BenchRun r = geombench(s, "--quick --no-bake --scenes pipes --techniques ssm --sizes 256 -o '" + dir + "'",
                               "trap '' XFSZ; ulimit -f 2;");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("Error: "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir)) << "left behind: " << dir;
}

}  // namespace
