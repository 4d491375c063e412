// The baked reader's float validation (geom/baked_reader.h, validate_floats):
// every bake of random scenes passes it; a file that is intact as a container
// (every checksum right) but holds one NaN, infinity or absurd value in any
// float a consumer hands to GL or Embree (positions, planes, frame, lights,
// the records' points) is refused, naming the section and the element.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geom/bake.h"
#include "geom/baked_reader.h"
#include "geom/baked_writer.h"

namespace {

namespace gb = geom::baked;

// A box (12 triangles) centred at c with half-size h.
void add_box(geom::Scene& s, const float c[3], float h) {
  const uint32_t base = uint32_t(s.vertex_count());
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) s.positions.push_back(c[k] + ((i >> k) & 1 ? h : -h));
  const uint32_t f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f)
    for (uint32_t v : t) s.indices.push_back(base + v);
  s.sources.resize(s.triangle_count());
}

// A random scene of boxes with one point and one directional light.
geom::Scene random_scene(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-50, 50);
  geom::Scene s;
  const int n = 1 + int(rng() % 4);
  for (int i = 0; i < n; ++i) {
    const float c[3] = {u(rng), u(rng), u(rng)};
    add_box(s, c, 0.5f + std::fabs(u(rng)) * 0.05f);
  }
  geom::Light point, sun;
  point.position[0] = u(rng), point.position[1] = 80, point.position[2] = u(rng);
  sun.type = geom::LightType::Directional;
  sun.direction[0] = 0.3, sun.direction[1] = -1, sun.direction[2] = 0.2;
  s.lights = {point, sun};
  return s;
}

std::vector<unsigned char> serialize(const std::vector<geom::BakedSection>& sections) {
  std::vector<unsigned char> bytes;
  std::string error;
  EXPECT_TRUE(geom::serialize_baked(sections, bytes, error)) << error;
  return bytes;
}

// Validates a serialized file; "" when it passes, else the error.
std::string validate(const std::vector<unsigned char>& bytes) {
  gb::Reader reader;
  if (!reader.open(bytes.data(), bytes.size())) return "container: " + reader.error();
  std::string error;
  return gb::validate_floats(reader, error) ? "" : error;
}

// Where a section's floats are: per element, how many from byte 0, and their width.
struct Floats {
  uint32_t per_element, width;
};
bool floats_of(const geom::BakedSection& s, Floats& f) {
  switch (s.format) {
    case gb::Format::F32x3:
      return f = {3, 4}, true;
    case gb::Format::F32x4:
      return f = {4, 4}, true;
    case gb::Format::F64x3:
      return f = {3, 8}, true;
    case gb::Format::F64x4:
      return f = {4, 8}, true;
    case gb::Format::Record:
      if (s.type == gb::SectionType::VolumeCaps || s.type == gb::SectionType::LightCaps) return f = {9, 4}, true;
      if (s.type == gb::SectionType::EsmQuads || s.type == gb::SectionType::VolumeSides ||
          s.type == gb::SectionType::LightSides)
        return f = {6, 4}, true;
      return false;
    default:
      return false;
  }
}

void store(geom::BakedSection& s, size_t at, uint32_t width, double v) {
  std::vector<unsigned char> bytes(s.data(), s.data() + s.size());
  if (width == 8)
    std::memcpy(&bytes[at], &v, 8);
  else {
    const float f = float(v);
    std::memcpy(&bytes[at], &f, 4);
  }
  s.bytes = std::move(bytes);
  s.view = nullptr, s.view_size = 0, s.keep.reset();
}

TEST(BakedFloats, EveryBakePasses) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const geom::BakeResult r = geom::bake_scene(random_scene(rng), "random");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(validate(serialize(r.sections)), "") << "trial " << trial;
  }
}

// One bad value in one float of one element of every float section, as an
// intact container: refused, naming the section's index, its name and the element.
TEST(BakedFloats, OneBadFloatAnywhereIsRefusedByName) {
  std::mt19937 rng(11);
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity(), 1e30, -3e16};
  size_t refused = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const geom::BakeResult r = geom::bake_scene(random_scene(rng), "random");
    ASSERT_TRUE(r.ok) << r.error;
    for (size_t i = 0; i < r.sections.size(); ++i) {
      Floats f;
      if (!floats_of(r.sections[i], f) || r.sections[i].count == 0) continue;
      for (double v : bad) {
        std::vector<geom::BakedSection> sections = r.sections;
        geom::BakedSection& s = sections[i];
        const uint64_t element = rng() % s.count;
        const uint32_t component = rng() % f.per_element;
        store(s, size_t(element * s.stride + component * f.width), f.width, v);
        const std::string error = validate(serialize(sections));
        SCOPED_TRACE(s.name + " element " + std::to_string(element) + " = " + std::to_string(v));
        ASSERT_NE(error, "");
        EXPECT_EQ(error.rfind("container", 0), std::string::npos) << error;
        EXPECT_NE(error.find("section " + std::to_string(i) + " '" + s.name + "'"), std::string::npos) << error;
        EXPECT_NE(error.find("element " + std::to_string(element)), std::string::npos) << error;
        ++refused;
      }
    }
  }
  EXPECT_GT(refused, 100u);
}

// A light section: a directional light without a direction, a point light
// beyond the limit, a w other than 0 or 1, a direction too long: refused; the
// limits themselves pass.
TEST(BakedFloats, LightsWithinTheLimits) {
  const double cases[][4] = {{0, 0, 0, 0},     {1e-20, 0, 0, 0},   {2e18, 0, 0, 1},
                             {1, 1, 1, 1e-20}, {1e20, 1e20, 0, 0}, {2, 0, 0, 2}};
  const double fine[][4] = {{1e15, -1e15, 0, 1}, {0, -1, 0, 0}, {1e-15, 0, 0, 0}};
  for (int good = 0; good < 2; ++good)
    for (size_t c = 0; c < (good ? 3u : 6u); ++c) {
      const double* h = good ? fine[c] : cases[c];
      std::vector<double> light(h, h + 4);
      std::vector<geom::BakedSection> sections = {
          geom::make_baked_section(gb::SectionType::Lights, gb::Format::F64x4, 32, "lights", light)};
      const std::string error = validate(serialize(sections));
      SCOPED_TRACE(std::to_string(h[0]) + "," + std::to_string(h[1]) + "," + std::to_string(h[2]) + "," +
                   std::to_string(h[3]));
      if (good) {
        EXPECT_EQ(error, "");
      } else {
        EXPECT_NE(error.find("section 0 'lights' (lights): element 0"), std::string::npos) << error;
      }
    }
}

// Planes: a normal that is no unit normal, an offset over the limit: refused.
TEST(BakedFloats, PlanesHaveUnitNormals) {
  for (const std::vector<float>& plane : {std::vector<float>{2, 0, 0, 1}, std::vector<float>{0, 1, 0, 1e16f}}) {
    std::vector<geom::BakedSection> sections = {
        geom::make_baked_section(gb::SectionType::FacePlanes, gb::Format::F32x4, 16, "face_planes", plane)};
    EXPECT_NE(validate(serialize(sections)).find("element 0: plane"), std::string::npos);
  }
  std::vector<float> fine = {0, 0, 0, 0, 0.6f, 0.8f, 0, -1e15f};
  std::vector<geom::BakedSection> sections = {
      geom::make_baked_section(gb::SectionType::FacePlanes, gb::Format::F32x4, 16, "face_planes", fine)};
  EXPECT_EQ(validate(serialize(sections)), "");
}

}  // namespace
