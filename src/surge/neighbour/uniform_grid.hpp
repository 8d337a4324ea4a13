// Uniform-grid neighbour search (SPEC §5): cell keys, sort, cell start table,
// and the one neighbour loop every physics module uses.
#pragma once
#include "surge/par/parallel.hpp"

#include <cstdint>

namespace surge::neighbour {

struct GridSpec {
  Vec3 lo{};     // lower corner, in the case's local coordinates
  Real cell = 1; // cell edge, >= interaction radius / span
  int nx = 1, ny = 1, nz = 1;
  int span = 1; // stencil half-width in cells: (2 span + 1)^3 cells cover the interaction radius

  [[nodiscard]] SURGE_HD std::uint32_t cells() const { return static_cast<std::uint32_t>(nx) * ny * nz; }
  [[nodiscard]] SURGE_HD int coord(Real x, Real lo_c, int n) const {
    int c = static_cast<int>((x - lo_c) / cell);
    return c < 0 ? 0 : (c >= n ? n - 1 : c);
  }
  [[nodiscard]] SURGE_HD std::uint32_t key(const Vec3& p) const {
    const int cx = coord(p.x, lo.x, nx), cy = coord(p.y, lo.y, ny), cz = coord(p.z, lo.z, nz);
    return static_cast<std::uint32_t>(cx + nx * (cy + ny * cz));
  }
};

// Builds a grid over [lo, hi] with cells of at least radius / span. span 2 (cells of h for
// an SPH support of 2h) scans 125 h^3 around a particle instead of 216 h^3 with span 1.
GridSpec make_grid(const Vec3& lo, const Vec3& hi, Real radius, int span = 1);

// What a kernel needs to walk neighbours: the grid, the sorted positions and
// cell_start. Particles are sorted by (cell, class): within each cell the class-0
// particles (fluid) come first, then class-1 (boundary). cell_start has cells() + 1
// entries: cell c holds [start[c], start[c + 1]), its fluid part up to the first particle
// whose kind is not Fluid (4 B per cell, not 8 for a start per class).
struct GridView {
  GridSpec spec;
  const std::uint32_t* cell_start = nullptr;
  const Vec3* pos = nullptr;
  // The sorted particles' kinds, for for_each_fluid_neighbour (null: every particle fluid).
  const std::uint8_t* kind = nullptr;
  // A bit per cell, set iff the stencil around the cell holds a class-0 (fluid) particle
  // (null: not known); each row of cells along x starts a new 32-bit word (wet_row_words).
  // Boundary particles far from water skip their scan (UniformGrid::mark_wet).
  const std::uint32_t* wet = nullptr;
};

// The 32-bit words of one row of GridView::wet.
[[nodiscard]] SURGE_HD inline int wet_row_words(const GridSpec& s) { return (s.nx + 31) / 32; }

// Whether the stencil around cell c may hold fluid (GridView::wet; true when not known).
[[nodiscard]] SURGE_HD inline bool stencil_wet(const GridView& g, std::uint32_t c) {
  if (!g.wet) return true;
  const auto nx = static_cast<std::uint32_t>(g.spec.nx);
  const std::uint32_t x = c % nx, row = c / nx;
  return ((g.wet[row * static_cast<std::uint32_t>(wet_row_words(g.spec)) + (x >> 5)] >> (x & 31)) & 1U) != 0;
}

// Calls row(first_cell, last_cell) for the (2 span + 1)^2 rows of up to 2 span + 1 cells
// (along x) that make up the stencil around x, clipped to the grid.
template <class R>
SURGE_HD inline void for_each_stencil_row(const GridSpec& s, const Vec3& x, R&& row) {
  const int cx = s.coord(x.x, s.lo.x, s.nx), cy = s.coord(x.y, s.lo.y, s.ny), cz = s.coord(x.z, s.lo.z, s.nz);
  const int m = s.span;
  const int x0 = cx - m > 0 ? cx - m : 0, x1 = cx + m < s.nx ? cx + m : s.nx - 1;
  for (int z = cz - m; z <= cz + m; ++z) {
    if (z < 0 || z >= s.nz) continue;
    for (int y = cy - m; y <= cy + m; ++y) {
      if (y < 0 || y >= s.ny) continue;
      const int base = s.nx * (y + s.ny * z);
      row(base + x0, base + x1);
    }
  }
}

// Calls f(j, x - pos[j], |x - pos[j]|^2) for each j in [begin, end) closer than sqrt(r2max).
template <class F>
SURGE_HD inline void scan_range(const GridView& g, const Vec3& x, Real r2max, std::uint32_t begin, std::uint32_t end,
                                F& f) {
  for (std::uint32_t j = begin; j < end; ++j) {
    const Vec3 d = x - g.pos[j];
    const Real r2 = dot(d, d);
    if (r2 < r2max) f(static_cast<int>(j), d, r2);
  }
}

// Calls range(begin, end) for the particles of each row of the stencil around x (every
// class): contiguous index ranges, in the order of the neighbour loops.
template <class R>
SURGE_HD inline void for_each_stencil_range(const GridView& g, const Vec3& x, R&& range) {
  for_each_stencil_row(g.spec, x, [&](int c0, int c1) { range(g.cell_start[c0], g.cell_start[c1 + 1]); });
}

// Calls f(j, x - pos[j], |x - pos[j]|^2) for every particle j with distance^2 < r2max,
// scanning the stencil around x as contiguous rows. Includes x's own particle.
template <class F>
SURGE_HD inline void for_each_neighbour(const GridView& g, const Vec3& x, Real r2max, F&& f) {
  for_each_stencil_range(g, x, [&](std::uint32_t begin, std::uint32_t end) { scan_range(g, x, r2max, begin, end, f); });
}

// Like for_each_neighbour, over class-0 (fluid) particles only: what boundary
// particles need, without scanning the other boundary particles around them.
template <class F>
SURGE_HD inline void for_each_fluid_neighbour(const GridView& g, const Vec3& x, Real r2max, F&& f) {
  if (!stencil_wet(g, g.spec.key(x))) return; // no fluid in the stencil
  const auto fluid = static_cast<std::uint8_t>(Kind::Fluid);
  for_each_stencil_row(g.spec, x, [&](int c0, int c1) {
    for (int c = c0; c <= c1; ++c) {
      std::uint32_t end = g.cell_start[c];
      if (g.kind)
        while (end < g.cell_start[c + 1] && g.kind[end] == fluid) ++end;
      else
        end = g.cell_start[c + 1];
      scan_range(g, x, r2max, g.cell_start[c], end, f);
    }
  });
}

// Sorting state: keys, the permutation of the last sort, the cell start table.
class UniformGrid {
public:
  void set_spec(const GridSpec& s) { spec_ = s; }
  [[nodiscard]] const GridSpec& spec() const { return spec_; }

