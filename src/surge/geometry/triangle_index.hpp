// A bucket grid over a mesh's triangles, so that the queries near a point (closest
// triangle, the triangles a vertical line crosses) visit a few triangles instead of all:
// a terrain of 10^5 triangles made every wall particle's distance cost 10^5 closest points.
// Queries return triangle indices in ascending order, so that a loop over them meets the
// triangles in the mesh's order, as the loop over all of them did (same ties, same bits).
#pragma once
#include "surge/core/types.hpp"

#include <cstdint>
#include <vector>

namespace surge::geometry {

struct Triangle;

class TriangleIndex {
public:
  explicit TriangleIndex(const std::vector<Triangle>& tris);
  // Indices of the triangles whose bounding boxes meet the box [lo, hi], ascending.
  void overlapping(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const;
  // The smallest box holding every triangle.
  [[nodiscard]] const Vec3d& lo() const { return lo_; }
  [[nodiscard]] const Vec3d& hi() const { return hi_; }
  [[nodiscard]] double cell() const { return cell_; }

private:
  Vec3d lo_{}, hi_{};
  double cell_ = 1;
  long n_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_; // per cell, into items_ (CSR)
  std::vector<std::uint32_t> items_;
  std::vector<Vec3d> box_lo_, box_hi_; // per triangle
  void cell_range(const Vec3d& lo, const Vec3d& hi, long (&c0)[3], long (&c1)[3]) const;
};

} // namespace surge::geometry
