// geombench: the quick run (CI keeps the tool working) and the exact reference
// it measures every technique against, checked on a case computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geom/shadow_reference.h"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, sep)) out.push_back(item);
  return out;
}

// Side view of the hand-computed case (camera above and in front, looking at
// the origin; the light straight down, w = 0):
//
//          eye (0, 6, 8)
//             \
//              \        occluder: square |x|,|z| <= 1 at y = 1, facing up
//     ==========\==     (its top lit: it faces the light)
//     ___________\___________ ground y = 0, |x|,|z| <= 10, facing up
//            |////|  shadow: exactly the square |x|,|z| < 1 under it,
//                    of which the part z > -0.4 is visible in front of it
// Every pixel's ray is intersected with the two planes in closed form.
TEST(GeombenchReference, SquareOccluderOverGroundUnderOverheadLight) {
  const float a = 1, h = 1, g = 10;
  std::vector<float> pos = {-g, 0, -g, -g, 0, g, g, 0, g, g, 0, -g,   // ground, counter-clockwise from above
                            -a, h, -a, -a, h, a, a, h, a, a, h, -a};  // occluder
  std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  geom::Camera cam;
  const float eye[3] = {0, 6, 8};
  for (int k = 0; k < 3; ++k) cam.eye[k] = eye[k], cam.target[k] = 0, cam.up[k] = k == 1;
  cam.fovy_deg = 50, cam.width = 128, cam.height = 96, cam.near_plane = 0.1f, cam.far_plane = 100;
  const double towards_light[4] = {0, 1, 0, 0};
  const geom::Light light = geom::light_from_homogeneous(towards_light);
  const geom::ShadowReference ref =
      geom::shadow_reference(geom::positions_of(pos.data(), 8), idx.data(), idx.size(), cam, light);
  ASSERT_TRUE(ref.ok) << ref.error;
  ASSERT_EQ(ref.mask.size(), size_t(128 * 96));

  // The camera frame: forward f, right r = f x up, true up u = r x f.
  const double len = std::sqrt(36.0 + 64.0);
  const double f[3] = {0, -6 / len, -8 / len}, r[3] = {1, 0, 0}, u[3] = {0, 8 / len, -6 / len};
  const double t = std::tan(25.0 * M_PI / 180), aspect = 128.0 / 96.0;
  size_t checked = 0, shadowed = 0, occluder = 0, uncertain = 0;
  for (int py = 0; py < 96; ++py)
    for (int px = 0; px < 128; ++px) {
      const double sx = (2 * (px + 0.5) / 128 - 1) * t * aspect, sy = (1 - 2 * (py + 0.5) / 96) * t;
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = f[k] + sx * r[k] + sy * u[k];
      uint8_t expect = 128;
      const double to = (h - eye[1]) / d[1];  // the occluder's plane
      const double ox = eye[0] + to * d[0], oz = eye[2] + to * d[2];
      const double tg = -eye[1] / d[1];  // the ground's plane
      const double gx = eye[0] + tg * d[0], gz = eye[2] + tg * d[2];
      if (d[1] < 0 && std::fabs(ox) <= a && std::fabs(oz) <= a) {
        expect = 255, ++occluder;
      } else if (d[1] < 0 && std::fabs(gx) <= g && std::fabs(gz) <= g) {
        expect = std::fabs(gx) < a && std::fabs(gz) < a ? 0 : 255;
      }
      const size_t i = size_t(py) * 128 + px;
      if (ref.uncertain[i]) {
        ++uncertain;
        continue;
      }
      ++checked;
      shadowed += expect == 0;
      EXPECT_EQ(int(ref.mask[i]), int(expect)) << "pixel " << px << ", " << py << " ground " << gx << ", " << gz;
    }
  EXPECT_GT(shadowed, 100u);  // the visible strip of shadow is really there
  EXPECT_GT(occluder, 200u);
  EXPECT_LT(uncertain, checked / 10);  // the uncertain band is thin
}

// The same occluder under a point light right above its centre: the shadow
// is the square scaled by L / (L - h) (similar triangles), here 4 / 3.
TEST(GeombenchReference, PointLightShadowScalesBySimilarTriangles) {
  const float a = 1, h = 1, g = 10, L = 4;
  std::vector<float> pos = {-g, 0, -g, -g, 0, g, g, 0, g, g, 0, -g, -a, h, -a, -a, h, a, a, h, a, a, h, -a};
  std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  geom::Camera cam;  // straight down from far above: the occluder hides only |x|,|z| < a * 20 / 19
  cam.eye[0] = 0, cam.eye[1] = 20, cam.eye[2] = 0, cam.up[0] = 0, cam.up[1] = 0, cam.up[2] = -1;
  cam.fovy_deg = 20, cam.width = 100, cam.height = 100, cam.near_plane = 1, cam.far_plane = 100;
  const double at[4] = {0, L, 0, 1};
  const geom::Light light = geom::light_from_homogeneous(at);
  const geom::ShadowReference ref =
      geom::shadow_reference(geom::positions_of(pos.data(), 8), idx.data(), idx.size(), cam, light);
  ASSERT_TRUE(ref.ok) << ref.error;
  const double t = std::tan(10.0 * M_PI / 180), s = a * L / (L - h), hide = a * 20 / 19;
  size_t shadowed = 0;
  for (int py = 0; py < 100; ++py)
    for (int px = 0; px < 100; ++px) {
      const double x = 20 * (2 * (px + 0.5) / 100 - 1) * t, z = -20 * (1 - 2 * (py + 0.5) / 100) * t;  // on the ground
      uint8_t expect = 255;
      if (std::fabs(x) < hide && std::fabs(z) < hide)
        expect = 255;  // the occluder's lit top
      else if (std::fabs(x) < s && std::fabs(z) < s)
        expect = 0;
      const size_t i = size_t(py) * 100 + px;
      if (ref.uncertain[i]) continue;
      shadowed += expect == 0;
      EXPECT_EQ(int(ref.mask[i]), int(expect)) << "pixel " << px << ", " << py;
    }
  EXPECT_GT(shadowed, 50u);
}