  // keys[i] = 2 cell(pos[i]) + cls[i] (cls 0: fluid, 1: boundary), or 2 cells() for
  // cls[i] == 2 (dead), then stable sort. permutation()[i] is the old index of new i.
  // cls may be null (all class 0). With `id` (not null) each cell's particles are ordered
  // by id rather than kept in their previous order: neighbour sums then visit the same
  // particles in the same order however the particles were stored or distributed
  // (what makes a distributed run equal to one process, bit for bit).
  // `scratch` (bytes): memory the sort may use (algo::sort_by_key).
  void sort(const Vec3* pos, const std::uint8_t* cls, int n, const std::uint32_t* id = nullptr, void* scratch = nullptr,
            std::size_t scratch_bytes = 0);
  // Builds cell_start from the sorted keys (no host synchronisation).
  void build_cell_start(int n);
  // The keys, spent once build_cell_start has run: the store's sort borrows them as the
  // scratch of its 4-byte fields (they come back holding anything; the next sort rebuilds them).
  [[nodiscard]] par::Buffer<std::uint32_t>& spent_keys() { return keys_; }
  // After build_cell_start, with the sorted particles' kinds: marks the cells whose stencil
  // holds a fluid particle (GridView::wet): the cells holding one, dilated by the span
  // along x (shifts within a row's words), y and z (ORs of whole rows' words). A bit per
  // cell (span < 32); the SPH store calls it, the DEM does not need it.
  void mark_wet(const std::uint8_t* kind);
  // The number of live (class < 2) particles after build_cell_start: a 4-byte copy to
  // the host (a synchronisation on the GPU, so the step does not ask for it there).
  [[nodiscard]] int live_count() const;

  [[nodiscard]] const std::uint32_t* permutation() const { return perm_.data(); }
  [[nodiscard]] GridView view(const Vec3* sorted_pos, const std::uint8_t* sorted_kind = nullptr) const {
    return {spec_, cell_start_.data(), sorted_pos, sorted_kind, wet_.size() == wet_words() ? wet_.data() : nullptr};
  }
  [[nodiscard]] std::size_t bytes() const {
    return keys_.bytes() + keys64_.bytes() + perm_.bytes() + cell_start_.bytes() + wet_.bytes() + wet_tmp_.bytes();
  }

private:
  [[nodiscard]] std::size_t wet_words() const {
    return static_cast<std::size_t>(spec_.ny) * static_cast<std::size_t>(spec_.nz) *
           static_cast<std::size_t>(wet_row_words(spec_));
  }
  GridSpec spec_;
  par::Buffer<std::uint32_t> keys_, perm_, cell_start_;
  par::Buffer<std::uint64_t> keys64_;        // (key << 32 | id), only for sorts by id
  par::Buffer<std::uint32_t> wet_, wet_tmp_; // a bit per cell, and the dilation's scratch
};

} // namespace surge::neighbour
