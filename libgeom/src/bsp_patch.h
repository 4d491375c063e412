// Private: tessellation of Quake 3 Bezier patches (BSP face type 2).
//
// A patch is a grid of width x height control points (both odd, >= 3), stored
// row-major with x (width) fastest, as in the BSP vertex lump. It is made of
// ((width-1)/2) x ((height-1)/2) biquadratic Bezier pieces, each spanning 3x3
// control points; neighbouring pieces share a row or column of control points.
// (Arneson n.d., Real-Time Shadows, Sect. 2.3: "Patches refer to quadratic
// Bezier patches ... we tessellate them just once at startup".)
//
// Tessellation at level N cuts every piece into N x N cells, so the output is a
// grid of columns x rows points with
//   columns = (width-1)/2 * N + 1,  rows = (height-1)/2 * N + 1,
// stored row-major like the control points, and 2 triangles per cell.
//
// Crack-free by construction: a point on a piece's border is computed from the
// three control points of that border only (the weights of the other rows are
// exactly 0 and 1), with parameters t = i/N and s = (N-i)/N each taken by one
// division, and the quadratic evaluated as (b0*p0 + b2*p2) + b1*p1 with
// b0 = s*s, b1 = 2*(t*s), b2 = t*t. Reversing the border (p2, p1, p0) at index
// N-i swaps t and s and therefore b0 and b2, and the sum is written so that the
// swap gives the same floating-point operations. Two patches that share a
// border curve (same three control points, in either order, at the same level)
// therefore produce bit-identical points along it, so welding by exact position
// joins them with no crack. Negative zero is normalised to +0 so that the bits
// agree too. Arithmetic is in double, rounded once to float.
//
// Winding: triangles are counter-clockwise seen from the side that
// d/dx x d/dy points to (x along width, y along height), which is the side the
// BSP vertex normals of real OpenArena maps point to, the front.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace geom::detail {

constexpr int kMaxPatchLevel = 64;    // segments per piece side
constexpr int kMaxPatchControl = 65;  // control points per side (Quake 3 renderer's MAX_GRID_SIZE)

// Valid sizes: odd, 3 <= width, height <= kMaxPatchControl; 1 <= level <= kMaxPatchLevel.
inline bool patch_size_valid(int64_t width, int64_t height) {
  return width >= 3 && height >= 3 && width <= kMaxPatchControl && height <= kMaxPatchControl && (width & 1) &&
         (height & 1);
}
inline uint64_t patch_columns(int width, int level) { return uint64_t(width - 1) / 2 * uint64_t(level) + 1; }
inline uint64_t patch_rows(int height, int level) { return uint64_t(height - 1) / 2 * uint64_t(level) + 1; }
inline uint64_t patch_triangle_count(int width, int height, int level) {
  return 2 * (patch_columns(width, level) - 1) * (patch_rows(height, level) - 1);
}

// One point of a quadratic Bezier curve with control points p0, p1, p2 (xyz),
// at parameter i/level: symmetric under (p0, p1, p2, i) -> (p2, p1, p0, level-i).
void bezier3(const double* p0, const double* p1, const double* p2, int i, int level, double* out);

// Tessellates one patch. `control` holds width*height xyz triples (read with
// `stride` floats between consecutive points, >= 3). Appends columns*rows xyz
// floats to `points`. Preconditions: patch_size_valid(width, height), level in
// [1, kMaxPatchLevel] (asserted).
void tessellate_patch(const float* control, size_t stride, int width, int height, int level,
                      std::vector<float>& points);

// Appends the 2*(columns-1)*(rows-1) triangles of a columns x rows grid whose
// first point has index `base`, counter-clockwise as documented above.
void patch_grid_triangles(uint32_t columns, uint32_t rows, uint32_t base, std::vector<uint32_t>& indices);

}  // namespace geom::detail
