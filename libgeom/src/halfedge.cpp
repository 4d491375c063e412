// Half-edge summary (geom/halfedge.h): from the edge table where every vertex
// is a single fan; else OpenMesh's add_face replayed on the edge table (below).
// No OpenMesh here: the tests hold this equal to OpenMesh itself
// (tests/oracle/openmesh_halfedge.cpp).
//
// Why the table suffices there: OpenMesh's add_face refuses a face only at a
// complex edge (the edge already has a face on that side: an inconsistent or
// non-manifold edge in the finished mesh), at a complex vertex (the vertex's
// fan is already closed: it would end with two fans) or when it cannot
// re-link the fans around a vertex into a free gap (which needs another fan
// left at the vertex once the mesh is complete). With none of those, every
// face is added, and the boundary half-edge leaving a vertex is unique, so
// the holes are exactly the cycles of boundary edges.
#include "geom/halfedge.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "work_count.h"

namespace geom {

namespace {

// Which corner of face `f` holds vertex `v`.
inline int corner_of(const uint32_t* f, uint32_t v) { return f[0] == v ? 0 : f[1] == v ? 1 : 2; }

// On the twins, one walk per vertex, forward only: a corner is named by the
// slot of the edge leaving its vertex; from slot s out to its twin 3g + j,
// which enters the vertex, so the vertex is g's corner j + 1 and the walk goes
// on out through that slot. An open fan starts at the one corner whose
// entering edge (slot k + 2) has no twin (its head) and ends at a boundary; a
// closed one comes back to where it started. Each vertex walks from its head
// if it has one (a second head is a second fan), else from any corner; every
// vertex is a single fan exactly when the walks cover every corner.
bool single_fans_on_twins(const uint32_t* indices, size_t triangle_count, size_t vertex_count, const Topology& t,
                          uint64_t& steps) {
  constexpr uint32_t kNone = Topology::kNone;
  std::vector<uint32_t> start(vertex_count, kNone);
  std::vector<uint8_t> headed(vertex_count, 0);
  uint64_t corners = 0;
  for (size_t f = 0; f < triangle_count; ++f) {
    if (t.face_flags[f] & kFaceCollapsed) continue;
    corners += 3;
    const uint32_t* tw = t.face_twins.data() + 3 * f;
    const uint32_t* v = indices + 3 * f;
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t c = v[k], slot = uint32_t(3 * f) + k;
      if (tw[k == 0 ? 2 : k - 1] == kNone) {
        if (headed[c]) return false;
        headed[c] = 1;
        start[c] = slot;
      } else if (start[c] == kNone) {
        start[c] = slot;
      }
    }
  }
  uint64_t covered = 0;
  for (size_t v = 0; v < vertex_count; ++v) {
    const uint32_t s0 = start[v];
    if (s0 == kNone) continue;
    uint64_t n = 1;
    for (uint32_t s = s0;;) {
      const uint32_t tw = t.face_twins[s];
      if (tw == kNone) break;
      s = tw % 3 == 2 ? tw - 2 : tw + 1;
      if (s == s0) break;
      ++n;
    }
    covered += n;
  }
  steps += covered;
  return covered == corners;
}

// Without twins: both ways round each vertex through the edge table.
bool single_fans_on_edges(const uint32_t* indices, size_t triangle_count, size_t vertex_count, const Topology& t,
                          uint64_t& steps) {
  auto other_face = [&](uint32_t e, uint32_t f) -> uint32_t {
    const Edge& edge = t.edges[e];
    if (edge.face_count != 2) return Topology::kNone;
    const uint32_t a = t.edge_faces[edge.first] >> 1, b = t.edge_faces[edge.first + 1] >> 1;
    return a == f ? b : a;
  };
  std::vector<uint8_t> seen(triangle_count, 0);  // bit k: corner k visited
  std::vector<uint8_t> fans(vertex_count, 0);
  for (size_t f0 = 0; f0 < triangle_count; ++f0) {
    if (t.face_flags[f0] & kFaceCollapsed) continue;
    for (int k0 = 0; k0 < 3; ++k0) {
      if (seen[f0] >> k0 & 1) continue;
      const uint32_t v = indices[3 * f0 + k0];
      if (fans[v]++) return false;
      seen[f0] |= uint8_t(1 << k0);
      // Both ways round v from (f0, k0): out through the edge leaving v, then
      // through the edge entering it.
      for (int way = 0; way < 2; ++way) {
        uint32_t f = uint32_t(f0), e = t.face_edges[3 * f0 + (way ? (k0 + 2) % 3 : k0)];
        for (;;) {
          const uint32_t g = other_face(e, f);
          if (g == Topology::kNone) break;
          const int k = corner_of(indices + 3 * size_t(g), v);
          if (seen[g] >> k & 1) break;  // back at the start: a closed fan
          seen[g] |= uint8_t(1 << k);
          ++steps;
          const uint32_t e0 = t.face_edges[3 * size_t(g) + k], e1 = t.face_edges[3 * size_t(g) + (k + 2) % 3];
          e = e0 == e ? e1 : e0;
          f = g;
        }
      }
    }
  }
  return true;
}

// Walks the fan of each vertex through its manifold edges, corner to corner:
// each corner is visited once. False where a vertex has a second fan.
bool single_fans(const uint32_t* indices, size_t triangle_count, size_t vertex_count, const Topology& t) {
  uint64_t steps = 0;
  const bool single = t.face_twins.size() == 3 * triangle_count && t.stats.inconsistent_edges == 0
                          ? single_fans_on_twins(indices, triangle_count, vertex_count, t, steps)
                          : single_fans_on_edges(indices, triangle_count, vertex_count, t, steps);
  detail::count_work(steps);
  return single;
}

// OpenMesh's PolyConnectivity::add_face (OpenMesh 9), step for step, on the
// half-edges of the edge table: half-edge 2e runs edge e's v0 -> v1, 2e + 1
// back; an edge exists once a face added it. What OpenMesh finds by walking
// round a vertex (find_halfedge's search of its outgoing half-edges, the free
// gap of "patch re-linking", adjust_outgoing_halfedge's search for a boundary
// half-edge) is read here from each fan's two ends: every fan of faces round a
// vertex that is not closed starts with a boundary half-edge leaving the
// vertex and ends with one entering it, and the walks go from one end of a
// fan to the other. So each face costs a constant, whatever the valences, and
// the next / prev links, the vertices' half-edges and the refusals are
// OpenMesh's own (tests/test_halfedge.cpp holds them equal on every mesh).
class AddFaceReplay {
 public:
  enum class Step { Added, Refused, Lost };

