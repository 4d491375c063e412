// Meshes and helpers shared by test_shadow_volume, test_esm_quads and
// test_adjacency: closed, open, non-manifold, inconsistent and degenerate
// meshes, each small enough to check laws by brute force.
#pragma once
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "geom/pipeline.h"

namespace fixtures {

struct Mesh {
  std::string name;
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  bool closed = false;  // a closed, consistently oriented surface (silhouette loops apply)
  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
  uint32_t add(double x, double y, double z) {
    positions.insert(positions.end(), {float(x), float(y), float(z)});
    return uint32_t(vertex_count() - 1);
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) { indices.insert(indices.end(), {a, b, c}); }
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {  // a b c d counter-clockwise
    tri(a, b, c);
    tri(a, c, d);
  }
  void append(const Mesh& m) {
    const uint32_t base = uint32_t(vertex_count());
    positions.insert(positions.end(), m.positions.begin(), m.positions.end());
    for (uint32_t i : m.indices) indices.push_back(base + i);
  }
  void translate(double x, double y, double z) {
    for (size_t i = 0; i < positions.size(); i += 3) {
      positions[i] = float(positions[i] + x);
      positions[i + 1] = float(positions[i + 1] + y);
      positions[i + 2] = float(positions[i + 2] + z);
    }
  }
};

//      7-------6
//     /|      /|      an axis-aligned box, outward counter-clockwise faces,
//    4-------5 |      two triangles per face
//    | 3-----|-2
//    |/      |/
//    0-------1
inline Mesh box(double x0, double y0, double z0, double x1, double y1, double z1) {
  Mesh m;
  m.name = "box";
  m.closed = true;
  m.add(x0, y0, z0), m.add(x1, y0, z0), m.add(x1, y1, z0), m.add(x0, y1, z0);
  m.add(x0, y0, z1), m.add(x1, y0, z1), m.add(x1, y1, z1), m.add(x0, y1, z1);
  m.quad(0, 3, 2, 1);  // z0
  m.quad(4, 5, 6, 7);  // z1
  m.quad(0, 1, 5, 4);  // y0
  m.quad(2, 3, 7, 6);  // y1
  m.quad(1, 2, 6, 5);  // x1
  m.quad(3, 0, 4, 7);  // x0
  return m;
}

// A UV sphere (closed, convex, poles as single vertices).
inline Mesh sphere(int nu, int nv, double r = 1) {
  Mesh m;
  m.name = "sphere";
  m.closed = true;
  const uint32_t south = m.add(0, -r, 0);
  for (int j = 1; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      double u = 2 * M_PI * i / nu, v = M_PI * j / nv - M_PI / 2;
      m.add(r * std::cos(v) * std::cos(u), r * std::sin(v), r * std::cos(v) * std::sin(u));
    }
  const uint32_t north = m.add(0, r, 0);
  auto at = [&](int i, int j) { return uint32_t(1 + (j - 1) * nu + (i % nu)); };
  for (int i = 0; i < nu; ++i) {
    m.tri(south, at(i, 1), at(i + 1, 1));
    m.tri(north, at(i + 1, nv - 1), at(i, nv - 1));
    for (int j = 1; j + 1 < nv; ++j) m.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  }
  // orientation: make the normals point outward
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    uint32_t* v = &m.indices[3 * t];
    const float* a = &m.positions[3 * v[0]];
    const float* b = &m.positions[3 * v[1]];
    const float* c = &m.positions[3 * v[2]];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    if (n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]) < 0)
      std::swap(v[1], v[2]);
  }
  return m;
}

// A torus (closed, genus 1, concave edges on the inside).
inline Mesh torus(int nu, int nv, double R = 1, double r = 0.35) {
  Mesh m;
  m.name = "torus";
  m.closed = true;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.add((R + r * std::cos(v)) * std::cos(u), r * std::sin(v), (R + r * std::cos(v)) * std::sin(u));
    }
  auto at = [&](int i, int j) { return uint32_t((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) m.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  return m;
}

// An open height-field sheet over [-1, 1]^2 (y up), n x n quads.
inline Mesh sheet(int n, double amplitude, uint32_t seed = 1, double noise = 0) {
  Mesh m;
  m.name = "sheet";
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-noise, noise);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double x = -1 + 2.0 * i / n, z = -1 + 2.0 * j / n;
      m.add(x, amplitude * std::sin(2.5 * x) * std::cos(1.7 * z) + (noise > 0 ? jitter(rng) : 0), z);
    }
  auto at = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  return m;
}

// An open box (no lid): boundary edges around the top.
inline Mesh open_box() {
  Mesh m = box(-1, -1, -1, 1, 1, 1);
  m.name = "open_box";
  m.closed = false;
  m.indices.erase(m.indices.begin() + 3 * 6, m.indices.begin() + 3 * 8);  // drop the y1 face
  return m;
}

