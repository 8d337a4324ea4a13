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
// `aligned` (bonded bodies): each column starts at the first lattice level (origin.z +
// (k + 1/2) 2 radius) clear of the sliding surface instead of on it, so that neighbouring
// columns' spheres touch (and bond) as in a lattice; the body then rests up to a diameter
// above the surface, on its lowest columns. `jitter` (a fraction of the radius, at most
// 1/2) moves each column by a uniform random offset in x and y (fixed seed), its floor
// taken under the moved footprint.
SlideBody fill_slide(const Raster& top, const Raster& bottom, double radius, const Vec3d& origin,
                     const std::string& bottom_name, double jitter = 0, bool aligned = false, unsigned seed = 12345);
// The integral of top - bottom where positive, on the bottom grid's pixels [m^3]; the
// crossing check of fill_slide.
double slide_volume(const Raster& top, const Raster& bottom, const std::string& bottom_name, double tol = 1e-3);
// The space between the surfaces as a pack region (random packs): the box around the nodes
// where top lies above bottom, grown by a pixel, from the lowest bottom to the highest top.
PackRegion slide_region(const Raster& top, const Raster& bottom);

} // namespace surge::geometry
