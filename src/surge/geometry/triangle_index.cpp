#include "surge/geometry/triangle_index.hpp"

#include "surge/geometry/stl_mesh.hpp"

#include <algorithm>

namespace surge::geometry {

TriangleIndex::TriangleIndex(const std::vector<Triangle>& tris) {
  box_lo_.resize(tris.size());
  box_hi_.resize(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) {
    Vec3d a = tris[t].a, b = tris[t].a;
    for (const Vec3d& v : {tris[t].b, tris[t].c})
      for (int k = 0; k < 3; ++k) {
        a[k] = std::min(a[k], v[k]);
        b[k] = std::max(b[k], v[k]);
      }
    box_lo_[t] = a;
    box_hi_[t] = b;
  }
  grid_ = bucket_boxes(box_lo_, box_hi_, 0.0);
  hi_ = grid_.lo;
  for (const Vec3d& b : box_hi_)
    for (int k = 0; k < 3; ++k) hi_[k] = std::max(hi_[k], b[k]);
}

void TriangleIndex::overlapping(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (grid_.start.empty()) return;
  for (int k = 0; k < 3; ++k)
    if (hi[k] < grid_.lo[k] || lo[k] > hi_[k]) return;
  long c0[3], c1[3];
  grid_.cells(lo, hi, c0, c1);
  // A triangle spanning several cells is met once per cell: each is marked in a bitmap of
  // all triangles (this thread's, cleared after use), which is then read in ascending
  // order. The same list as sorting and removing duplicates, without the sort (most of a
  // large query's cost).
  thread_local std::vector<std::uint64_t> seen;
  const std::size_t words = (box_lo_.size() + 63) / 64;
  if (seen.size() < words) seen.resize(words, 0);
  std::size_t first = words, last = 0;
  for (long z = c0[2]; z <= c1[2]; ++z)
    for (long y = c0[1]; y <= c1[1]; ++y)
      for (long x = c0[0]; x <= c1[0]; ++x) {
        const std::size_t c = grid_.index(x, y, z);
        for (std::uint32_t i = grid_.start[c]; i < grid_.start[c + 1]; ++i) {
          const std::uint32_t t = grid_.items[i];
          const Vec3d &a = box_lo_[t], &b = box_hi_[t];
          if (a.x <= hi.x && b.x >= lo.x && a.y <= hi.y && b.y >= lo.y && a.z <= hi.z && b.z >= lo.z) {
            const std::size_t w = t / 64;
            seen[w] |= std::uint64_t{1} << (t % 64);
            first = std::min(first, w);
            last = std::max(last, w);
          }
        }
      }
  for (std::size_t w = first; w <= last && first < words; ++w) {
    for (std::uint64_t bits = seen[w]; bits != 0; bits &= bits - 1)
      out.push_back(static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits))));
    seen[w] = 0;
  }
}

} // namespace surge::geometry
