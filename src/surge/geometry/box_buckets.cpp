#include "surge/geometry/box_buckets.hpp"

#include <algorithm>
#include <cmath>

namespace surge::geometry {

void BoxBuckets::cells(const Vec3d& a, const Vec3d& b, long (&c0)[3], long (&c1)[3]) const {
  auto at = [&](double v, int k) {
    return static_cast<long>(std::clamp(std::floor((v - lo[k]) / cell), 0.0, static_cast<double>(n[k] - 1)));
  };
  for (int k = 0; k < 3; ++k) {
    c0[k] = at(a[k], k);
    c1[k] = at(b[k], k);
  }
}

BoxBuckets bucket_boxes(const std::vector<Vec3d>& box_lo, const std::vector<Vec3d>& box_hi, double min_cell) {
  BoxBuckets g;
  if (box_lo.empty()) return g;
  Vec3d hi{-1e300, -1e300, -1e300};
  g.lo = {1e300, 1e300, 1e300};
  double extent = 0;
  for (std::size_t t = 0; t < box_lo.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      g.lo[k] = std::min(g.lo[k], box_lo[t][k]);
      hi[k] = std::max(hi[k], box_hi[t][k]);
      extent = std::max(extent, box_hi[t][k] - box_lo[t][k]);
    }
  const Vec3d size = hi - g.lo;
  g.cell = std::max({extent, min_cell, 1e-9 * std::max({size.x, size.y, size.z, 1.0})});
  const double max_cells = 8.0 * static_cast<double>(box_lo.size()) + 64;
  while (true) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) cells *= std::floor(size[k] / g.cell) + 1;
    if (cells <= max_cells) break;
    g.cell *= 1.5;
  }
  for (int k = 0; k < 3; ++k) g.n[k] = static_cast<long>(std::floor(size[k] / g.cell)) + 1;
  const auto n_cells = static_cast<std::size_t>(g.n[0] * g.n[1] * g.n[2]);
  std::vector<std::uint32_t> count(n_cells + 1, 0);
  // Two passes (count, then place): boxes ascending within each cell.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      g.start.assign(n_cells + 1, 0);
      for (std::size_t c = 0; c < n_cells; ++c) g.start[c + 1] = g.start[c] + count[c];
      g.items.resize(g.start[n_cells]);
      std::fill(count.begin(), count.end(), 0);
    }
    for (std::size_t t = 0; t < box_lo.size(); ++t) {
      long c0[3], c1[3];
      g.cells(box_lo[t], box_hi[t], c0, c1);
      for (long z = c0[2]; z <= c1[2]; ++z)
        for (long y = c0[1]; y <= c1[1]; ++y)
          for (long x = c0[0]; x <= c1[0]; ++x) {
            const std::size_t c = g.index(x, y, z);
            if (pass == 1) g.items[g.start[c] + count[c]] = static_cast<std::uint32_t>(t);
            ++count[c];
          }
    }
  }
  return g;
}

} // namespace surge::geometry
