// geombench's verdicts over result rows (tools/geombench/claims.h, size_law.h):
// each claim holds exactly at its bound and fails one pixel (or one step)
// beyond it, on many random rows; the pixel slack makes a claim that compares
// with a near-zero error meaningful (2 wrong pixels against 0 is within it).
#include <gtest/gtest.h>

#include <random>

#include "claims.h"
#include "size_law.h"

namespace {

using geombench::Row;

Row row(const std::string& scene, const std::string& t, int size, double wrong, size_t visible = 100000) {
  Row r;
  r.scene = scene, r.technique = t, r.size = size, r.visible = visible, r.cast = visible / 2, r.self = visible / 4;
  r.error_visible = wrong / double(visible);
  r.error_cast = wrong / double(r.cast);
  r.error_self = 0;
  r.time_ms = 1, r.time_kind = "wall";
  return r;
}

std::string line(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& l : lines)
    if (l.find(part) != std::string::npos) return l;
  return "";
}

bool holds(const std::string& l) { return l.rfind("holds:", 0) == 0; }

TEST(GeombenchClaims, EdgeMapsWithinTwoPixelsOfSsm) {
  std::mt19937 rng(7);
  for (int k = 0; k < 200; ++k) {
    const double ssm = double(rng() % 50);
    const int over = int(rng() % 5) - 1;  // -1 .. 3 pixels over ssm's
    const std::vector<Row> rows = {row("jenga", "ssm", 512, ssm), row("jenga", "edsm", 512, ssm + over)};
    const std::string l = line(geombench::claims(rows, {}, {}), "edsm@N wrong visible pixels");
    ASSERT_FALSE(l.empty());
    EXPECT_EQ(holds(l), over <= 2) << l;
  }
}

TEST(GeombenchClaims, SilhouetteMapAgainstAnExactEdsm) {
  // edsm exact (0 wrong cast pixels): sssm's 2 wrong pixels are within the slack, 3 are not.
  for (int wrong = 0; wrong <= 4; ++wrong) {
    const std::vector<Row> rows = {row("default", "edsm", 512, 0), row("default", "sssm", 512, wrong)};
    const std::string l = line(geombench::claims(rows, {}, {}), "sssm error_cast");
    ASSERT_FALSE(l.empty());
    EXPECT_EQ(holds(l), wrong <= 2) << l;
  }
}

TEST(GeombenchClaims, WarpsAgainstUniformAndSelfShadowing) {
  std::mt19937 rng(11);
  for (int k = 0; k < 200; ++k) {
    const double uniform = double(rng() % 1000), warp = double(rng() % 1200);
    std::vector<Row> rows = {row("jenga", "uniform", 1024, uniform), row("jenga", "lispsm", 1024, warp)};
    rows[1].error_self = double(rng() % 5) * 0.001;  // 0 .. 0.4%
    const std::vector<std::string> out = geombench::claims(rows, {}, {});
    const std::string w = line(out, "lispsm wrong visible pixels <= 1.1x uniform's");
    ASSERT_FALSE(w.empty());
    EXPECT_EQ(holds(w), warp <= 1.1 * uniform + 2) << w;
    const std::string s = line(out, "error_self <= 0.2%");
    ASSERT_FALSE(s.empty());
    EXPECT_EQ(holds(s), rows[1].error_self <= 0.002) << s;
  }
}

TEST(GeombenchClaims, CostIsJudgedOnTheMedian) {
  // Five cells, one outlier: the median decides.
  std::vector<Row> rows;
  const double q[5] = {1.5, 1.8, 1.9, 2.1, 12};
  for (int i = 0; i < 5; ++i) {
    rows.push_back(row("s" + std::to_string(i), "ssm", 512, 0));
    rows.push_back(row("s" + std::to_string(i), "edsm", 512, 0));
    rows.back().time_ms = q[i];
  }
  std::string l = line(geombench::claims(rows, {}, {}), "edsm time <= 2x");
  EXPECT_TRUE(holds(l)) << l;
  rows[5].time_ms = 2.5;  // the median moves to 2.1
  l = line(geombench::claims(rows, {}, {}), "edsm time <= 2x");
  EXPECT_FALSE(holds(l)) << l;
}

TEST(GeombenchSizeLaw, HardAndSoftTechniques) {
  using geombench::SizePoint;
  // Hard: falls by half and never steps up by more than 0.0002.
  EXPECT_TRUE(holds(
      geombench::size_law_lines({{"a", "ssm", 512, 0.004}, {"a", "ssm", 1024, 0.0041}, {"a", "ssm", 4096, 0.002}})[0]));
  EXPECT_FALSE(holds(geombench::size_law_lines(
      {{"a", "ssm", 512, 0.004}, {"a", "ssm", 1024, 0.00421}, {"a", "ssm", 4096, 0.001}})[0]));
  EXPECT_FALSE(holds(geombench::size_law_lines({{"a", "ssm", 512, 0.004}, {"a", "ssm", 4096, 0.0021}})[0]));
  // Soft: judged on the fraction error, no halving, 0.001 + 5% of slack.
  EXPECT_TRUE(holds(geombench::size_law_lines({{"a", "pcf-soft", 512, 0.02, true},
                                               {"a", "pcf-soft", 1024, 0.0209, true},
                                               {"a", "pcf-soft", 4096, 0.02, true}})[0]));
  EXPECT_FALSE(
      holds(geombench::size_law_lines({{"a", "pcf-soft", 512, 0.02, true}, {"a", "pcf-soft", 1024, 0.0221, true}})[0]));
  EXPECT_TRUE(
      holds(geombench::size_law_lines({{"a", "pcf-soft", 512, 0.02, true}, {"a", "pcf-soft", 1024, 0.0219, true}})[0]));
  // A row without the figure (-1: not measured) takes no part.
  EXPECT_TRUE(holds(geombench::size_law_lines({{"a", "pcf-soft", 512, 0.02, true},
                                               {"a", "pcf-soft", 1024, -1, true},
                                               {"a", "pcf-soft", 2048, 0.02, true}})[0]));
}

}  // namespace
