// libgeom/src/draco_guard.cpp: libdraco's texture-coordinate decoders with the
// orientation count bounded by the corners.
//
// Laws checked:
//   - the definitions the dynamic linker binds libdraco's calls to are ours, not
//     libdraco's (else hostile streams would loop for seconds again);
//   - the guarded decoders decode right: real and random meshes with texture
//     coordinates, encoded by libdraco's own encoder with the portable
//     texture-coordinate prediction, decode to their texture coordinates within
//     the quantisation step, corner by corner, and the guard never refuses them;
//     the legacy streams of the shared Draco test data decode too;
//   - the guard refuses every absurd count: each 4-byte window of those streams
//     set to 2^31 - 1 is decoded or refused within a second of CPU, never both
//     refused by the guard and decoded, and in every stream at least one window
//     (the orientation count) is refused by the guard, naming the count.
// Without the bound the windows that hit the count take 2 to 30 s each inside
// libdraco (checked by hand: the test fails).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "cli_run.h"
#include "draco/compression/decode.h"
#include "draco/compression/encode.h"
#include "draco/io/mesh_io.h"
#include "draco/mesh/triangle_soup_mesh_builder.h"
#include "importers.h"

namespace fs = std::filesystem;

namespace {

const std::string kData = GEOM_TEST_DATA;

// The four instantiations libdraco.so uses and draco_guard.cpp replaces.
const char* const kGuarded[] = {
    "_ZN5draco44MeshPredictionSchemeTexCoordsPortableDecoderIiNS_37PredictionSchemeWrapDecodingTransformIiiEENS_"
    "24MeshPredictionSchemeDataINS_11CornerTableEEEE20DecodePredictionDataEPNS_13DecoderBufferE",
    "_ZN5draco36MeshPredictionSchemeTexCoordsDecoderIiNS_37PredictionSchemeWrapDecodingTransformIiiEENS_"
    "24MeshPredictionSchemeDataINS_11CornerTableEEEE20DecodePredictionDataEPNS_13DecoderBufferE",
    "_ZN5draco44MeshPredictionSchemeTexCoordsPortableDecoderIiNS_37PredictionSchemeWrapDecodingTransformIiiEENS_"
    "24MeshPredictionSchemeDataINS_24MeshAttributeCornerTableEEEE20DecodePredictionDataEPNS_13DecoderBufferE",
    "_ZN5draco36MeshPredictionSchemeTexCoordsDecoderIiNS_37PredictionSchemeWrapDecodingTransformIiiEENS_"
    "24MeshPredictionSchemeDataINS_24MeshAttributeCornerTableEEEE20DecodePredictionDataEPNS_13DecoderBufferE",
};

uint64_t guard_checks() {
  uint64_t n = 0;
  for (int i = 0; i < 4; ++i) n += geom::detail::draco_guard_checks(i);
  return n;
}

std::unique_ptr<draco::Mesh> decode(const char* data, size_t size, std::string* refusal = nullptr) {
  draco::DecoderBuffer buffer;
  buffer.Init(data, size);
  draco::Decoder decoder;
  geom::detail::draco_guard_refusal();
  auto r = decoder.DecodeMeshFromBuffer(&buffer);
  const std::string guard = geom::detail::draco_guard_refusal();
  if (refusal) *refusal = guard;
  return r.ok() ? std::move(r).value() : nullptr;
}

std::string encode(const draco::Mesh& mesh, int speed) {
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  encoder.SetSpeedOptions(speed, speed);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  EXPECT_TRUE(
      encoder
          .SetAttributePredictionScheme(draco::GeometryAttribute::TEX_COORD, draco::MESH_PREDICTION_TEX_COORDS_PORTABLE)
          .ok());
  draco::EncoderBuffer out;
  const draco::Status s = encoder.EncodeMeshToBuffer(mesh, &out);
  EXPECT_TRUE(s.ok()) << s.error_msg_string();
  return std::string(out.data(), out.size());
}

struct Corner {
  float p[3], uv[2];
};

std::vector<Corner> corners(const draco::Mesh& mesh) {
  const draco::PointAttribute* pos = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  const draco::PointAttribute* tex = mesh.GetNamedAttribute(draco::GeometryAttribute::TEX_COORD);
  std::vector<Corner> out;
  if (!pos || !tex) return out;
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    Corner c[3];
    for (int k = 0; k < 3; ++k) {
      pos->ConvertValue<float, 3>(pos->mapped_index(mesh.face(f)[k]), c[k].p);
      tex->ConvertValue<float, 2>(tex->mapped_index(mesh.face(f)[k]), c[k].uv);
    }
    out.insert(out.end(), c, c + 3);
  }
  return out;
}

