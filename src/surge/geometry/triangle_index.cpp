#include "surge/geometry/triangle_index.hpp"

#include "surge/geometry/stl_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace surge::geometry {

TriangleIndex::TriangleIndex(const std::vector<Triangle>& tris) {
  lo_ = {1e300, 1e300, 1e300};
  hi_ = {-1e300, -1e300, -1e300};
  box_lo_.resize(tris.size());
  box_hi_.resize(tris.size());
  double extent = 0;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    Vec3d a = tris[t].a, b = tris[t].a;
    for (const Vec3d& v : {tris[t].b, tris[t].c})
      for (int k = 0; k < 3; ++k) {
        a[k] = std::min(a[k], v[k]);
        b[k] = std::max(b[k], v[k]);
      }
    box_lo_[t] = a;
    box_hi_[t] = b;
    for (int k = 0; k < 3; ++k) {
      lo_[k] = std::min(lo_[k], a[k]);
      hi_[k] = std::max(hi_[k], b[k]);
    }
    extent = std::max({extent, b.x - a.x, b.y - a.y, b.z - a.z});
  }
  if (tris.empty()) return;
  // Cells about a triangle wide (each triangle in a few cells), but no more cells than
  // 8 per triangle (a mesh of a few long triangles over a large box).
  const Vec3d size = hi_ - lo_;
  cell_ = std::max(extent, 1e-9 * std::max({size.x, size.y, size.z, 1.0}));
  const double max_cells = 8.0 * static_cast<double>(tris.size()) + 64;
  while (true) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) cells *= std::floor(size[k] / cell_) + 1;
    if (cells <= max_cells) break;
    cell_ *= 1.5;
  }
  for (int k = 0; k < 3; ++k) n_[k] = static_cast<long>(std::floor(size[k] / cell_)) + 1;
  const auto n_cells = static_cast<std::size_t>(n_[0] * n_[1] * n_[2]);
  std::vector<std::uint32_t> count(n_cells + 1, 0);
  // Two passes (count, then place): CSR, triangles ascending within each cell.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      start_.assign(n_cells + 1, 0);
      for (std::size_t c = 0; c < n_cells; ++c) start_[c + 1] = start_[c] + count[c];
      items_.resize(start_[n_cells]);
      std::fill(count.begin(), count.end(), 0);
    }
    for (std::size_t t = 0; t < tris.size(); ++t) {
      long c0[3], c1[3];
      cell_range(box_lo_[t], box_hi_[t], c0, c1);
      for (long z = c0[2]; z <= c1[2]; ++z)
        for (long y = c0[1]; y <= c1[1]; ++y)
          for (long x = c0[0]; x <= c1[0]; ++x) {
            const auto c = static_cast<std::size_t>((z * n_[1] + y) * n_[0] + x);
            if (pass == 1) items_[start_[c] + count[c]] = static_cast<std::uint32_t>(t);
            ++count[c];
          }
    }
  }
}

void TriangleIndex::cell_range(const Vec3d& lo, const Vec3d& hi, long (&c0)[3], long (&c1)[3]) const {
  // Clamped as doubles: a query box may reach to +-1e300 (a vertical line), beyond long.
  auto cell = [&](double v, int k) {
    return static_cast<long>(std::clamp(std::floor((v - lo_[k]) / cell_), 0.0, static_cast<double>(n_[k] - 1)));
  };
  for (int k = 0; k < 3; ++k) {
    c0[k] = cell(lo[k], k);
    c1[k] = cell(hi[k], k);
  }
}

void TriangleIndex::overlapping(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  out.clear();
  for (int k = 0; k < 3; ++k)
    if (hi[k] < lo_[k] || lo[k] > hi_[k] || start_.empty()) return;
  long c0[3], c1[3];
  cell_range(lo, hi, c0, c1);
  for (long z = c0[2]; z <= c1[2]; ++z)
    for (long y = c0[1]; y <= c1[1]; ++y)
      for (long x = c0[0]; x <= c1[0]; ++x) {
        const auto c = static_cast<std::size_t>((z * n_[1] + y) * n_[0] + x);
        for (std::uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
          const std::uint32_t t = items_[i];
          const Vec3d &a = box_lo_[t], &b = box_hi_[t];
          if (a.x <= hi.x && b.x >= lo.x && a.y <= hi.y && b.y >= lo.y && a.z <= hi.z && b.z >= lo.z) out.push_back(t);
        }
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

} // namespace surge::geometry
