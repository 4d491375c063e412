// Face planes and coplanar groups (see geom/face_planes.h for the contract).
// Region growing over manifold edges, in triangle order, against the seed's
// plane; everything in double, stored as float in the local frame.
#include "geom/face_planes.h"

#include <algorithm>
#include <cmath>

#include "geom/precondition.h"

namespace geom {
namespace {

// Local frame: the centre of the bounding box of every referenced vertex,
// and the box's diagonal. In float (widening is exact and keeps the order, so
// the bounds are the same), widened once. Where the topology counted every
// vertex as used, a pass over the vertices (each once, in order) instead of
// over the indices (each about six times, scattered): the same bounds, as min
// and max pick the same value whatever the order, but for the sign of a zero
// (equal, so the first seen wins), which reaches the frame only where an axis
// is flat at zero: that case takes the index pass.
void local_frame(PositionSpan positions, const uint32_t* indices, size_t triangle_count, const Topology& topology,
                 FacePlanes& r) {
  float lof[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF}, hif[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
  const auto grow = [&](const Float3& p) {
    const float c[3] = {p.x, p.y, p.z};
    for (int a = 0; a < 3; ++a) {
      lof[a] = std::min(lof[a], c[a]);
      hif[a] = std::max(hif[a], c[a]);
    }
  };
  const TopologyStats& ts = topology.stats;
  bool by_vertex = ts.triangles == triangle_count && ts.vertices == positions.size() && triangle_count > 0;
  if (by_vertex) {
    for (size_t v = 0; v < positions.size(); ++v) grow(positions[v]);
    for (int a = 0; a < 3; ++a) by_vertex = by_vertex && !(lof[a] == 0 && hif[a] == 0);
  }
  if (!by_vertex) {
    for (int a = 0; a < 3; ++a) lof[a] = HUGE_VALF, hif[a] = -HUGE_VALF;
    for (size_t i = 0; i < 3 * triangle_count; ++i) grow(positions[indices[i]]);
  }
  const double lo[3] = {lof[0], lof[1], lof[2]}, hi[3] = {hif[0], hif[1], hif[2]};
  double diag2 = 0;
  for (int a = 0; a < 3; ++a) {
    r.origin[a] = 0.5 * (lo[a] + hi[a]);
    diag2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  }
  r.diagonal = std::sqrt(diag2);
}

// A vertex in the local frame, in double.
struct LocalPositions {
  PositionSpan positions;
  const double* origin;
  void operator()(uint32_t v, double out[3]) const {
    const Float3& p = positions[v];
    out[0] = double(p.x) - origin[0];
    out[1] = double(p.y) - origin[1];
    out[2] = double(p.z) - origin[2];
  }
};

// Unit normals in double; degenerate faces keep a zero normal.
void unit_normals(const LocalPositions& local, const uint32_t* indices, size_t triangle_count, const Topology& topology,
                  FacePlanes& r) {
  const bool have_flags = topology.face_flags.size() == triangle_count;
  for (size_t f = 0; f < triangle_count; ++f) {
    if (have_flags && (topology.face_flags[f] & (kFaceCollapsed | kFaceZeroArea))) {
      ++r.degenerate_faces;
      continue;
    }
    double a[3], b[3], c[3];
    local(indices[3 * f], a);
    local(indices[3 * f + 1], b);
    local(indices[3 * f + 2], c);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0.0) || !std::isfinite(len)) {
      ++r.degenerate_faces;
      continue;
    }
    for (int k = 0; k < 3; ++k) r.normals[3 * f + k] = n[k] / len;
  }
}

// The face across side k of face g over a manifold edge, or kNone.
inline uint32_t across(const Topology& topology, const uint32_t* indices, bool have_twins, size_t seed, uint32_t g,
                       int k) {
  if (have_twins) {  // the other face of a two-faced edge, run the other way (a manifold edge)
    const size_t s = 3 * size_t(g) + k;
    const uint32_t tw = topology.face_twins[s];
    // A face before the seed has its plane or none (degenerate): it joins no
    // group from this seed, so it is skipped before its loads.
    if (tw == Topology::kNone || tw / 3 < seed || indices[tw] == indices[s]) return Topology::kNone;
    return tw / 3;
  }
  const uint32_t e = topology.face_edges[3 * size_t(g) + k];
  if (e == Topology::kNone || topology.edges[e].kind != EdgeKind::Manifold) return Topology::kNone;
  const Edge& edge = topology.edges[e];
  uint32_t h = topology.edge_faces[edge.first] >> 1;
  if (h == g) h = topology.edge_faces[edge.first + 1] >> 1;
  return h;
}

// The seed's coplanar group, grown over manifold edges: a face joins when its
// normal is within cos_tol of the seed's and its vertices within dist_tol of
// the seed's plane (n, d).
void grow_group(const LocalPositions& local, const uint32_t* indices, const Topology& topology, bool have_twins,
                size_t seed, uint32_t id, const double* n, double d, double cos_tol, double dist_tol,
                std::vector<uint32_t>& queue, FacePlanes& r) {
  queue.assign(1, uint32_t(seed));
  for (size_t qi = 0; qi < queue.size(); ++qi) {
    const uint32_t g = queue[qi];
    for (int k = 0; k < 3; ++k) {
      const uint32_t h = across(topology, indices, have_twins, seed, g, k);
      if (h == Topology::kNone) continue;
      if (r.face_plane[h] != FacePlanes::kNone) continue;
      const double* m = &r.normals[3 * size_t(h)];
      if (n[0] * m[0] + n[1] * m[1] + n[2] * m[2] < cos_tol) continue;  // also rejects degenerate (0)
      bool near = true;
      for (int j = 0; j < 3 && near; ++j) {
        double q[3];
        local(indices[3 * size_t(h) + j], q);
        near = std::fabs(n[0] * q[0] + n[1] * q[1] + n[2] * q[2] + d) <= dist_tol;
      }
      if (!near) continue;
      r.face_plane[h] = id;
      ++r.shared_faces;
      queue.push_back(h);
    }
  }
}

}  // namespace

