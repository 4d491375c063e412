// `geombake focus` and `geombake inspect` on hostile input, as the baker is
// held: `Error: FILE: cause`, exit 1, never a singular or non-finite matrix
// with exit 0, never raw control bytes on the terminal.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "cli_run.h"
#include "geom/baked_reader.h"
#include "geom/baked_writer.h"
#include "scratch.h"

namespace {

namespace fs = std::filesystem;

struct Temp : testfs::Scratch {
  Temp() : testfs::Scratch("focus_inspect_hostile") {}
};

// A frame with these pieces (JSON text).
std::string frame(const std::string& light, const std::string& fovy = "60", const std::string& aspect = "1.5",
                  const std::string& eye = "[0, 2, 10]") {
  return "{\"camera\": {\"eye\": " + eye + ", \"target\": [0, 0, 0], \"up\": [0, 1, 0], \"fovy_degrees\": " + fovy +
         ", \"aspect\": " + aspect + ", \"near\": 0.1, \"far\": 100}, \"light\": " + light +
         ", \"scene_bounds\": {\"min\": [-5, -1, -5], \"max\": [5, 3, 5]}}";
}

cli::Run focus(const Temp& t, const std::string& text) {
  const fs::path file = t.dir / "frame.json";
  std::ofstream(file, std::ios::binary) << text;
  return cli::run({"focus", file.string()}, t.dir / "run");
}

// |det| against Hadamard's bound (the product of the column lengths).
bool usable(const std::vector<double>& m) {
  double bound = 1;
  for (int c = 0; c < 4; ++c) {
    double l = 0;
    for (int r = 0; r < 4; ++r) l += m[4 * c + r] * m[4 * c + r];
    bound *= std::sqrt(l);
  }
  auto at = [&](int r, int c) { return m[4 * c + r]; };
  double det = 0;
  for (int c = 0; c < 4; ++c) {
    double n[9];
    int k = 0;
    for (int r = 1; r < 4; ++r)
      for (int cc = 0; cc < 4; ++cc)
        if (cc != c) n[k++] = at(r, cc);
    det +=
        (c % 2 ? -1 : 1) * at(0, c) *
        (n[0] * (n[4] * n[8] - n[5] * n[7]) - n[1] * (n[3] * n[8] - n[5] * n[6]) + n[2] * (n[3] * n[7] - n[4] * n[6]));
  }
  return std::isfinite(det) && std::fabs(det) > 1e-12 * bound;
}

TEST(FocusHostile, AbsurdFramesAreErrorsNotSingularMatrices) {
  Temp t;
  const std::string sun = "{\"type\": \"directional\", \"direction\": [0.3, -1, 0.2]}";
  const std::string bad[] = {
      frame("{\"type\": \"directional\", \"direction\": [1e154, -1e154, 0]}"),
      frame("{\"type\": \"directional\", \"direction\": [1e200, 0, 0]}"),
      frame("{\"type\": \"point\", \"position\": [2e18, 5, 0]}"),
      frame(sun, "1e-300"),
      frame(sun, "60", "1e300"),
      frame(sun, "60", "1e-300"),
      frame(sun, "60", "1.5", "[1e19, 2, 10]"),
      frame(sun) + std::string("\0{\"more\": 1}", 12),
      frame(sun) + std::string("\0", 1),
      frame(sun) + " trailing",
  };
  for (const std::string& text : bad) {
    const cli::Run r = focus(t, text);
    SCOPED_TRACE(text);
    EXPECT_EQ(r.exit_code, 1) << cli::describe(r);
    EXPECT_EQ(r.err.rfind("Error: " + (t.dir / "frame.json").string() + ": ", 0), 0u) << r.err;
    EXPECT_EQ(r.out, "");
  }
}

// Random frames, the hard ones among them (light along the view, behind the
// viewer, grazing): every matrix printed is finite and not singular.
TEST(FocusHostile, EveryPrintedMatrixIsUsable) {
  Temp t;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 40; ++trial) {
    char light[256];
    if (trial % 3 == 0)
      std::snprintf(light, sizeof light, "{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g]}",
                    trial % 2 ? 0.0 : u(rng), trial % 2 ? 0.0 : u(rng) - 1.1, trial % 2 ? -1.0 : u(rng));
    else
      std::snprintf(light, sizeof light, "{\"type\": \"point\", \"position\": [%.17g, %.17g, %.17g]}", 8 * u(rng),
                    1 + 6 * std::fabs(u(rng)), 12 * u(rng));
    const char* methods[] = {"psm", "lispsm", "uniform"};
    std::string text = frame(light);
    text.insert(text.size() - 1, std::string(", \"method\": \"") + methods[trial % 3] + "\"");
    const cli::Run r = focus(t, text);
    SCOPED_TRACE(text);
    ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
    const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.out;
    ASSERT_EQ(j["matrix"].size(), 16u);
    std::vector<double> m;
    for (const auto& v : j["matrix"]) {
      ASSERT_TRUE(v.is_number()) << r.out;
      m.push_back(v.get<double>());
    }
    EXPECT_TRUE(usable(m)) << r.out;
  }
}

// A topology report holding terminal escapes, a bell and a NUL: printed with
// every control byte escaped.
TEST(InspectHostile, TextSectionsAreEscaped) {
  Temp t;
  const std::string report = std::string("{\"x\": \"\x1b[2J\x1b]0;owned\x07\", \"y\": 1}\r\n\t") + '\0' + "end";
  std::vector<char> text(report.begin(), report.end());
  std::vector<geom::BakedSection> sections = {geom::make_baked_section(geom::baked::SectionType::TopologyReport,
                                                                       geom::baked::Format::Utf8, 1, "topology", text)};
  const fs::path file = t.dir / "escape.gbake";
  std::string error;
  ASSERT_TRUE(geom::write_baked(file.string(), sections, error)) << error;
  const cli::Run r = cli::run({"inspect", "-v", file.string()}, t.dir / "run");
  ASSERT_EQ(r.exit_code, 0) << cli::describe(r);
  const size_t at = r.out.find("topology: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string line = r.out.substr(at);
  for (char c : line.substr(0, line.size() - 1))  // the line's own newline aside
    EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "raw byte " << int(c) << " in: " << line;
  EXPECT_NE(line.find("\\x1b[2J"), std::string::npos) << line;
  EXPECT_NE(line.find("\\x07"), std::string::npos) << line;
  EXPECT_NE(line.find("\\x00end"), std::string::npos) << line;
}

}  // namespace
