// `geombake inspect --json` lists a baked file's lights whole, with the names
// of KHR_lights_punctual, null where the light's type has no such field. The
// oracle is the importer's reading of the same glTF (geom::import_file): the
// bake must lose nothing of it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "cli_run.h"
#include "geom/import.h"
#include "scratch.h"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

struct Temp : testfs::Scratch {
  Temp() : testfs::Scratch("inspect_lights") {}
};

// The bundled scene with its lights replaced by `lights`, each placed by a node
// of its own (translation, rotation) added to the scene.
json scene_with(const json& lights, std::mt19937& rng) {
  std::ifstream in(std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf");
  json doc = json::parse(in);
  std::uniform_real_distribution<double> u(-1, 1);
  doc["extensions"]["KHR_lights_punctual"]["lights"] = lights;
  for (size_t i = 0; i < lights.size(); ++i) {
    double q[4] = {u(rng), u(rng), u(rng), u(rng)};
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    json node = {{"name", "light node " + std::to_string(i)},
                 {"translation", {3 * u(rng), 8 + u(rng), 3 * u(rng)}},
                 {"rotation", {q[0] / len, q[1] / len, q[2] / len, q[3] / len}},
                 {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}};
    doc["scenes"][0]["nodes"].push_back(doc["nodes"].size());
    doc["nodes"].push_back(node);
  }
  // The scene's own light nodes now point at lights that may not exist: drop their extension.
  for (size_t n = 0; n + lights.size() < doc["nodes"].size(); ++n) doc["nodes"][n].erase("extensions");
  return doc;
}

// Random lights of every type, with and without range, colour, intensity, cones, name.
json random_lights(std::mt19937& rng) {
  std::uniform_real_distribution<double> a(0.01, 1);
  const char* types[3] = {"directional", "point", "spot"};
  const char* names[4] = {"sun", "lamp \xc3\xa0 huile", "", "spot.001"};
  json lights = json::array();
  for (int i = 0; i < 2 + int(rng() % 4); ++i) {
    const std::string type = types[rng() % 3];
    json l = {{"type", type}};
    if (rng() % 4) l["name"] = names[rng() % 4];
    if (rng() % 2) l["color"] = {a(rng), a(rng), a(rng)};
    if (rng() % 2) l["intensity"] = 50 * a(rng);
    if (type != "directional" && rng() % 2) l["range"] = 5 + 20 * a(rng);
    if (type == "spot") {
      json spot = json::object();
      const double outer = 1.2 * a(rng) + 0.1;
      if (rng() % 2) spot["innerConeAngle"] = outer * a(rng) * 0.9;
      if (rng() % 2) spot["outerConeAngle"] = outer;
      l["spot"] = spot;
    }
    lights.push_back(l);
  }
  return lights;
}

void expect_vec3(const json& j, const double* v, const std::string& what) {
  ASSERT_TRUE(j.is_array()) << what << ": " << j.dump();
  ASSERT_EQ(j.size(), 3u) << what;
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(j[k].get<double>(), v[k]) << what << " " << k;
}

// One light of inspect's list against the importer's light.
void expect_light(const json& j, const geom::Light& e) {
  const bool directional = e.type == geom::LightType::Directional, point = e.type == geom::LightType::Point;
  const bool spot = e.type == geom::LightType::Spot;
  EXPECT_EQ(j.size(), 9u) << j.dump();
  EXPECT_EQ(j["name"], e.name);
  EXPECT_EQ(j["type"], directional ? "directional" : point ? "point" : "spot");
  if (directional) EXPECT_TRUE(j["position"].is_null()) << j.dump();
  if (!directional) expect_vec3(j["position"], e.position, "position");
  if (point) EXPECT_TRUE(j["direction"].is_null()) << j.dump();
  if (!point) expect_vec3(j["direction"], e.direction, "direction");
  if (directional || e.range == 0) EXPECT_TRUE(j["range"].is_null()) << j.dump();
  if (!directional && e.range > 0) EXPECT_DOUBLE_EQ(j["range"].get<double>(), e.range);
  const double color[3] = {e.color[0], e.color[1], e.color[2]};
  expect_vec3(j["color"], color, "color");
  EXPECT_DOUBLE_EQ(j["intensity"].get<double>(), double(e.intensity));
  if (!spot) EXPECT_TRUE(j["inner_cone_angle"].is_null() && j["outer_cone_angle"].is_null()) << j.dump();
  if (spot) {
    EXPECT_DOUBLE_EQ(j["inner_cone_angle"].get<double>(), e.inner_cone);
    EXPECT_DOUBLE_EQ(j["outer_cone_angle"].get<double>(), e.outer_cone);
  }
}

TEST(InspectLights, EveryFieldOfEveryLightType) {
  Temp t;
  std::mt19937 rng(27);
  int seen[3] = {0, 0, 0};
  for (int trial = 0; trial < 12; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const fs::path gltf = t.dir / ("lights" + std::to_string(trial) + ".gltf");
    const fs::path baked = t.dir / ("lights" + std::to_string(trial) + ".gbake");
    testfs::write_text(gltf, scene_with(random_lights(rng), rng).dump());
    const geom::ImportResult imported = geom::import_file(gltf.string());
    ASSERT_TRUE(imported.ok) << imported.error;
    const cli::Run bake = cli::run({"bake", "-q", gltf.string(), "-o", baked.string()}, t.dir / "run");
    ASSERT_EQ(bake.exit_code, 0) << bake.err;
    const cli::Run inspect = cli::run({"inspect", "--json", baked.string()}, t.dir / "run");
    ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
    const json report = json::parse(inspect.out);
    EXPECT_EQ(report["version"], "2.0");
    const json& lights = report["lights"];
    ASSERT_EQ(lights.size(), imported.scene.lights.size()) << inspect.out;
    for (size_t i = 0; i < lights.size(); ++i) {
      SCOPED_TRACE("light " + std::to_string(i));
      expect_light(lights[i], imported.scene.lights[i]);
      ++seen[int(imported.scene.lights[i].type)];
    }
  }
  for (int type = 0; type < 3; ++type) EXPECT_GT(seen[type], 0) << "light type " << type << " never drawn";
}

// A file without lights lists none; `--light` ones are listed as point or
// directional lights named "--light N".
TEST(InspectLights, NoLightsAndGivenLights) {
  Temp t;
  const fs::path obj = t.dir / "tri.obj", baked = t.dir / "tri.gbake";
  testfs::write_text(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n");
  ASSERT_EQ(cli::run({"bake", "-q", obj.string(), "-o", baked.string()}, t.dir / "run").exit_code, 0);
  cli::Run inspect = cli::run({"inspect", "--json", baked.string()}, t.dir / "run");
  ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
  EXPECT_EQ(json::parse(inspect.out)["lights"], json::array());
  ASSERT_EQ(cli::run({"bake", "-q", "--force", "--light", "1,2,3,1", "--light", "0,1,0,0", obj.string(), "-o",
                      baked.string()},
                     t.dir / "run")
                .exit_code,
            0);
  inspect = cli::run({"inspect", "--json", baked.string()}, t.dir / "run");
  const json lights = json::parse(inspect.out)["lights"];
  ASSERT_EQ(lights.size(), 2u) << inspect.out;
  EXPECT_EQ(lights[0]["name"], "--light 1");
  EXPECT_EQ(lights[0]["type"], "point");
  EXPECT_EQ(lights[0]["position"], json({1, 2, 3}));
  EXPECT_EQ(lights[1]["type"], "directional");
  EXPECT_EQ(lights[1]["direction"], json({-0.0, -1, -0.0}));
  EXPECT_TRUE(lights[1]["position"].is_null());
}

}  // namespace
