// Triangles-with-adjacency index buffer (see geom/adjacency.h), for the
// geometry-shader silhouette test of seed 001_0225cc27c0669b01.txt, section
// 3.2.1. Directed half-edges are bucketed by their start vertex (a counting
// sort, in triangle order), so "the first triangle traversing b -> a" is the
// first match in b's bucket: linear time, no hashing, deterministic.
#include "geom/adjacency.h"

#include <new>
#include <vector>

namespace geom {

bool build_adjacency(uint32_t* out, const uint32_t* indices, size_t triangle_count, size_t vertex_count) {
  struct Half {
    uint32_t to, third, tri;
  };
  try {
    std::vector<uint32_t> start(vertex_count + 1, 0);
    auto collapsed = [&](const uint32_t* v) { return v[0] == v[1] || v[1] == v[2] || v[2] == v[0]; };
    for (size_t t = 0; t < triangle_count; ++t) {
      const uint32_t* v = indices + 3 * t;
      if (collapsed(v)) continue;
      ++start[v[0] + 1];
      ++start[v[1] + 1];
      ++start[v[2] + 1];
    }
    for (size_t i = 0; i < vertex_count; ++i) start[i + 1] += start[i];
    std::vector<Half> half(start[vertex_count]);
    {
      std::vector<uint32_t> fill(start.begin(), start.end() - 1);
      for (size_t t = 0; t < triangle_count; ++t) {
        const uint32_t* v = indices + 3 * t;
        if (collapsed(v)) continue;
        half[fill[v[0]]++] = {v[1], v[2], uint32_t(t)};
        half[fill[v[1]]++] = {v[2], v[0], uint32_t(t)};
        half[fill[v[2]]++] = {v[0], v[1], uint32_t(t)};
      }
    }
    for (size_t t = 0; t < triangle_count; ++t) {
      const uint32_t* v = indices + 3 * t;
      uint32_t* o = out + 6 * t;
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = v[k], b = v[(k + 1) % 3], own = v[(k + 2) % 3];
        o[2 * k] = a;
        uint32_t n = own;
        if (!collapsed(v)) {
          bool found = false;
          for (uint32_t i = start[b], e = start[b + 1]; i < e; ++i)
            if (half[i].to == a) {
              n = half[i].third;
              found = true;
              break;
            }
          if (!found)
            for (uint32_t i = start[a], e = start[a + 1]; i < e; ++i)
              if (half[i].to == b && half[i].tri != t) {
                n = half[i].third;
                break;
              }
        }
        o[2 * k + 1] = n;
      }
    }
  } catch (const std::bad_alloc&) {
    return false;
  }
  return true;
}

}  // namespace geom
