// Spheres by cell of a hashed uniform grid, for set-up work on the host: which of the
// spheres added so far lie near a point (random packs, carving water out of spheres).
#pragma once
#include "surge/core/types.hpp"

#include <cmath>
#include <unordered_map>
#include <vector>

namespace surge::geometry {

class SphereIndex {
public:
  // cell: at least the largest distance asked about (twice the largest radius).
  explicit SphereIndex(double cell) : cell_(cell) {}
  void add(int k, const Vec3d& centre) { cells_[key(idx(centre.x), idx(centre.y), idx(centre.z))].push_back(k); }
  // Calls pred(k) for the spheres in the 27 cells around x until one returns true;
  // returns whether one did.
  template <class P>
  [[nodiscard]] bool any_near(const Vec3d& x, P&& pred) const {
    const long long i0 = idx(x.x), j0 = idx(x.y), k0 = idx(x.z);
    for (long long i = i0 - 1; i <= i0 + 1; ++i)
      for (long long j = j0 - 1; j <= j0 + 1; ++j)
        for (long long k = k0 - 1; k <= k0 + 1; ++k) {
          const auto it = cells_.find(key(i, j, k));
          if (it == cells_.end()) continue;
          for (int s : it->second)
            if (pred(s)) return true;
        }
    return false;
  }

private:
  static long long key(long long i, long long j, long long k) {
    return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL);
  }
  [[nodiscard]] long long idx(double v) const { return static_cast<long long>(std::floor(v / cell_)); }
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

} // namespace surge::geometry
