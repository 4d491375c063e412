// The viewer's file path (fuzz/viewer_file.h: the baked reader, then its
// float validation) replayed in the tests: every input kept in
// tests/fuzz_regressions/viewer/ (the fuzz target's seed and its findings, the
// first byte the target's mode), and mutations of a real bake, each with its
// checksums repaired so that the floats reach the validation: every law holds,
// and a NaN or absurd float in any section is refused, never accepted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "baked_repair.h"
#include "cli_run.h"
#include "viewer_file.h"

namespace fs = std::filesystem;

namespace {

std::vector<unsigned char> as_target_does(const std::string& bytes) {
  std::vector<unsigned char> file(bytes.begin() + 1, bytes.end());
  if (bytes[0] & 1) geom_fuzz::repair_checksums(file);
  return file;
}

TEST(FuzzViewerFile, EveryKeptInputKeepsTheLaws) {
  const fs::path dir = fs::path(GEOM_SOURCE_DIR) / "tests" / "fuzz_regressions" / "viewer";
  size_t replayed = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string bytes = cli::slurp(e.path());
    ASSERT_FALSE(bytes.empty()) << e.path();
    const std::vector<unsigned char> file = as_target_does(bytes);
    EXPECT_EQ(geom_fuzz::check_viewer_file(file.data(), file.size()), "") << e.path();
    ++replayed;
  }
  EXPECT_GE(replayed, 1u);
}

// Random mutations of the kept bake (bytes flipped, floats set to NaN, inf,
// 1e30 at random offsets), checksums repaired: the laws hold on every one, and
// some are refused by the float validation (the mutations reach it).
TEST(FuzzViewerFile, MutationsKeepTheLaws) {
  const std::string seed = cli::slurp(fs::path(GEOM_SOURCE_DIR) / "tests/fuzz_regressions/viewer/scene_and_light.1");
  ASSERT_GT(seed.size(), 200u);
  const std::vector<unsigned char> base = as_target_does(seed);
  std::mt19937 rng(17);
  const float specials[] = {std::nanf(""), INFINITY, -INFINITY, 1e30f, -3e16f};
  size_t float_refusals = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<unsigned char> file = base;
    const int edits = 1 + int(rng() % 3);
    for (int k = 0; k < edits; ++k) {
      const size_t at = 64 + rng() % (file.size() - 68);  // past the header
      if (rng() % 2)
        file[at] ^= uint8_t(1u << (rng() % 8));
      else
        std::memcpy(&file[at & ~size_t(3)], &specials[rng() % 5], 4);
    }
    geom_fuzz::repair_checksums(file);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ASSERT_EQ(geom_fuzz::check_viewer_file(file.data(), file.size()), "");
    geom::baked::Reader r;
    std::string error;
    float_refusals += r.open(file.data(), file.size()) && !geom::baked::validate_floats(r, error);
  }
  EXPECT_GT(float_refusals, 300u);
}

}  // namespace