#ifdef GEOMBENCH_EXE
TEST(GeombenchQuick, WritesTableCsvJsonSvg) {
  const std::string dir = std::string(GEOM_BINARY_DIR) + "/test_geombench_out";
  // -o names a folder that does not exist yet: geombench creates it.
  ASSERT_EQ(std::system(("rm -rf '" + dir + "' '" + dir + ".txt'").c_str()), 0);
  const std::string cmd = std::string("'") + GEOMBENCH_EXE + "' --quick -o '" + dir + "' > '" + dir + ".txt' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + ".txt");
  const std::string out = slurp(dir + ".txt");
  EXPECT_NE(out.find("technique"), std::string::npos);
  EXPECT_NE(out.find("Best technique at each time budget"), std::string::npos);

  // CSV: the required columns, fractions in [0, 1], the shadow volumes ~exact.
  std::stringstream csv(slurp(dir + "/results.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const std::vector<std::string> header = split(line, ',');
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (const char* c :
       {"scene", "technique", "shadow_map_size", "time_ms", "time_kind", "error_visible", "error_boundary"})
    ASSERT_TRUE(col.count(c)) << "missing column " << c;
  std::map<std::string, int> per_scene;
  size_t rows = 0, sv_rows = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> v = split(line, ',');
    ASSERT_EQ(v.size(), header.size()) << line;
    ++rows, ++per_scene[v[col["scene"]]];
    const double ev = std::stod(v[col["error_visible"]]), eb = std::stod(v[col["error_boundary"]]);
    const double ms = std::stod(v[col["time_ms"]]);
    EXPECT_TRUE(ev >= 0 && ev <= 1) << line;
    EXPECT_TRUE(eb >= 0 && eb <= 1) << line;
    EXPECT_TRUE(ms >= 0 && std::isfinite(ms)) << line;
    EXPECT_TRUE(v[col["time_kind"]] == "gpu" || v[col["time_kind"]] == "wall") << line;
    const std::string t = v[col["technique"]];
    const int size = std::stoi(v[col["shadow_map_size"]]);
    if (t.rfind("sv", 0) == 0) {
      ++sv_rows;
      EXPECT_EQ(size, 0) << line;
      EXPECT_LE(ev, 0.001) << "shadow volumes must match the reference: " << line;
    } else {
      EXPECT_TRUE(size == 256 || size == 1024) << line;
    }
  }
  EXPECT_EQ(per_scene.size(), 3u);
  EXPECT_GE(rows, 3u * 17);
  EXPECT_EQ(sv_rows, 9u);

  // JSON: parses, holds the same rows and the bake table with its ratios.
  const nlohmann::json j = nlohmann::json::parse(slurp(dir + "/results.json"), nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_EQ(j["results"].size(), rows);
  EXPECT_EQ(j["quick"], true);
  ASSERT_EQ(j["bake"].size(), 6u);  // 2 meshes x (bake, meshopt, openmesh)
  for (const auto& b : j["bake"]) {
    EXPECT_GT(b["triangles_per_second"].get<double>(), 0);
    EXPECT_GT(b["speed_vs_meshopt"].get<double>(), 0);
  }
  EXPECT_FALSE(j["best_at_budget"].empty());

  // SVG: a complete document with a panel per scene and a line per technique.
  const std::string svg = slurp(dir + "/plot.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  for (const auto& s : per_scene) EXPECT_NE(svg.find(">" + s.first + "</text>"), std::string::npos) << s.first;
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_FALSE(slurp(dir + "/summary.md").empty());
  if (!HasFailure()) EXPECT_EQ(std::system(("rm -rf '" + dir + "' '" + dir + ".txt'").c_str()), 0);  // kept on failure
}

TEST(GeombenchQuick, BadUsageFailsCleanly) {
  EXPECT_NE(std::system((std::string("'") + GEOMBENCH_EXE + "' --sizes 3 > /dev/null 2>&1").c_str()), 0);
  EXPECT_NE(std::system((std::string("'") + GEOMBENCH_EXE + "' --techniques nope > /dev/null 2>&1").c_str()), 0);
  EXPECT_NE(
      std::system((std::string("'") + GEOMBENCH_EXE + "' --quick --no-bake -o /dev/null/dir > /dev/null 2>&1").c_str()),
      0);
}
#endif

}  // namespace