// Every decoded corner has an original corner within the quantisation step of
// its position whose texture coordinate is within the step of its own (the
// encoder reorders faces and corners, so corners are matched through a grid),
// and no face was lost but those that quantisation made degenerate (two
// corners within two steps), which Draco's encoder drops.
void expect_same_corners(const std::vector<Corner>& original, const std::vector<Corner>& decoded) {
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  float ulo[2] = {1e30f, 1e30f}, uhi[2] = {-1e30f, -1e30f};
  for (const Corner& c : original) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], c.p[k]), hi[k] = std::max(hi[k], c.p[k]);
    for (int k = 0; k < 2; ++k) ulo[k] = std::min(ulo[k], c.uv[k]), uhi[k] = std::max(uhi[k], c.uv[k]);
  }
  // Draco quantises over the largest extent, 1 where it is 0.
  float extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}),
        uv_extent = std::max(uhi[0] - ulo[0], uhi[1] - ulo[1]);
  if (extent <= 0) extent = 1;
  if (uv_extent <= 0) uv_extent = 1;
  const float step = extent / float((1 << 14) - 1), cell = 4 * step, uv_step = uv_extent / float((1 << 12) - 1);
  auto near = [&](const float* a, const float* b, float d) {
    return std::fabs(a[0] - b[0]) <= d && std::fabs(a[1] - b[1]) <= d && std::fabs(a[2] - b[2]) <= d;
  };
  size_t sound = 0;  // original faces no quantisation can collapse
  for (size_t f = 0; f + 2 < original.size(); f += 3)
    sound +=
        !(near(original[f].p, original[f + 1].p, 2 * step) || near(original[f + 1].p, original[f + 2].p, 2 * step) ||
          near(original[f + 2].p, original[f].p, 2 * step));
  EXPECT_LE(decoded.size(), original.size());
  EXPECT_GE(decoded.size(), 3 * sound);
  auto key = [](int x, int y, int z) {
    return (int64_t(x) * 73856093) ^ (int64_t(y) * 19349663) ^ (int64_t(z) * 83492791);
  };
  auto cellof = [&](float v, int k) { return int(std::floor((v - lo[k]) / cell)); };
  std::unordered_multimap<int64_t, size_t> grid;
  for (size_t i = 0; i < original.size(); ++i)
    grid.emplace(key(cellof(original[i].p[0], 0), cellof(original[i].p[1], 1), cellof(original[i].p[2], 2)), i);
  size_t bad = 0;
  for (const Corner& d : decoded) {
    bool found = false;
    const int cx = cellof(d.p[0], 0), cy = cellof(d.p[1], 1), cz = cellof(d.p[2], 2);
    for (int dx = -1; dx <= 1 && !found; ++dx)
      for (int dy = -1; dy <= 1 && !found; ++dy)
        for (int dz = -1; dz <= 1 && !found; ++dz) {
          auto range = grid.equal_range(key(cx + dx, cy + dy, cz + dz));
          for (auto it = range.first; it != range.second && !found; ++it) {
            const Corner& o = original[it->second];
            const float uv_tol = 2 * uv_step + 1e-5f * (1 + std::fabs(o.uv[0]) + std::fabs(o.uv[1]));
            found = near(o.p, d.p, 2 * step) && std::fabs(o.uv[0] - d.uv[0]) <= uv_tol &&
                    std::fabs(o.uv[1] - d.uv[1]) <= uv_tol;
          }
        }
    bad += !found;
  }
  EXPECT_EQ(bad, 0u) << "of " << decoded.size() << " corners";
}

