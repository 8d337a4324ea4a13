// The faces with images of a domain (periodic and symmetry) and the one formula that
// moves a coordinate to its image: header only, plain data, shared by the water's copies
// (domain/images.hpp) and the DEM's mirror partners (dem/dem_solver.cpp), which are not
// copied.
#pragma once
#include "surge/core/types.hpp"

#include <cstdint>

namespace surge::domain {

// The faces with images of a domain (local coordinates) and how far beyond a face they reach.
struct ImageFrame {       // plain data: kernels capture it by value
  int periodic[3]{};      // 1: the two faces of this axis are one
  int mirror_lo[3]{};     // 1: the face lo of this axis is a symmetry plane
  int mirror_hi[3]{};     // 1: ... and hi
  Vec3 lo{}, hi{}, len{}; // the faces, and hi - lo, per axis
  Vec3 band{};            // images lie within this distance of the faces, per axis
  [[nodiscard]] SURGE_HD bool has_images(int k) const { return periodic[k] || mirror_lo[k] || mirror_hi[k]; }
  [[nodiscard]] bool any() const { return has_images(0) || has_images(1) || has_images(2); }
};

// The shifts that put coordinate x of axis k within the band of the domain, the shift 0
// included. Periodic axes: s periods (-3 to 3), lo - band <= x + s len < hi + band. Symmetry
// faces: -1 the mirror in lo (2 lo - x), +1 the mirror in hi, when x is within the band of it.
struct AxisShifts {
  int first = 0, count = 1;
};
[[nodiscard]] SURGE_HD inline AxisShifts axis_shifts(const ImageFrame& f, int k, Real x) {
  if (f.periodic[k]) {
    AxisShifts a{0, 0};
    for (int s = -3; s <= 3; ++s) {
      const Real y = x + static_cast<Real>(s) * f.len[k];
      if (y < f.lo[k] - f.band[k] || y >= f.hi[k] + f.band[k]) continue;
      if (a.count == 0) a.first = s;
      ++a.count;
    }
    if (a.count == 0) return {0, 1}; // outside the band itself (the step's checks see it): no images
    return a;
  }
  const int first = f.mirror_lo[k] && x - f.lo[k] < f.band[k] ? -1 : 0;
  const int last = f.mirror_hi[k] && f.hi[k] - x < f.band[k] ? 1 : 0;
  return {first, last - first + 1};
}

// Coordinate x of axis k moved by shift s (axis_shifts): the one formula of the rebuild and
// the refresh, so that an image refreshed without moving keeps its bits.
[[nodiscard]] SURGE_HD inline Real shifted(const ImageFrame& f, int k, Real x, int s) {
  if (s == 0) return x;
  if (f.periodic[k]) return x + static_cast<Real>(s) * f.len[k];
  return (s < 0 ? 2 * f.lo[k] : 2 * f.hi[k]) - x;
}

} // namespace surge::domain
