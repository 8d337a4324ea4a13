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

void UniformGrid::sort(const Vec3* pos, const std::uint8_t* cls, int n, const std::uint32_t* id, void* scratch,
                       std::size_t scratch_bytes) {
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
    algo::sort_by_key(keys, perm_.data(), n, sentinel, scratch, scratch_bytes);
    return;
  }
  keys64_.resize(static_cast<std::size_t>(n));
  std::uint64_t* k64 = keys64_.data();
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { k64[i] = static_cast<std::uint64_t>(keys[i]) << 32 | id[i]; });
  algo::sort_by_key(k64, perm_.data(), n, static_cast<std::uint64_t>(sentinel) << 32 | 0xffffffffULL, scratch,
                    scratch_bytes);
  par::parallel_for(
      n, SURGE_LAMBDA(int i) { keys[i] = static_cast<std::uint32_t>(k64[i] >> 32); });
}

void UniformGrid::build_cell_start(int n) {
  const std::uint32_t ncell = spec_.cells();
  cell_start_.resize(static_cast<std::size_t>(ncell) + 1);
  std::uint32_t* start = cell_start_.data();
  const std::uint32_t* keys = keys_.data();
  if (n == 0) {
    par::fill(cell_start_, 0U);
    return;
  }
  // Every cell c gets the first index whose cell (key / 2) is >= c; each entry is written
  // once: by the particle where the cell jumps past it, or by the tail loop. One entry per
  // cell, not per (cell, class): a cell's fluid part ends at its first boundary particle.
  par::parallel_for(
      n, SURGE_LAMBDA(int i) {
        const std::uint32_t prev = i == 0 ? 0U : (keys[i - 1] >> 1) + 1U;
        const std::uint32_t k = (keys[i] >> 1) < ncell ? keys[i] >> 1 : ncell;
        for (std::uint32_t c = prev; c <= k; ++c) start[c] = static_cast<std::uint32_t>(i);
        if (i == n - 1) {
          for (std::uint32_t c = k + 1; c <= ncell; ++c) start[c] = static_cast<std::uint32_t>(n);
        }
      });
}

namespace detail {
// out's row (y, z) = the OR of in's rows (y + d, z) (along y) or (y, z + d) (along z) for
// |d| <= m, `words` 32-bit words per row. (A free function: nvcc's extended lambdas need an
// enclosing function with external linkage.)
void dilate_rows(const std::uint32_t* in, std::uint32_t* out, int words, int ny, int nz, int m, bool along_z) {
  par::parallel_for(
      ny * nz, SURGE_LAMBDA(int row) {
        const int y = row % ny, z = row / ny;
        std::uint32_t* o = out + static_cast<std::ptrdiff_t>(row) * words;
        for (int w = 0; w < words; ++w) o[w] = 0;
        for (int d = -m; d <= m; ++d) {
          const int yy = along_z ? y : y + d, zz = along_z ? z + d : z;
          if (yy < 0 || yy >= ny || zz < 0 || zz >= nz) continue;
          const std::uint32_t* r = in + static_cast<std::ptrdiff_t>(yy + ny * zz) * words;
          for (int w = 0; w < words; ++w) o[w] |= r[w];
        }
      });
}
} // namespace detail

void UniformGrid::mark_wet(const std::uint8_t* kind) {
  const GridSpec s = spec_;
  if (s.span >= 32) throw std::invalid_argument("mark_wet: the stencil's span must be below 32 cells");
  const int words = wet_row_words(s), rows = s.ny * s.nz, m = s.span, ny = s.ny, nz = s.nz, nx = s.nx;
  wet_.resize(wet_words());
  wet_tmp_.resize(wet_words());
  std::uint32_t* wet = wet_.data();
  std::uint32_t* tmp = wet_tmp_.data();
  const std::uint32_t* start = cell_start_.data();
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  // Each row: the cells holding fluid (a cell does iff its first particle is fluid: fluid
  // comes first in each cell) as bits in `wet`, then dilated along x into `tmp`.
  par::parallel_for(
      rows, SURGE_LAMBDA(int row) {
        std::uint32_t* in = wet + static_cast<std::ptrdiff_t>(row) * words;
        std::uint32_t* out = tmp + static_cast<std::ptrdiff_t>(row) * words;
        const std::uint32_t first = static_cast<std::uint32_t>(row) * static_cast<std::uint32_t>(nx);
        for (int w = 0; w < words; ++w) {
          std::uint32_t bits = 0;
          for (int b = 0; b < 32 && 32 * w + b < nx; ++b) {
            const std::uint32_t c = first + static_cast<std::uint32_t>(32 * w + b);
            bits |= static_cast<std::uint32_t>(start[c + 1] > start[c] && kind[start[c]] == fluid) << b;
          }
          in[w] = bits;
        }
        for (int w = 0; w < words; ++w) {
          std::uint32_t d = in[w];
          const std::uint32_t below = w > 0 ? in[w - 1] : 0U, above = w + 1 < words ? in[w + 1] : 0U;
          for (int k = 1; k <= m; ++k) // bit x takes bits x - k and x + k
            d |= in[w] << k | below >> (32 - k) | in[w] >> k | above << (32 - k);
          out[w] = d;
        }
      });
  // Along y (tmp -> wet), then z (wet -> tmp), whole rows ORed word by word; the result
  // ends in tmp, which becomes wet.
  detail::dilate_rows(tmp, wet, words, ny, nz, m, false);
  detail::dilate_rows(wet, tmp, words, ny, nz, m, true);
  wet_.swap(wet_tmp_);
}

int UniformGrid::live_count() const {
  std::vector<std::uint32_t> live;
  par::download_range(live, cell_start_, cell_start_.size() - 1, 1);
  return static_cast<int>(live[0]);
}

} // namespace surge::neighbour