// A bumpy sphere with a seam, its texture coordinates mirrored in random bands
// (so both orientations occur), n x m quads.
std::unique_ptr<draco::Mesh> random_sphere(std::mt19937& rng, int n, int m) {
  std::uniform_real_distribution<float> bump(0.9f, 1.1f);
  std::vector<float> radius(size_t((n + 1) * (m + 1)));
  for (float& r : radius) r = bump(rng);
  for (int i = 0; i <= n; ++i) radius[size_t(i * (m + 1) + m)] = radius[size_t(i * (m + 1))];  // closed seam
  std::vector<int> mirror(static_cast<size_t>(n));
  for (int& v : mirror) v = int(rng() % 3 == 0);
  auto pos = [&](int i, int j, float* p) {
    const float th = float(M_PI) * float(i) / float(n), ph = 2 * float(M_PI) * float(j) / float(m);
    const float r = (i == 0 || i == n) ? 1.0f : radius[size_t(i * (m + 1) + j)];
    p[0] = r * std::sin(th) * std::cos(ph), p[1] = r * std::cos(th), p[2] = r * std::sin(th) * std::sin(ph);
  };
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(2 * n * m);
  const int pa = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int ta = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  int f = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int q[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
      float p[4][3], t[4][2];
      for (int k = 0; k < 4; ++k) {
        pos(q[k][0], q[k][1], p[k]);
        const float u = float(q[k][1]) / float(m);
        t[k][0] = mirror[size_t(i)] ? 1 - u : u, t[k][1] = float(q[k][0]) / float(n);
      }
      static const int kTris[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (const int* tri : kTris) {
        builder.SetAttributeValuesForFace(pa, draco::FaceIndex(f), p[tri[0]], p[tri[1]], p[tri[2]]);
        builder.SetAttributeValuesForFace(ta, draco::FaceIndex(f), t[tri[0]], t[tri[1]], t[tri[2]]);
        ++f;
      }
    }
  return builder.Finalize();
}

// Sets each 4-byte window of `stream` to 2^31 - 1 in turn and decodes it:
// returns how many windows the guard refused (naming the count).
size_t absurd_windows(const std::string& stream) {
  size_t refused = 0;
  for (size_t at = 0; at + 4 <= stream.size(); ++at) {
    std::string damaged = stream;
    const unsigned char big[4] = {0xff, 0xff, 0xff, 0x7f};
    std::memcpy(&damaged[at], big, 4);
    std::string refusal;
    const std::clock_t start = std::clock();
    const bool decoded = decode(damaged.data(), damaged.size(), &refusal) != nullptr;
    const double cpu = double(std::clock() - start) / CLOCKS_PER_SEC;
    EXPECT_LT(cpu, 1.0 * cli::kSanitizerFactor) << "decoding with 2^31 - 1 at byte " << at << " took " << cpu << " s";
    if (!refusal.empty()) {
      EXPECT_FALSE(decoded) << "the guard refused, yet the stream decoded";
      EXPECT_NE(refusal.find("orientations for"), std::string::npos) << refusal;
      ++refused;
    }
  }
  return refused;
}

}  // namespace

TEST(DracoGuard, TheDynamicLinkerBindsOurDecoders) {
  for (const char* name : kGuarded) {
    SCOPED_TRACE(name);
    void* sym = dlsym(RTLD_DEFAULT, name);
    ASSERT_NE(sym, nullptr);
    Dl_info info;
    ASSERT_NE(dladdr(sym, &info), 0);
    EXPECT_EQ(std::string(info.dli_fname).find("libdraco"), std::string::npos) << info.dli_fname;
  }
}

TEST(DracoGuard, RealMeshesWithTextureCoordinatesRoundTrip) {
  std::vector<fs::path> objs;
  for (const char* dir : {"/draco", ""})
    for (const auto& e : fs::directory_iterator(kData + dir))
      if (e.path().extension() == ".obj") objs.push_back(e.path());
  const fs::path assimp = "/usr/share/assimp/models/OBJ";
  if (fs::exists(assimp))
    for (const auto& e : fs::directory_iterator(assimp))
      if (e.path().extension() == ".obj") objs.push_back(e.path());
  size_t tested = 0;
  for (const fs::path& p : objs) {
    auto read = draco::ReadMeshFromFile(p.string());
    if (!read.ok()) continue;
    const draco::Mesh& mesh = *read.value();
    const draco::PointAttribute* tex = mesh.GetNamedAttribute(draco::GeometryAttribute::TEX_COORD);
    if (mesh.num_faces() == 0 || !tex || tex->num_components() != 2) continue;
    SCOPED_TRACE(p.string());
    for (int speed : {0, 5}) {
      const std::string stream = encode(mesh, speed);
      const uint64_t before = guard_checks();
      std::string refusal;
      auto decoded = decode(stream.data(), stream.size(), &refusal);
      ASSERT_NE(decoded, nullptr) << refusal;
      EXPECT_EQ(refusal, "");
      EXPECT_GT(guard_checks(), before) << "the stream did not use the texture-coordinate prediction";
      expect_same_corners(corners(mesh), corners(*decoded));
    }
    ++tested;
  }
  EXPECT_GE(tested, 5u);
}

