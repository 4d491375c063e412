// geom/baked_records.h with geom/baked_reader.h: what an engine reads a
// `.gbake` with, the two headers alone (this file includes no other geom
// header). Laws over real bakes by this build's geombake (the bundled default
// scene with its two lights and an extra one, and OpenArena's oa_dm1): every
// Record section's stride is its struct's size and it views as that struct;
// every plane index of every record, flag bits masked, lies inside the plane
// table of its own section family and item; record positions and planes are
// finite; quads' extrusion vectors are unit length after decoding; each light
// volume's records stand beside its planes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "geom/baked_file.h"
#include "geom/baked_reader.h"
#include "geom/baked_records.h"
#include "scratch.h"

namespace {

namespace fs = std::filesystem;
using geom::baked::File;
using geom::baked::Section;
using geom::baked::SectionType;

struct Scratch : testfs::Scratch {
  Scratch() : testfs::Scratch("geom_records") {}
};

bool finite3(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
bool finite3(const double* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// The plane table `records` index: same family, same item.
const Section* planes_of(const File& f, SectionType planes, uint32_t item) { return f.reader().find(planes, item); }

struct Plane {  // one F32x4 element of a plane table: (nx, ny, nz, d)
  float v[4];
};

void check_planes_finite(const Section& s) {
  ASSERT_EQ(s.stride, sizeof(Plane));
  const Plane* p = s.as<Plane>();
  ASSERT_NE(p, nullptr) << s.name;
  for (uint64_t i = 0; i < s.count; ++i)
    for (int k = 0; k < 4; ++k) ASSERT_TRUE(std::isfinite(p[i].v[k])) << s.name << " plane " << i;
}

// Checks every Record section of a baked file; `records`: how many it saw.
void check_file(const std::string& path, uint64_t& records) {
  File f;
  ASSERT_TRUE(f.load(path)) << f.error();
  records = 0;
  uint64_t quads = 0, sides = 0, caps = 0;
  for (const Section& s : f.reader().sections()) {
    if (s.format != geom::baked::Format::Record) continue;
    switch (s.type) {
      case SectionType::EsmQuads: {
        EXPECT_EQ(s.stride, sizeof(geom::EsmQuad));
        const geom::EsmQuad* q = s.as<geom::EsmQuad>();
        const Section* planes = planes_of(f, SectionType::EsmPlanes, s.item);
        EXPECT_TRUE(q && planes) << s.name;
        if (!q || !planes) break;
        check_planes_finite(*planes);
        for (uint64_t i = 0; i < s.count; ++i) {
          const geom::EsmQuad& r = q[i];
          ASSERT_TRUE(finite3(r.p0) && finite3(r.p1)) << "quad " << i;
          ASSERT_LT(r.plane_a & ~geom::EsmQuad::kFlip, planes->count) << "quad " << i;
          ASSERT_LT(r.plane_b & ~geom::EsmQuad::kFlip, planes->count) << "quad " << i;
          // The octahedral snorm16 q decodes to a unit vector.
          float x = std::max(-1.0f, r.q[0] / 32767.0f), y = std::max(-1.0f, r.q[1] / 32767.0f);
          float z = 1 - std::fabs(x) - std::fabs(y);
          if (z < 0) {
            const float ox = x, oy = y;
            x = (1 - std::fabs(oy)) * (ox >= 0 ? 1 : -1), y = (1 - std::fabs(ox)) * (oy >= 0 ? 1 : -1);
          }
          ASSERT_GT(std::sqrt(x * x + y * y + z * z), 0.5f) << "quad " << i;
        }
        quads += s.count;
        break;
      }
      case SectionType::VolumeSides:
      case SectionType::LightSides: {
        EXPECT_EQ(s.stride, sizeof(geom::SvSide));
        const geom::SvSide* r = s.as<geom::SvSide>();
        const Section* planes = planes_of(
            f, s.type == SectionType::VolumeSides ? SectionType::VolumePlanes : SectionType::LightPlanes, s.item);
        EXPECT_TRUE(r && planes) << s.name << " item " << s.item;
        if (!r || !planes) break;
        check_planes_finite(*planes);
        for (uint64_t i = 0; i < s.count; ++i) {
          ASSERT_TRUE(finite3(r[i].p0) && finite3(r[i].p1)) << s.name << " " << i;
          ASSERT_LT(r[i].plane_a & ~geom::SvSide::kSecond, planes->count) << s.name << " " << i;
          ASSERT_LT(r[i].plane_b & ~geom::SvSide::kFlip, planes->count) << s.name << " " << i;
        }
        sides += s.count;
        break;
      }
      case SectionType::VolumeCaps:
      case SectionType::LightCaps: {
        EXPECT_EQ(s.stride, sizeof(geom::SvCap));
        const geom::SvCap* r = s.as<geom::SvCap>();
        const Section* planes = planes_of(
            f, s.type == SectionType::VolumeCaps ? SectionType::VolumePlanes : SectionType::LightPlanes, s.item);
        EXPECT_TRUE(r && planes) << s.name << " item " << s.item;
        if (!r || !planes) break;
        for (uint64_t i = 0; i < s.count; ++i) {
          ASSERT_TRUE(finite3(r[i].a) && finite3(r[i].b) && finite3(r[i].c)) << s.name << " " << i;
          ASSERT_LT(r[i].plane & ~geom::SvCap::kDoubleSided, planes->count) << s.name << " " << i;
        }
        caps += s.count;
        break;
      }
      case SectionType::LightParams: {
        EXPECT_EQ(s.stride, sizeof(geom::LightRecord));
        const geom::LightRecord* l = s.as<geom::LightRecord>();
        const Section* names = f.reader().find(SectionType::LightNames);
        const Section* table = f.reader().find(SectionType::Lights);
        EXPECT_TRUE(l && names && table && table->count == s.count) << s.name;
        if (!l || !names) break;
        for (uint64_t i = 0; i < s.count; ++i) {
          ASSERT_LE(l[i].type, geom::LightRecord::kSpot) << "light " << i;
          ASSERT_LE(uint64_t(l[i].name_offset) + l[i].name_size, names->size) << "light " << i;
          ASSERT_TRUE(finite3(l[i].position) && finite3(l[i].direction) && finite3(l[i].color)) << "light " << i;
        }
        break;
      }
      default:
        ADD_FAILURE() << "a Record section no struct of baked_records.h describes: " << s.name;
    }
    records += s.count;
  }
  EXPECT_GT(quads, 0u) << path;
  EXPECT_GT(sides, 0u) << path;
  EXPECT_GT(caps, 0u) << path;
  // Every light of the lights table has its three volume sections.
  if (const Section* lights = f.reader().find(SectionType::Lights))
    for (uint32_t i = 0; i < lights->count; ++i) {
      EXPECT_NE(f.reader().find(SectionType::LightSides, i), nullptr) << "light " << i;
      EXPECT_NE(f.reader().find(SectionType::LightCaps, i), nullptr) << "light " << i;
      EXPECT_NE(f.reader().find(SectionType::LightPlanes, i), nullptr) << "light " << i;
    }
}

TEST(BakedRecords, AnEngineReadsEveryRecordSectionWithTheTwoHeaders) {
  Scratch s;
  const std::string scene = std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf";
  const std::string map = "/usr/share/games/openarena/baseoa/pak1-maps.pk3:maps/oa_dm1.bsp";
  const std::string a = (s.dir / "scene.gbake").string(), b = (s.dir / "map.gbake").string();
  ASSERT_EQ(
      std::system((std::string(GEOMBAKE_EXE) + " bake " + scene + " -o " + a + " --light 0.3,1,0.2,0 -q").c_str()), 0);
  ASSERT_EQ(std::system((std::string(GEOMBAKE_EXE) + " bake " + map + " -o " + b + " --light 0,0,500,1 -q").c_str()),
            0);
  uint64_t records = 0;
  check_file(a, records);
  EXPECT_GT(records, 100u);
  check_file(b, records);
  EXPECT_GT(records, 10000u);
}

}  // namespace