//   Pages of a book: k quads sharing the spine edge (0,0,-1)-(0,0,1); each
//   spine edge has k faces (non-manifold), plus a closed box beside.
inline Mesh book(int pages) {
  Mesh m;
  m.name = "book";
  const uint32_t s0 = m.add(0, 0, -1), s1 = m.add(0, 0, 1);
  for (int k = 0; k < pages; ++k) {
    double a = M_PI * (0.1 + 0.8 * k / std::max(1, pages - 1));
    uint32_t p0 = m.add(std::cos(a), std::sin(a), -1), p1 = m.add(std::cos(a), std::sin(a), 1);
    if (k % 2)
      m.quad(s0, s1, p1, p0);
    else
      m.quad(s0, p0, p1, s1);
  }
  return m;
}

// Two boxes sharing one edge (an edge with 4 faces), and a box with an
// internal wall (edges with 3 faces): the non-manifold cases of game levels.
inline Mesh bowtie() {
  Mesh m = box(0, 0, 0, 1, 1, 1);
  m.append(box(1, 1, 0, 2, 2, 1));  // shares the edge x = y = 1: 4 faces
  m.append(box(-2, 0, 0, -1, 1, 1));
  Mesh fin;  // on the edge x = -1, y = 1: 3 faces
  uint32_t a = fin.add(-1, 1, 0), b = fin.add(-1, 1, 1), c = fin.add(-0.4, 1.7, 1), d = fin.add(-0.4, 1.7, 0);
  fin.quad(a, b, c, d);
  m.append(fin);
  m.name = "bowtie";
  return m;
}

// A box with one face's winding flipped (inconsistent edges).
inline Mesh flipped_box() {
  Mesh m = box(-1, -1, -1, 1, 1, 1);
  m.name = "flipped_box";
  m.closed = false;
  std::swap(m.indices[3 * 4 + 1], m.indices[3 * 4 + 2]);
  std::swap(m.indices[3 * 5 + 1], m.indices[3 * 5 + 2]);
  return m;
}

//   Degenerate faces and a T-junction: a box whose +x face is split at the
//   midpoint m of edge 1-2 on one side only (a T-junction: the neighbour
//   across that edge does not know m), plus a zero-area sliver (1, m, 2) and
//   a collapsed triangle, which must cast no shadow.
inline Mesh degenerate_box() {
  Mesh m = box(-1, -1, -1, 1, 1, 1);
  m.name = "degenerate_box";
  m.closed = false;
  // x1 face is quad(1, 2, 6, 5): triangles (1,2,6), (1,6,5). Replace (1,2,6) by
  // (1,mid,6), (mid,2,6) with mid on edge 1-2.
  const uint32_t mid = m.add(1, 0, -1);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    uint32_t* v = &m.indices[3 * t];
    if (v[0] == 1 && v[1] == 2 && v[2] == 6) {
      v[1] = mid;
      m.tri(mid, 2, 6);
      break;
    }
  }
  m.tri(1, 2, mid);  // zero area (collinear), wound against the T-junction
  m.tri(3, 3, 7);    // collapsed
  return m;
}

//   A closed box whose top face holds a sliver: m sits 1e-6 inside edge 4-5
//   and 1e-7 above the face, so the sliver (4, 5, m) has its own plane, tilted
//   about 6 degrees, and an area of 1e-6.
//        7---------6
//        |  .   .  |
//        | .     . |
//        4----m----5
inline Mesh sliver_box() {
  Mesh m = box(-1, -1, -1, 1, 1, 1);
  m.name = "sliver_box";
  const uint32_t mid = m.add(0, -1 + 1e-6, 1 + 1e-7);
  // the top face quad(4, 5, 6, 7) is triangles 2 and 3
  uint32_t* t = &m.indices[3 * 2];
  t[0] = 4, t[1] = 5, t[2] = mid;
  t = &m.indices[3 * 3];
  t[0] = 4, t[1] = mid, t[2] = 7;
  m.tri(mid, 5, 6);
  m.tri(mid, 6, 7);
  return m;
}

// A scene: several closed and open pieces stacked, so segments cross many faces.
inline Mesh stack() {
  Mesh m = box(-0.5, 0.2, -0.5, 0.5, 0.6, 0.5);
  m.append(box(-0.2, 0.8, -0.3, 0.3, 1.4, 0.2));
  Mesh s = sheet(6, 0.1, 3);
  m.append(s);
  Mesh t = torus(10, 6, 0.6, 0.15);
  t.translate(0, -0.7, 0);
  m.append(t);
  m.name = "stack";
  return m;
}

// The pipeline (geom/pipeline.h) on a fixture, every buffer kept (dihedral
// angles included).
using Baked = geom::Pipeline;

inline Baked bake(const Mesh& m, const geom::ShadowVolumeOptions& svo = {}, const geom::EsmOptions& eo = {}) {
  geom::PipelineOptions o;
  o.dihedral_angles = true;
  o.volume_options = svo;
  o.esm_options = eo;
  return geom::run_pipeline(geom::positions_of(m.positions.data(), m.vertex_count()), m.indices.data(),
                            m.triangle_count(), {}, o);
}

}  // namespace fixtures