  AddFaceReplay(size_t vertex_count, const Topology& t)
      : t_(t),
        hn_(2 * t.edges.size()),
        next_(hn_, kNone),
        prev_(hn_, kNone),
        fan_end_(hn_, kNone),
        fan_start_(hn_, kNone),
        face_(hn_, 0),
        exists_(t.edges.size(), 0),
        out_(vertex_count, kNone) {}

  // Adds face f (vertices v), as OpenMesh's add_face would: Lost where a
  // link the replay needs is missing (a bug: the summary is refused).
  Step add(size_t f, const uint32_t* v) {
    cached_ = 0;
    bool ok = true;
    for (int i = 0; i < 3 && ok; ++i) {
      const uint32_t e = t_.face_edges[3 * f + i];
      he_[i] = 2 * e + (v[i] == t_.edges[e].v1 ? 1u : 0u);
      fresh_[i] = !exists_[e];
      ok = boundary_vertex(v[i]) && (fresh_[i] || !face_[he_[i]]);  // complex vertex, complex edge
    }
    if (ok) {
      const Step relinked = relink_patches();
      if (relinked != Step::Added) return relinked;
    }
    if (!ok) return Step::Refused;
    for (int i = 0; i < 3; ++i) exists_[he_[i] >> 1] = 1;
    uint32_t adjust_to[3] = {kNone, kNone, kNone};  // per corner: the fan end whose next becomes the vertex's
    bool adjust[3] = {false, false, false};
    for (int i = 0; i < 3; ++i)
      if (!link_corner(i, v, adjust, adjust_to)) return Step::Lost;
    for (int i = 0; i < cached_; ++i) {
      next_[cache_[i].first] = cache_[i].second;
      prev_[cache_[i].second] = cache_[i].first;
    }
    // adjust_outgoing_halfedge: round the vertex from inner_next, through its
    // fan, to the first boundary half-edge: the one after the fan's end; none
    // when the fan closed.
    for (int i = 0; i < 3; ++i)
      if (adjust[i] && adjust_to[i] != kNone) out_[v[i]] = next_[adjust_to[i]];
    return Step::Added;
  }

