// Static casters' hull computed once (focus_caster_hull, or a baked file's
// caster_hull section) and passed every frame (FocusOptions::caster_hull)
// gives the focus that computing the hull from the points every frame
// (FocusOptions::casters) gives: the same matrix, body and cube faces, on
// random scenes of every light type and method.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "geom/bake.h"
#include "geom/baked_reader.h"
#include "geom/baked_writer.h"
#include "geom/focus.h"

namespace {

using namespace geom;

struct Frame {
  CameraMatrices camera;
  Light light;
  FocusBox box;
  std::vector<float> casters;  // xyz
  FocusOptions options;
};

// A camera, a light, a scene box and casters: clusters of points inside the
// box and some beyond it, so the hull and the box each cut the other.
Frame random_frame(std::mt19937& rng, int trial) {
  std::uniform_real_distribution<double> u(-1, 1);
  Frame f;
  for (int k = 0; k < 3; ++k) {
    f.box.min[k] = -20 + 5 * u(rng);
    f.box.max[k] = 20 + 5 * u(rng);
  }
  const double eye[3] = {30 * u(rng), 2 + 10 * std::fabs(u(rng)), 30 * u(rng)};
  const double target[3] = {10 * u(rng), 0, 10 * u(rng)}, up[3] = {0, 1, 0};
  f.camera = camera_look_at(eye, target, up, 40 + 30 * std::fabs(u(rng)), 1.5, 0.1, trial % 4 ? 300 : HUGE_VAL);
  f.light.type = LightType(trial % 3);
  f.light.position[0] = 25 * u(rng), f.light.position[1] = 15 + 20 * std::fabs(u(rng)),
  f.light.position[2] = 25 * u(rng);
  if (trial % 7 == 0) f.light.position[1] = 3;  // among the receivers: cube faces
  f.light.direction[0] = 0.5 * u(rng), f.light.direction[1] = -1, f.light.direction[2] = 0.5 * u(rng);
  f.light.outer_cone = 0.3 + 0.6 * std::fabs(u(rng));
  f.light.range = trial % 5 == 0 ? 60 : 0;
  const int clusters = 1 + int(rng() % 6);
  for (int c = 0; c < clusters; ++c) {
    const double cx = 22 * u(rng), cy = 4 + 4 * u(rng), cz = 22 * u(rng), r = 1 + 5 * std::fabs(u(rng));
    for (int i = 0; i < 4 + int(rng() % 40); ++i)
      f.casters.insert(f.casters.end(), {float(cx + r * u(rng)), float(cy + r * u(rng)), float(cz + r * u(rng))});
  }
  f.options.method = FocusMethod(trial % 4 == 3 ? 0 : trial % 3);
  f.options.faces = trial % 2 == 0;
  f.options.cube_cone_degrees = trial % 6 == 1 ? 100 : 0;
  return f;
}

void expect_same_matrix(const double* a, const double* b, const std::string& what) {
  double scale = 0;
  for (int i = 0; i < 16; ++i) scale = std::fmax(scale, std::fabs(a[i]));
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(a[i], b[i], 1e-12 * scale) << what << " [" << i << "]";
}

// The two results agree: what was chosen, the matrix, H, the cube faces.
void expect_same(const FocusResult& a, const FocusResult& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.fallback, b.fallback) << a.reason << " | " << b.reason;
  EXPECT_EQ(a.light_kind, b.light_kind);
  EXPECT_EQ(a.needs_cube_map, b.needs_cube_map);
  EXPECT_EQ(a.near_floor_cut, b.near_floor_cut);
  expect_same_matrix(a.matrix, b.matrix, "matrix");
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i)
    EXPECT_NEAR(a.vertices[i], b.vertices[i], 1e-12 * (1 + std::fabs(a.vertices[i]))) << "vertex " << i / 3;
  EXPECT_EQ(a.face_sizes, b.face_sizes);
  EXPECT_EQ(a.face_indices, b.face_indices);
  EXPECT_EQ(a.cube, b.cube);
  for (int i = 0; a.cube && i < 6; ++i) {
    EXPECT_EQ(a.cube_faces[i].empty, b.cube_faces[i].empty) << "face " << i;
    expect_same_matrix(a.cube_faces[i].matrix, b.cube_faces[i].matrix, "cube face " + std::to_string(i));
    expect_same_matrix(a.cube_faces[i].focused, b.cube_faces[i].focused, "focused face " + std::to_string(i));
  }
}

