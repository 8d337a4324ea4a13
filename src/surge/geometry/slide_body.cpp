#include "surge/geometry/slide_body.hpp"

#include "surge/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace surge::geometry {

double slide_volume(const Raster& top, const Raster& bottom, const std::string& bottom_name, double tol) {
  // The surfaces must not cross: the bottom's nodes against the top there.
  long crossed = 0;
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300;
  for (long j = 0; j < bottom.ny; ++j)
    for (long i = 0; i < bottom.nx; ++i) {
      const double t = surface_height(top, bottom.x(i), bottom.y(j)), b = bottom.at(i, j);
      if (std::isnan(t) || !(b > t + tol)) continue;
      ++crossed;
      xlo = std::min(xlo, bottom.x(i));
      xhi = std::max(xhi, bottom.x(i));
      ylo = std::min(ylo, bottom.y(j));
      yhi = std::max(yhi, bottom.y(j));
    }
  if (crossed > 0) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "the sliding surface lies above the pre-failure surface at %ld nodes (%.1f m^2) within x [%.3f, "
                  "%.3f], y [%.3f, %.3f]",
                  crossed, static_cast<double>(crossed) * bottom.dx * bottom.dy, xlo, xhi, ylo, yhi);
    throw InputError(bottom_name, 0, "", msg);
  }
  double volume = 0;
  for (long j = 0; j < bottom.ny; ++j)
    for (long i = 0; i < bottom.nx; ++i) {
      const double t = surface_height(top, bottom.x(i), bottom.y(j));
      if (!std::isnan(t)) volume += std::max(t - bottom.at(i, j), 0.0) * bottom.dx * bottom.dy;
    }
  return volume;
}

PackRegion slide_region(const Raster& top, const Raster& bottom) {
  PackRegion region;
  region.top = &top;
  region.bottom = &bottom;
  Box& b = region.box;
  b.min = {1e300, 1e300, 1e300};
  b.max = {-1e300, -1e300, -1e300};
  for (long j = 0; j < bottom.ny; ++j)
    for (long i = 0; i < bottom.nx; ++i) {
      const double x = bottom.x(i), y = bottom.y(j), t = surface_height(top, x, y), z = bottom.at(i, j);
      if (!(t > z)) continue;
      b.min = {std::min(b.min.x, x - bottom.dx), std::min(b.min.y, y - bottom.dy), std::min(b.min.z, z)};
      b.max = {std::max(b.max.x, x + bottom.dx), std::max(b.max.y, y + bottom.dy), std::max(b.max.z, t)};
    }
  if (b.min.x > b.max.x) b = Box{}; // the surfaces never part: an empty region
  return region;
}

SlideBody fill_slide(const Raster& top, const Raster& bottom, double radius, const Vec3d& origin,
                     const std::string& bottom_name, double jitter, bool aligned, unsigned seed) {
  SlideBody out;
  out.volume = slide_volume(top, bottom, bottom_name);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-jitter * radius, jitter * radius);
  const double d = 2 * radius;
  const double x0 = std::max(top.x(0), bottom.x(0)), x1 = std::min(top.x(top.nx - 1), bottom.x(bottom.nx - 1));
  const double y0 = std::max(top.y(0), bottom.y(0)), y1 = std::min(top.y(top.ny - 1), bottom.y(bottom.ny - 1));
  const long i0 = static_cast<long>(std::ceil((x0 - origin.x) / d - 0.5)),
             i1 = static_cast<long>(std::floor((x1 - origin.x) / d - 0.5));
  const long j0 = static_cast<long>(std::ceil((y0 - origin.y) / d - 0.5)),
             j1 = static_cast<long>(std::floor((y1 - origin.y) / d - 0.5));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const double x = origin.x + (static_cast<double>(i) + 0.5) * d, y = origin.y + (static_cast<double>(j) + 0.5) * d;
      const double t = surface_height(top, x, y), b = surface_height(bottom, x, y);
      if (!(t > b)) continue;
      // Lattice levels origin.z + (k + 1/2) d in (b, t): the column's share of the volume.
      const long k0 = static_cast<long>(std::floor((b - origin.z) / d - 0.5)) + 1;
      const long k1 = static_cast<long>(std::ceil((t - origin.z) / d - 0.5)) - 1;
      const long n = k1 - k0 + 1;
      if (n <= 0) continue;
      // The floor: the sliding surface's highest point under the (moved) sphere's footprint.
      const double sx = jitter > 0 ? shift(rng) : 0, sy = jitter > 0 ? shift(rng) : 0;
      const double floor = std::max(b, highest_under(bottom, x + sx, y + sy, radius));
      double z = floor + radius;
      if (aligned) z = origin.z + (std::ceil((z - origin.z) / d - 0.5) + 0.5) * d;
      for (long k = 0; k < n; ++k) out.spheres.push_back({{x + sx, y + sy, z + static_cast<double>(k) * d}, radius});
    }
  return out;
}

} // namespace surge::geometry