  // The holes: the cycles of next among the boundary half-edges, as OpenMesh walks them.
  uint64_t count_holes(uint64_t& steps) const {
    uint64_t loops = 0;
    std::vector<uint8_t> visited(hn_, 0);
    for (uint32_t h = 0; h < hn_; ++h) {
      if (!exists_[h >> 1] || face_[h] || visited[h]) continue;
      ++loops;
      uint32_t g = h;
      do {
        visited[g] = 1;
        g = next_[g];
        ++steps;
      } while (g != h && g != kNone && !visited[g]);
    }
    return loops;
  }
  size_t halfedge_count() const { return hn_; }

 private:
  static constexpr uint32_t kNone = Topology::kNone;

  bool boundary_vertex(uint32_t v) const { return out_[v] == kNone || !face_[out_[v]]; }
  // A link the replay needs and does not have would mean the fans' ends went
  // wrong: never seen (the tests replay every mesh they have), but then
  // the summary is refused rather than anything being read out of bounds.
  bool lost(uint32_t h) const { return h >= hn_; }

  // Re-link patches: Added when every pair of old consecutive half-edges can
  // be made adjacent, Refused where the face would close a fan beside others.
  Step relink_patches() {
    for (int i = 0; i < 3; ++i) {
      const int ii = (i + 1) % 3;
      if (fresh_[i] || fresh_[ii] || next_[he_[i]] == he_[ii]) continue;
      const uint32_t inner_prev = he_[i], inner_next = he_[ii];
      const uint32_t boundary_prev = fan_end_[inner_next];  // the free gap: after inner_next's fan
      if (lost(boundary_prev) || lost(next_[boundary_prev]) || lost(next_[inner_prev]) || lost(prev_[inner_next]))
        return Step::Lost;
      if (boundary_prev == inner_prev) return Step::Refused;  // "patch re-linking failed"
      cache_[cached_++] = {boundary_prev, next_[inner_prev]};
      cache_[cached_++] = {prev_[inner_next], next_[boundary_prev]};
      cache_[cached_++] = {inner_prev, inner_next};
    }
    return Step::Added;
  }

  // Sets up the half-edges at corner ii = i + 1; false where a link is lost.
  bool link_corner(int i, const uint32_t* v, bool adjust[3], uint32_t adjust_to[3]) {
    const int ii = (i + 1) % 3;
    const uint32_t vh = v[ii], inner_prev = he_[i], inner_next = he_[ii];
    const uint32_t outer_prev = inner_next ^ 1u, outer_next = inner_prev ^ 1u;
    const int id = (fresh_[i] ? 1 : 0) | (fresh_[ii] ? 2 : 0);
    const uint32_t needed = id == 1   ? std::max(prev_[inner_next], fan_end_[inner_next])
                            : id == 2 ? std::max(next_[inner_prev], fan_start_[inner_prev])
                            : id == 3 ? (out_[vh] == kNone ? 0 : prev_[out_[vh]])
                                      : std::max(fan_start_[inner_prev], fan_end_[inner_next]);
    if (lost(needed)) return false;
    if (id == 1) {  // prev new, next old: the face starts inner_next's fan anew
      cache_[cached_++] = {prev_[inner_next], outer_next};
      out_[vh] = outer_next;
      const uint32_t in = fan_end_[inner_next];
      fan_end_[outer_next] = in, fan_start_[in] = outer_next;
    } else if (id == 2) {  // next new, prev old: the face ends inner_prev's fan anew
      cache_[cached_++] = {outer_prev, next_[inner_prev]};
      out_[vh] = next_[inner_prev];
      const uint32_t start = fan_start_[inner_prev];
      fan_start_[outer_prev] = start, fan_end_[start] = outer_prev;
    } else if (id == 3) {  // both new: a fan of its own, before the vertex's half-edge's
      if (out_[vh] == kNone) {
        out_[vh] = outer_next;
        cache_[cached_++] = {outer_prev, outer_next};
      } else {
        cache_[cached_++] = {prev_[out_[vh]], outer_next};
        cache_[cached_++] = {outer_prev, out_[vh]};
      }
      fan_end_[outer_next] = outer_prev, fan_start_[outer_prev] = outer_next;
    } else {  // both old: the face joins two fans (or closes one)
      adjust[ii] = out_[vh] == inner_next;
      const uint32_t start = fan_start_[inner_prev], end = fan_end_[inner_next];
      if (start != inner_next) {
        fan_end_[start] = end, fan_start_[end] = start;
        adjust_to[ii] = end;
      }
    }
    if (id) cache_[cached_++] = {inner_prev, inner_next};
    face_[inner_prev] = 1;
    return true;
  }

