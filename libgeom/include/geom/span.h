// geom/span.h: a borrowed, strided, read-only view of vertex data.
//
// One type for "pointer + count + byte stride" so a pointer and a stride are
// never passed separately and mixed up. A tightly packed float xyz array has stride 12.
#pragma once
#include <cassert>
#include <cstddef>
#include <cstdint>

namespace geom {

template <class T>
struct StridedSpan {
  const unsigned char* data = nullptr;
  size_t count = 0;   // number of elements
  size_t stride = 0;  // bytes between consecutive elements

  StridedSpan() = default;
  StridedSpan(const T* first, size_t n, size_t stride_bytes = sizeof(T))
      : data(reinterpret_cast<const unsigned char*>(first)), count(n), stride(stride_bytes) {}
  StridedSpan(const void* first, size_t n, size_t stride_bytes)
      : data(static_cast<const unsigned char*>(first)), count(n), stride(stride_bytes) {}

  const T& operator[](size_t i) const {
    assert(i < count);
    return *reinterpret_cast<const T*>(data + i * stride);
  }
  size_t size() const { return count; }
  bool empty() const { return count == 0; }
};

// Three floats; the element type of position spans.
struct Float3 {
  float x, y, z;
};

using PositionSpan = StridedSpan<Float3>;

// Packed xyz float array of n vertices (3n floats).
inline PositionSpan positions_of(const float* xyz, size_t vertex_count) {
  return PositionSpan(xyz, vertex_count, 3 * sizeof(float));
}

}  // namespace geom
