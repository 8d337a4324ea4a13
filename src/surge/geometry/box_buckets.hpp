// Boxes by cell of a uniform grid (CSR): the one bucket structure behind the triangle
// index of the SPH walls (geometry/triangle_index.hpp) and the DEM's wall-triangle grid.
// Each cell lists, in ascending order, the boxes that meet it.
#pragma once
#include "surge/core/types.hpp"

#include <cstdint>
#include <vector>

namespace surge::geometry {

struct BoxBuckets {
  Vec3d lo{};                       // the grid's corner: the lowest corner of all boxes
  double cell = 1;                  // cube cells
  long n[3] = {1, 1, 1};            // cells per axis
  std::vector<std::uint32_t> start; // per cell, into items (n cells + 1); empty: no boxes
  std::vector<std::uint32_t> items; // box indices
  // Cell range [c0, c1] per axis covering [a, b], clamped to the grid (as doubles: a box
  // may reach +-1e300, beyond long).
  void cells(const Vec3d& a, const Vec3d& b, long (&c0)[3], long (&c1)[3]) const;
  [[nodiscard]] std::size_t index(long x, long y, long z) const {
    return static_cast<std::size_t>((z * n[1] + y) * n[0] + x);
  }
};

// Cells `min_cell` wide or as wide as the widest box, whichever is more, widened until
// there are at most 8 cells per box (a few long boxes over a large region).
BoxBuckets bucket_boxes(const std::vector<Vec3d>& box_lo, const std::vector<Vec3d>& box_hi, double min_cell);

} // namespace surge::geometry
