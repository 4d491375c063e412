// live_faces.h (private): an edge's faces that have a plane (not
// degenerate), as Topology::edge_faces entries, for the ESM quads and the
// shadow volume. An edge of one or two faces (nearly all) is gathered into
// the struct itself; more go to a vector kept across edges.
#pragma once
#include <cstdint>
#include <vector>

#include "geom/face_planes.h"
#include "geom/topology.h"

namespace geom::detail {

class LiveFaces {
 public:
  LiveFaces() = default;
  LiveFaces(const LiveFaces&) = delete;  // p_ may point into the object
  LiveFaces& operator=(const LiveFaces&) = delete;
  void gather(const Topology& t, const FacePlanes& fp, const Edge& e) {
    const uint32_t* ef = t.edge_faces.data() + e.first;
    if (e.face_count <= 2) {
      n_ = 0;
      for (uint32_t i = 0; i < e.face_count; ++i)
        if (fp.face_plane[ef[i] >> 1] != FacePlanes::kNone) small_[n_++] = ef[i];
      p_ = small_;
      return;
    }
    big_.clear();
    for (uint32_t i = 0; i < e.face_count; ++i)
      if (fp.face_plane[ef[i] >> 1] != FacePlanes::kNone) big_.push_back(ef[i]);
    p_ = big_.data(), n_ = big_.size();
  }
  size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  uint32_t operator[](size_t i) const { return p_[i]; }
  const uint32_t* begin() const { return p_; }
  const uint32_t* end() const { return p_ + n_; }

 private:
  uint32_t small_[2] = {0, 0};
  std::vector<uint32_t> big_;
  const uint32_t* p_ = small_;
  size_t n_ = 0;
};

}  // namespace geom::detail
