#include "surge/neighbour/uniform_grid.hpp"

#include "surge/algo/algo.hpp"

#include <cmath>
#include <stdexcept>

namespace surge::neighbour {

GridSpec make_grid(const Vec3& lo, const Vec3& hi, Real radius, int span) {
  if (!(radius > 0)) throw std::invalid_argument("grid cell size must be positive");
  if (span < 1) throw std::invalid_argument("grid stencil span must be at least 1");
  GridSpec s;
  s.lo = lo;
  s.span = span;
  // Slightly above radius / span, so that float rounding of the division never makes the
  // stencil miss a neighbour at exactly the radius.
  s.cell = span == 1 ? radius : radius / static_cast<Real>(span) * (1 + Real(1e-6));
  radius = s.cell;
  auto count = [&](Real a, Real b) {
    const double n = std::floor(static_cast<double>(b - a) / static_cast<double>(radius)) + 1.0;
    return n < 1.0 ? 1 : static_cast<int>(n);
  };
  s.nx = count(lo.x, hi.x);
  s.ny = count(lo.y, hi.y);
  s.nz = count(lo.z, hi.z);
  if (static_cast<double>(s.nx) * s.ny * s.nz > 2.0e9)
    throw std::invalid_argument("neighbour grid too large: domain / (2h) exceeds 2e9 cells");
  return s;
}

void UniformGrid::sort(const Vec3* pos, const std::uint8_t* cls, int n, const std::uint32_t* id) {
  keys_.resize(static_cast<std::size_t>(n));
  perm_.resize(static_cast<std::size_t>(n));
  std::uint32_t* keys = keys_.data();
  const GridSpec s = spec_;
  const std::uint32_t sentinel = 2 * s.cells();
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        const std::uint32_t c = cls ? cls[i] : 0U;
        keys[i] = c >= 2 ? sentinel : 2 * s.key(pos[i]) + c;
      });
  algo::iota(perm_.data(), n);
  if (!id) {
    algo::sort_by_key(keys, perm_.data(), n, sentinel);
    return;
  }
  keys64_.resize(static_cast<std::size_t>(n));
  std::uint64_t* k64 = keys64_.data();
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { k64[i] = static_cast<std::uint64_t>(keys[i]) << 32 | id[i]; });
  algo::sort_by_key(k64, perm_.data(), n, static_cast<std::uint64_t>(sentinel) << 32 | 0xffffffffULL);
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { keys[i] = static_cast<std::uint32_t>(k64[i] >> 32); });
}

void UniformGrid::build_cell_start(int n) {
  const std::uint32_t ncell = 2 * spec_.cells(); // (cell, class) slots
  cell_start_.resize(static_cast<std::size_t>(ncell) + 1);
  std::uint32_t* start = cell_start_.data();
  const std::uint32_t* keys = keys_.data();
  if (n == 0) {
    par::fill(cell_start_, 0U);
    return;
  }
  // Every cell c gets the first index whose key is >= c; each entry is written once:
  // by the particle where the key jumps past it, or by the tail loop.
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        const std::uint32_t prev = i == 0 ? 0U : keys[i - 1] + 1U;
        const std::uint32_t k = keys[i] < ncell ? keys[i] : ncell;
        for (std::uint32_t c = prev; c <= k; ++c) start[c] = static_cast<std::uint32_t>(i);
        if (i == n - 1) {
          for (std::uint32_t c = k + 1; c <= ncell; ++c) start[c] = static_cast<std::uint32_t>(n);
        }
      });
}

namespace detail {
// out[c] = whether any of in[] within `span` cells of c along `axis` (0, 1, 2) is set. One
// row of cells (along x) per index, ORed from shifted (x) or neighbouring (y, z) rows:
// contiguous byte loops the compiler vectorises.
void dilate_cells(const GridSpec& s, const std::uint8_t* in, std::uint8_t* out, int axis) {
  const int m = s.span, nx = s.nx, ny = s.ny, nz = s.nz;
  par::parallel_for(
      ny * nz, SURGE_LAMBDA(int row) {
        std::uint8_t* o = out + static_cast<std::ptrdiff_t>(row) * nx;
        for (int x = 0; x < nx; ++x) o[x] = 0;
        const int y = row % ny, z = row / ny;
        for (int d = -m; d <= m; ++d) {
          if (axis == 0) {
            const std::uint8_t* r = in + static_cast<std::ptrdiff_t>(row) * nx;
            for (int x = d < 0 ? -d : 0; x < (d > 0 ? nx - d : nx); ++x) o[x] |= r[x + d];
          } else {
            const int yy = axis == 1 ? y + d : y, zz = axis == 2 ? z + d : z;
            if (yy < 0 || yy >= ny || zz < 0 || zz >= nz) continue;
            const std::uint8_t* r = in + static_cast<std::ptrdiff_t>(yy + ny * zz) * nx;
            for (int x = 0; x < nx; ++x) o[x] |= r[x];
          }
        }
      });
}
} // namespace detail

void UniformGrid::mark_wet() {
  const GridSpec s = spec_;
  wet_.resize(s.cells());
  wet_scratch_.resize(s.cells());
  std::uint8_t* a = wet_.data();
  std::uint8_t* b = wet_scratch_.data();
  const std::uint32_t* start = cell_start_.data();
  par::parallel_for(
      static_cast<int>(s.cells()), SURGE_LAMBDA(int c) { b[c] = start[2 * c + 1] > start[2 * c] ? 1 : 0; });
  detail::dilate_cells(s, b, a, 0);
  detail::dilate_cells(s, a, b, 1);
  detail::dilate_cells(s, b, a, 2);
}

int UniformGrid::live_count() const {
  std::vector<std::uint32_t> live;
  par::download_range(live, cell_start_, cell_start_.size() - 1, 1);
  return static_cast<int>(live[0]);
}

} // namespace surge::neighbour
