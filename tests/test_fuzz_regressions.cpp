// Every input the fuzzers found (tests/fuzz_regressions/TARGET/NAME) replayed
// through the fuzz target's own body (fuzz/fuzz_import.h): the importer's
// contract must hold (a refusal names the file and leaves the scene empty; an
// accepted scene has indices in range and finite positions). The sanitizer job
// (scripts/sanitize.sh) runs this under ASan/UBSan, where each original finding
// (a crash, an overflow, undefined behaviour) would show again; the refusal
// each one must get is checked here too, so the test fails without the fix in
// any build.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "fuzz_import.h"
#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

// What each finding was, and the refusal it must get.
struct Finding {
  const char* what;
  const char* refusal;  // a fragment of the error message
};
const std::map<std::string, Finding> kFindings = {
    {"draco/bool_positions.drc",
     {"UBSan: a Draco POSITION attribute of type DT_BOOL read through `bool` (load of value 128), "
      "draco/attributes/geometry_attribute.h:300",
      "not a number type"}},
    {"draco/huge_counts.drc",
     {"out of memory: 325 bytes (Draco 1.1 Edgebreaker) claiming 808,464,432 faces and vertices, which "
      "libdraco allocated and filled before reading them (19 GB, 46 s through geombake)",
      "claims 808464432 faces"}},
    {"draco/texcoord_orientations.drc",
     {"timeout: 393 bytes whose texture-coordinate prediction claims 1,329,807,698 orientations, which libdraco "
      "allocated and looped over before noticing the data is missing (29 s through geombake)",
      "texture-coordinate prediction claims 1329807698 orientations for 36 corners"}},
    {"draco/metadata_flag_v1_1.drc",
     {"out of memory: 41 bytes (Draco 1.1 Edgebreaker) with the metadata flag set, which Draco ignores before "
      "1.3 and the count check read as metadata, so its billion faces went unchecked (malloc of 4.6 GB)",
      "claims 1145324612 faces"}},
};

}  // namespace

TEST(FuzzRegressions, EveryFindingKeepsTheContract) {
  const fs::path root = fs::path(GEOM_SOURCE_DIR) / "tests" / "fuzz_regressions";
  size_t replayed = 0;
  for (const auto& target_dir : fs::directory_iterator(root)) {
    const std::string target = target_dir.path().filename().string();
    if (target == "viewer") continue;  // not an importer: tests/test_fuzz_viewer_file.cpp replays it
    for (const auto& file : fs::directory_iterator(target_dir.path())) {
      const std::string key = target + "/" + file.path().filename().string();
      SCOPED_TRACE(key);
      const std::string bytes = cli::slurp(file.path());
      const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
      EXPECT_EQ(geom_fuzz::import_one(target, data, bytes.size()), "");
      auto it = kFindings.find(key);
      ASSERT_NE(it, kFindings.end()) << "a finding without its entry in kFindings";
      // Replay as the target does and check the refusal itself.
      const std::string name = geom_fuzz::name_for(target, data, bytes.size());
      std::vector<uint8_t> in(bytes.begin(), bytes.end());
      if (target == "draco") in = geom_fuzz::draco_glb(data, bytes.size());
      geom::ImportResult r = geom::import_memory(name, in.data(), in.size(), geom_fuzz::fuzz_options());
      EXPECT_FALSE(r.ok) << it->second.what;
      EXPECT_NE(r.error.find(it->second.refusal), std::string::npos) << r.error;
      ++replayed;
    }
  }
  EXPECT_EQ(replayed, kFindings.size());
}
