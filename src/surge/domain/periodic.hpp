// Periodic axes for what is not copied as images: the DEM's spheres and the coupling's
// body particles. Two spheres across a periodic face meet through the nearest image of
// one of them, found from their positions when the pair is evaluated (the minimum-image
// convention), so a contact or a bond keeps its history, its partner ids and its terms
// as it crosses. Header only: plain data that kernels capture by value.
#pragma once
#include "surge/core/case.hpp"
#include "surge/core/types.hpp"

#include <cmath>

namespace surge::domain {

struct PeriodicAxes {
  int on[3]{};     // 1: the two faces of this axis are one
  Vec3 lo{}, hi{}; // the faces
  Vec3 len{};      // hi - lo on the periodic axes
  [[nodiscard]] SURGE_HD bool any() const { return on[0] || on[1] || on[2]; }

  // The number of periods that puts b nearest to a along axis k (0 off the periodic axes).
  [[nodiscard]] SURGE_HD int periods(const Vec3& a, const Vec3& b, int k) const {
    return on[k] ? static_cast<int>(std::floor((a[k] - b[k]) / len[k] + Real(0.5))) : 0;
  }
  // The image of b nearest to a. Moved as b + s len: where a and b sit on either side of
  // a face at one period's distance, that sum is exact (Sterbenz), so a - image rounds as
  // the difference of the two unwrapped positions does.
  [[nodiscard]] SURGE_HD Vec3 nearest(const Vec3& a, Vec3 b) const {
    for (int k = 0; k < 3; ++k) {
      const int s = periods(a, b, k);
      if (s != 0) b[k] += static_cast<Real>(s) * len[k];
    }
    return b;
  }
  // a - b through the nearest image of b; a - b itself, bit for bit, without periodic axes.
  [[nodiscard]] SURGE_HD Vec3 rel(const Vec3& a, const Vec3& b) const { return any() ? a - nearest(a, b) : a - b; }

  // x moved by a period into [lo, hi) on each periodic axis, or with `half` into
  // [lo - len/2, hi + len/2): the DEM keeps its spheres within half a period beyond a face,
  // so that a cluster crossing a face moves as it would in a wider box.
  SURGE_HD void wrap(Vec3& x, bool half = false) const {
    for (int k = 0; k < 3; ++k) {
      if (!on[k]) continue;
      const Real slack = half ? len[k] / 2 : Real(0);
      if (x[k] >= hi[k] + slack)
        x[k] -= len[k];
      else if (x[k] < lo[k] - slack)
        x[k] += len[k];
    }
  }
};

// The case's periodic axes in local coordinates (the domain's corner at 0).
inline PeriodicAxes periodic_axes(const Case& c) {
  PeriodicAxes p;
  p.hi = Vec3(c.domain.max - c.domain.min);
  for (int k = 0; k < 3; ++k) {
    p.on[k] = c.periodic[static_cast<std::size_t>(k)] ? 1 : 0;
    if (p.on[k]) p.len[k] = p.hi[k] - p.lo[k];
  }
  return p;
}

} // namespace surge::domain
