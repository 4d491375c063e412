// Every step of the bake and of `geombake info` stays linear in the triangles
// whatever the valences: the work the valence-sensitive stages count
// (libgeom/src/work_count.h: topology's edge grouping and duplicate search, the
// half-edge summary on either path, adjacency) at 4n triangles is at most 5x
// the work at n (linear: 4x; the per-vertex sorts add a log factor, 4.6x at
// most at these sizes; a quadratic step: 16x). Counted, never timed.
//
//   fan: one vertex in every triangle     double cone: two apexes of valence n/2
//        ____                                   /\      (closed)
//       |\  /                                  /__\     book: every triangle on
//       | \/  ...                              \  /     one edge (a "spine")
//                                               \/      star: many separate fans
//                                                       at one vertex
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geom/bake.h"
#include "geom/report.h"
#include "work_count.h"

namespace {

geom::Scene fan(int n) {
  geom::Scene s;
  s.positions = {0, 0, 0};
  for (int i = 0; i <= n; ++i)
    s.positions.insert(s.positions.end(), {float(std::cos(6.2 * i / n)), float(std::sin(6.2 * i / n)), 0.0f});
  for (int i = 0; i < n; ++i) s.indices.insert(s.indices.end(), {0u, uint32_t(i + 1), uint32_t(i + 2)});
  return s;
}

geom::Scene double_cone(int n) {  // n triangles
  geom::Scene s;
  const int rim = n / 2;
  s.positions = {0, 0, 1, 0, 0, -1};
  for (int i = 0; i < rim; ++i)
    s.positions.insert(s.positions.end(),
                       {float(std::cos(2 * M_PI * i / rim)), float(std::sin(2 * M_PI * i / rim)), 0.0f});
  for (int i = 0; i < rim; ++i) {
    const uint32_t a = uint32_t(2 + i), b = uint32_t(2 + (i + 1) % rim);
    s.indices.insert(s.indices.end(), {0u, a, b, 1u, b, a});
  }
  return s;
}

geom::Scene book(int n) {  // pages alternate their winding; every tenth is a duplicate
  geom::Scene s;
  s.positions = {0, 0, 0, 0, 0, 1};
  for (int i = 0; i < n; ++i) {
    const int page = i % 10 == 9 ? i - 1 : i;
    s.positions.insert(s.positions.end(),
                       {float(std::cos(2 * M_PI * page / n)), float(std::sin(2 * M_PI * page / n)), 0.5f});
    const uint32_t p = uint32_t(2 + i);
    if (i % 2)
      s.indices.insert(s.indices.end(), {0u, 1u, p});
    else
      s.indices.insert(s.indices.end(), {1u, 0u, p});
  }
  return s;
}

geom::Scene star(int n) {  // n / 3 petals of three faces, fans apart at the centre until the third joins them
  geom::Scene s;
  s.positions = {0, 0, 0};
  for (int p = 0; p < n / 3; ++p) {
    const uint32_t v = uint32_t(s.positions.size() / 3);
    for (int k = 0; k < 4; ++k)
      s.positions.insert(s.positions.end(),
                         {float(std::cos(0.001 * p + k)), float(std::sin(0.001 * p + k)), float(p % 7 + k)});
    s.indices.insert(s.indices.end(), {0u, v, v + 1, 0u, v + 2, v + 3, 0u, v + 1, v + 2});
  }
  return s;
}

geom::Scene sphere(int n) {  // about n triangles
  geom::Scene s;
  const int k = int(std::sqrt(n / 2.0));
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i < k; ++i) {
      const double u = 2 * M_PI * i / k, v = M_PI * (0.05 + 0.9 * j / k);
      s.positions.insert(s.positions.end(),
                         {float(std::cos(u) * std::sin(v)), float(std::cos(v)), float(std::sin(u) * std::sin(v))});
    }
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      const uint32_t a = uint32_t(j * k + i), b = uint32_t(j * k + (i + 1) % k), c = a + uint32_t(k),
                     d = b + uint32_t(k);
      s.indices.insert(s.indices.end(), {a, b, c, b, d, c});
    }
  return s;
}

struct Work {
  uint64_t bake = 0, info = 0;
};

Work work_of(const geom::Scene& s) {
  Work w;
  geom::detail::work_steps = 0;
  geom::BakeResult r = geom::bake_scene(s, "mesh");
  EXPECT_TRUE(r.ok) << r.error;
  w.bake = geom::detail::work_steps;
  geom::detail::work_steps = 0;
  geom::Report report;
  geom::analyze(s, {}, report);
  w.info = geom::detail::work_steps;
  return w;
}

void expect_linear(const char* name, geom::Scene (*make)(int)) {
  const int n = 20000;
  const geom::Scene small = make(n), big = make(4 * n);
  const Work a = work_of(small), b = work_of(big);
  EXPECT_GE(a.bake, uint64_t(n)) << name;
  EXPECT_GE(a.info, uint64_t(n)) << name;
  EXPECT_LE(double(b.bake), 5.0 * double(a.bake)) << name << ": bake work " << a.bake << " -> " << b.bake;
  EXPECT_LE(double(b.info), 5.0 * double(a.info)) << name << ": info work " << a.info << " -> " << b.info;
  std::printf("%-12s bake %llu -> %llu (%.2fx), info %llu -> %llu (%.2fx)\n", name, (unsigned long long)a.bake,
              (unsigned long long)b.bake, double(b.bake) / a.bake, (unsigned long long)a.info,
              (unsigned long long)b.info, double(b.info) / a.info);
}

}  // namespace

TEST(LinearWork, Fan) { expect_linear("fan", fan); }
TEST(LinearWork, DoubleCone) { expect_linear("double cone", double_cone); }
TEST(LinearWork, Book) { expect_linear("book", book); }
TEST(LinearWork, Star) { expect_linear("star", star); }
TEST(LinearWork, Sphere) { expect_linear("sphere", sphere); }