  const Topology& t_;
  const size_t hn_;
  std::vector<uint32_t> next_, prev_;
  // fan_end_[h]: for h leaving a vertex, boundary, the start of a fan there:
  // the fan's boundary half-edge entering the vertex; fan_start_[h]: the reverse.
  std::vector<uint32_t> fan_end_, fan_start_;
  std::vector<uint8_t> face_, exists_;
  std::vector<uint32_t> out_;  // OpenMesh's halfedge_handle(vertex)
  // The face being added: its half-edges, whether each is new, and the
  // next / prev links it sets, applied together once it is accepted.
  uint32_t he_[3];
  bool fresh_[3];
  std::pair<uint32_t, uint32_t> cache_[18];
  int cached_ = 0;
};

HalfedgeSummary replay_add_face(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                const Topology& t) {
  AddFaceReplay replay(positions.size(), t);
  HalfedgeSummary s;
  uint64_t steps = 0;
  for (size_t f = 0; f < triangle_count; ++f) {
    if (t.face_flags[f] & kFaceCollapsed) {
      ++s.skipped_faces;
      continue;
    }
    ++steps;
    const AddFaceReplay::Step step = replay.add(f, indices + 3 * f);
    if (step == AddFaceReplay::Step::Lost)
      throw std::logic_error("the half-edge summary lost a link of its replay (a bug)");
    ++(step == AddFaceReplay::Step::Added ? s.added_faces : s.refused_faces);
  }
  s.boundary_loops = replay.count_holes(steps);
  detail::count_work(steps + replay.halfedge_count());
  return s;
}

}  // namespace

bool halfedges_from_edge_table(const uint32_t* indices, size_t triangle_count, size_t vertex_count,
                               const Topology& topology) {
  return topology.stats.non_manifold_edges == 0 && topology.stats.inconsistent_edges == 0 &&
         single_fans(indices, triangle_count, vertex_count, topology);
}

HalfedgeSummary summarize_halfedges(PositionSpan positions, const uint32_t* indices, size_t triangle_count,
                                    const Topology& t) {
  if (!halfedges_from_edge_table(indices, triangle_count, positions.size(), t))
    return replay_add_face(positions, indices, triangle_count, t);
  HalfedgeSummary s;
  s.skipped_faces = t.stats.collapsed_triangles;
  s.added_faces = triangle_count - s.skipped_faces;
  if (t.stats.boundary_edges == 0) return s;  // no hole to walk
  // Each boundary edge as the half-edge its face does not use; the one leaving
  // a vertex is unique (one fan per vertex), so following them walks each hole.
  std::vector<uint32_t> leaving(positions.size(), Topology::kNone);
  auto from_to = [&](const Edge& e, uint32_t& from, uint32_t& to) {
    const bool reversed = t.edge_faces[e.first] & 1;  // the face runs v1 -> v0: the hole runs v0 -> v1
    from = reversed ? e.v0 : e.v1;
    to = reversed ? e.v1 : e.v0;
  };
  for (uint32_t i = 0; i < t.edges.size(); ++i) {
    if (t.edges[i].kind != EdgeKind::Boundary) continue;
    uint32_t from, to;
    from_to(t.edges[i], from, to);
    leaving[from] = i;
  }
  std::vector<uint8_t> walked(t.edges.size(), 0);
  uint64_t steps = t.edges.size();
  for (uint32_t i = 0; i < t.edges.size(); ++i) {
    if (t.edges[i].kind != EdgeKind::Boundary || walked[i]) continue;
    ++s.boundary_loops;
    for (uint32_t e = i; e != Topology::kNone && !walked[e];) {
      walked[e] = 1;
      ++steps;
      uint32_t from, to;
      from_to(t.edges[e], from, to);
      e = leaving[to];
    }
  }
  detail::count_work(steps);
  return s;
}

}  // namespace geom