FacePlanes compute_face_planes(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                               const Topology& topology, const FacePlaneOptions& options) {
  GEOM_PRECONDITION_INDICES(indices, 3 * triangle_count, positions.size());
  GEOM_PRECONDITION(topology.face_flags.empty() || topology.face_flags.size() == triangle_count,
                    "a topology of " + std::to_string(topology.face_flags.size()) + " triangles, expected " +
                        std::to_string(triangle_count) + " (build_topology of these triangles)");
  FacePlanes r;
  r.face_plane.assign(triangle_count, FacePlanes::kNone);
  r.normals.assign(triangle_count * 3, 0.0);
  if (triangle_count == 0) return r;
  local_frame(positions, indices, triangle_count, topology, r);
  const LocalPositions local{positions, r.origin};
  unit_normals(local, indices, triangle_count, topology, r);

  const double cos_tol = std::cos(options.coplanar_degrees * M_PI / 180.0);
  const double dist_tol = options.coplanar_distance * r.diagonal;
  const bool have_edges = topology.face_edges.size() == 3 * triangle_count;
  const bool have_twins = topology.face_twins.size() == 3 * triangle_count;
  std::vector<uint32_t> queue;
  r.planes.reserve(4 * (triangle_count - r.degenerate_faces));  // at most a plane per face: never grown
  for (size_t seed = 0; seed < triangle_count; ++seed) {
    const double* n = &r.normals[3 * seed];
    if (r.face_plane[seed] != FacePlanes::kNone || (n[0] == 0 && n[1] == 0 && n[2] == 0)) continue;
    double p0[3];
    local(indices[3 * seed], p0);
    const double d = -(n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2]);
    const uint32_t id = uint32_t(r.plane_count());
    r.planes.push_back(float(n[0])), r.planes.push_back(float(n[1]));  // reserved: plain stores
    r.planes.push_back(float(n[2])), r.planes.push_back(float(d));
    r.face_plane[seed] = id;
    if (have_edges) grow_group(local, indices, topology, have_twins, seed, id, n, d, cos_tol, dist_tol, queue, r);
  }
  return r;
}

}  // namespace geom