TEST(FocusCasterHull, PrecomputedEqualsPerFrame) {
  std::mt19937 rng(2027);
  int cut = 0;    // frames where the casters changed H (so the hull mattered)
  int empty = 0;  // frames whose H is empty
  for (int trial = 0; trial < 600; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    Frame f = random_frame(rng, trial);
    const PositionSpan points = positions_of(f.casters.data(), f.casters.size() / 3);
    std::vector<double> planes;
    ASSERT_TRUE(focus_caster_hull(points, planes));
    ASSERT_EQ(planes.size() % 4, 0u);
    ASSERT_GE(planes.size(), 16u);  // a tetrahedron at least
    std::vector<double> again;
    focus_caster_hull(points, again);
    EXPECT_EQ(planes, again) << "the hull is not deterministic";
    FocusOptions per_frame = f.options, once = f.options, none = f.options;
    per_frame.casters = points;
    once.caster_hull = StridedSpan<FocusPlane>(planes.data(), planes.size() / 4, 4 * sizeof(double));
    FocusResult a, b, c;
    compute_focus(f.camera, f.light, f.box, per_frame, a);
    compute_focus(f.camera, f.light, f.box, once, b);
    compute_focus(f.camera, f.light, f.box, none, c);
    expect_same(a, b);
    // S's body is kept per thread while the planes stay the same: a thread
    // that starts afresh (nothing kept) gives the same answer.
    if (trial % 10 == 0) {
      FocusResult fresh;
      std::thread([&] { compute_focus(f.camera, f.light, f.box, once, fresh); }).join();
      expect_same(fresh, b);
    }
    // H lies in S: inside every hull plane (and so near the casters), and is
    // rarely empty (a frame's S made from other planes, or none, would fail).
    empty += b.fallback == FocusFallback::EmptyFocus;
    for (size_t v = 0; v + 2 < b.vertices.size(); v += 3)
      for (size_t p = 0; p < planes.size(); p += 4)
        ASSERT_GE(planes[p] * b.vertices[v] + planes[p + 1] * b.vertices[v + 1] + planes[p + 2] * b.vertices[v + 2] +
                      planes[p + 3],
                  -1e-6 * (1 + std::fabs(planes[p + 3])))
            << "H's vertex " << v / 3 << " outside hull plane " << p / 4;
    if (HasFailure()) return;
    bool differs = false;
    for (int i = 0; i < 16; ++i) differs = differs || std::fabs(a.matrix[i] - c.matrix[i]) > 1e-9;
    cut += differs;
  }
  EXPECT_GT(cut, 300) << "the casters should change most frames' focus";
  EXPECT_LT(empty, 200) << "H should hold receivers in most frames (114 of 600 are empty: nothing seen is in S)";
}

// The hull's planes hold every caster (within rounding); a flat or non-finite
// set has no hull; a non-finite plane is invalid input.
TEST(FocusCasterHull, PlanesHoldTheCastersAndBadInputIsRefused) {
  std::mt19937 rng(7);
  Frame f = random_frame(rng, 0);
  std::vector<double> planes;
  ASSERT_TRUE(focus_caster_hull(positions_of(f.casters.data(), f.casters.size() / 3), planes));
  for (size_t p = 0; p < planes.size(); p += 4) {
    EXPECT_NEAR(std::hypot(planes[p], planes[p + 1], planes[p + 2]), 1.0, 1e-12);
    for (size_t i = 0; i < f.casters.size(); i += 3)
      EXPECT_GE(planes[p] * f.casters[i] + planes[p + 1] * f.casters[i + 1] + planes[p + 2] * f.casters[i + 2] +
                    planes[p + 3],
                -1e-9)
          << "caster " << i / 3 << " outside plane " << p / 4;
  }
  std::vector<float> flat = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.5f, 0.5f, 0};
  EXPECT_FALSE(focus_caster_hull(positions_of(flat.data(), 5), planes));
  EXPECT_TRUE(planes.empty());
  std::vector<float> nan = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::nanf("")};
  EXPECT_FALSE(focus_caster_hull(positions_of(nan.data(), 4), planes));
  ASSERT_TRUE(focus_caster_hull(positions_of(f.casters.data(), f.casters.size() / 3), planes));
  planes[5] = std::nan("");
  FocusOptions o;
  o.caster_hull = StridedSpan<FocusPlane>(planes.data(), planes.size() / 4, 32);
  FocusResult r;
  EXPECT_FALSE(compute_focus(f.camera, f.light, f.box, o, r));
  EXPECT_EQ(r.fallback, FocusFallback::InvalidInput);
}

// The hull the bake stores (caster_hull, read back through the reader as the
// engine reads it) is the focus's own: the same result as the points.
TEST(FocusCasterHull, BakedSectionRoundTrips) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    Frame f = random_frame(rng, trial);
    Scene scene;
    scene.positions = f.casters;
    const size_t n = f.casters.size() / 3;
    for (uint32_t i = 0; i + 2 < n; ++i) scene.indices.insert(scene.indices.end(), {i, i + 1, i + 2});
    scene.sources.resize(scene.indices.size() / 3);
    scene.files = {"casters"};
    BakeOptions bo;
    bo.caster_hull = focus_caster_hull;
    bo.pipeline.esm = bo.pipeline.volume = bo.pipeline.adjacency = false;
    const BakeResult baked = bake_scene(scene, "casters", bo);
    ASSERT_TRUE(baked.ok) << baked.error;
    std::vector<unsigned char> bytes;
    std::string error;
    ASSERT_TRUE(serialize_baked(baked.sections, bytes, error)) << error;
    baked::Reader reader;
    ASSERT_TRUE(reader.open(bytes.data(), bytes.size())) << reader.error();
    const baked::Section* hull = reader.find(baked::SectionType::CasterHull);
    ASSERT_NE(hull, nullptr);
    ASSERT_NE(hull->as<FocusPlane>(), nullptr);
    const baked::Section* pos = reader.find(baked::SectionType::Positions);
    ASSERT_NE(pos, nullptr);
    FocusOptions from_file = f.options, from_points = f.options;
    from_file.caster_hull = StridedSpan<FocusPlane>(hull->as<FocusPlane>(), hull->count);
    from_points.casters = PositionSpan(pos->data, pos->count, pos->stride);
    FocusResult a, b;
    compute_focus(f.camera, f.light, f.box, from_points, a);
    compute_focus(f.camera, f.light, f.box, from_file, b);
    expect_same(a, b);
    if (HasFailure()) return;
  }
}

}  // namespace
