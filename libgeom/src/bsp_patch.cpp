// Quake 3 Bezier patch tessellation; the contract and the crack-free argument
// are in bsp_patch.h.
#include "bsp_patch.h"

#include <cassert>

namespace geom::detail {

void bezier3(const double* p0, const double* p1, const double* p2, int i, int level, double* out) {
  const double t = double(i) / double(level);
  const double s = double(level - i) / double(level);
  const double b0 = s * s, b1 = 2.0 * (t * s), b2 = t * t;
  for (int k = 0; k < 3; ++k) out[k] = (b0 * p0[k] + b2 * p2[k]) + b1 * p1[k];
}

void tessellate_patch(const float* control, size_t stride, int width, int height, int level,
                      std::vector<float>& points) {
  assert(patch_size_valid(width, height) && level >= 1 && level <= kMaxPatchLevel && stride >= 3);
  const int pieces_x = (width - 1) / 2, pieces_y = (height - 1) / 2;
  const int columns = int(patch_columns(width, level)), rows = int(patch_rows(height, level));
  auto cp = [&](int x, int y, double* out) {
    const float* p = control + (size_t(y) * size_t(width) + size_t(x)) * stride;
    out[0] = p[0], out[1] = p[1], out[2] = p[2];
  };
  points.reserve(points.size() + size_t(columns) * size_t(rows) * 3);
  std::vector<double> column_curves(size_t(width) * 3);  // the current row's point on every control column
  for (int gy = 0; gy < rows; ++gy) {
    // The piece and local step along y; a point on a seam between pieces is
    // the end of the piece below (i = level), which equals the start of the
    // next one: both are the seam's control point row, exactly.
    const int py = gy / level < pieces_y ? gy / level : pieces_y - 1;
    const int iy = gy - py * level;
    for (int x = 0; x < width; ++x) {
      double a[3], b[3], c[3];
      cp(x, 2 * py, a), cp(x, 2 * py + 1, b), cp(x, 2 * py + 2, c);
      bezier3(a, b, c, iy, level, &column_curves[size_t(x) * 3]);
    }
    for (int gx = 0; gx < columns; ++gx) {
      const int px = gx / level < pieces_x ? gx / level : pieces_x - 1;
      const int ix = gx - px * level;
      double p[3];
      bezier3(&column_curves[size_t(2 * px) * 3], &column_curves[size_t(2 * px + 1) * 3],
              &column_curves[size_t(2 * px + 2) * 3], ix, level, p);
      // On a border along y (ix = 0 or level) the weights (1,0,0) or (0,0,1)
      // return the column curve itself, which depends on that column's
      // control points only. On a border along x (iy = 0 or level) every
      // column curve is its control point, and the x curve uses only the
      // border row. "+ 0.0f" turns -0 into +0.
      for (int k = 0; k < 3; ++k) points.push_back(float(p[k]) + 0.0f);
    }
  }
}

void patch_grid_triangles(uint32_t columns, uint32_t rows, uint32_t base, std::vector<uint32_t>& indices) {
  for (uint32_t y = 0; y + 1 < rows; ++y) {
    for (uint32_t x = 0; x + 1 < columns; ++x) {
      const uint32_t a = base + y * columns + x, b = a + 1, c = a + columns, d = c + 1;
      // a-b along x, a-c along y: (a, b, d) and (a, d, c) turn from x to y.
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
  }
}

}  // namespace geom::detail