TEST(DracoGuard, RandomMeshesRoundTripAndAbsurdCountsAreRefused) {
  std::mt19937 rng(20261201);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 2 + int(rng() % 12), m = 3 + int(rng() % 16);
    SCOPED_TRACE("sphere " + std::to_string(n) + " x " + std::to_string(m));
    auto mesh = random_sphere(rng, n, m);
    ASSERT_NE(mesh, nullptr);
    const std::string stream = encode(*mesh, int(rng() % 8));
    std::string refusal;
    auto decoded = decode(stream.data(), stream.size(), &refusal);
    ASSERT_NE(decoded, nullptr) << refusal;
    expect_same_corners(corners(*mesh), corners(*decoded));
    if (trial < 4) EXPECT_GE(absurd_windows(stream), 1u);
  }
}

// The shared Draco test data: every stream decodes as before (none is refused
// by the guard), and in those using a texture-coordinate prediction an absurd
// orientation count is refused.
TEST(DracoGuard, SharedStreams) {
  size_t with_texcoords = 0;
  for (const auto& e : fs::directory_iterator(kData + "/draco")) {
    if (e.path().extension() != ".drc") continue;
    SCOPED_TRACE(e.path().string());
    const std::string stream = cli::slurp(e.path());
    const uint64_t before = guard_checks();
    std::string refusal;
    decode(stream.data(), stream.size(), &refusal);
    EXPECT_EQ(refusal, "");
    if (guard_checks() == before || stream.size() > 4096) continue;
    ++with_texcoords;
    EXPECT_GE(absurd_windows(stream), 1u);
  }
  for (int i = 0; i < 4; ++i)
    std::printf("guard instantiation %d checked %llu counts\n", i,
                static_cast<unsigned long long>(geom::detail::draco_guard_checks(i)));
  EXPECT_GE(with_texcoords, 1u);
}

// libdraco 1.5's encoder does not write the deprecated texture-coordinate scheme,
// so its two guarded instantiations are reached by streams whose method byte is
// turned from the portable scheme into the deprecated one: each such stream is
// decoded or refused, the deprecated decoders check its count, and an absurd
// count in it is refused by the guard.
TEST(DracoGuard, DeprecatedSchemeIsGuardedToo) {
  std::mt19937 rng(7);
  size_t variants = 0, refused = 0;
  const uint64_t before = geom::detail::draco_guard_checks(1) + geom::detail::draco_guard_checks(3);
  for (int trial = 0; trial < 3; ++trial) {
    auto mesh = random_sphere(rng, 3 + trial, 4 + trial);
    ASSERT_NE(mesh, nullptr);
    const std::string stream = encode(*mesh, 5);
    for (size_t at = 0; at < stream.size(); ++at) {
      if (stream[at] != char(draco::MESH_PREDICTION_TEX_COORDS_PORTABLE)) continue;
      std::string variant = stream;
      variant[at] = char(draco::MESH_PREDICTION_TEX_COORDS_DEPRECATED);
      const uint64_t checks = geom::detail::draco_guard_checks(1) + geom::detail::draco_guard_checks(3);
      decode(variant.data(), variant.size());
      if (geom::detail::draco_guard_checks(1) + geom::detail::draco_guard_checks(3) == checks) continue;
      ++variants;
      refused += absurd_windows(variant);
    }
  }
  EXPECT_GE(variants, 1u);
  EXPECT_GE(refused, variants);
  EXPECT_GT(geom::detail::draco_guard_checks(1) + geom::detail::draco_guard_checks(3), before);
}
