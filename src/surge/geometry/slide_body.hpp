// A slide body between two elevation grids: the pre-failure surface (top) and the sliding
// surface (bottom), filled with DEM spheres.
#pragma once
#include "surge/geometry/raster.hpp"
#include "surge/geometry/sphere_packs.hpp"

#include <string>
#include <vector>

namespace surge::geometry {

struct SlideBody {
  std::vector<SphereSpec> spheres;
  double volume = 0; // the integral of top - bottom where positive [m^3]
};

// Columns of spheres of `radius` on the lattice of spacing 2 radius in x and y (aligned to
// `origin`): a column holds as many spheres as lattice points of spacing 2 radius lie
// between the surfaces at its centre (so the spheres' cells hold the body's volume, to the
// rounding of each column), stacked from the sliding surface up, the lowest clear of it
// (its highest point within the sphere's footprint). Where the bottom lies above the top
// by more than `tol` the surfaces cross: InputError naming `bottom_name` with that area
// and its extent.
SlideBody fill_slide(const Raster& top, const Raster& bottom, double radius, const Vec3d& origin,
                     const std::string& bottom_name, double tol = 1e-3);

} // namespace surge::geometry
