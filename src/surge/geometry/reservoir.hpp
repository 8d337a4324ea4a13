// A reservoir's water: the lattice points below a level that are clear of the walls and
// connected to a seed point, so that basins the lake does not reach (above the dam, outside
// the valley) stay dry.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <functional>
#include <string>
#include <vector>

namespace surge::geometry {

struct ReservoirFill {
  std::vector<Vec3d> points; // lattice points, in z-y-x order
  long columns = 0;          // (x, y) columns holding water: the free surface's area / dp^2
  long near_shore = 0;       // of these, those within 2 dp of a dry column or the lattice's edge
  std::string seed_problem;  // non-empty: the seed is on dry land (why), no points
};

// True where wall w keeps a reservoir's water out of the lattice point p: at or behind a
// mesh's surface (the lattice runs on into the mesh's wall layers, so the water's volume
// is that of the lake, not short of a half spacing along its shores), inside a solid box
// or less than dp/2 from it, outside a tank's interior or less than dp/2 inside it.
bool keeps_water_out(const WallSpec& w, const Mesh* mesh, const Vec3d& p, double dp);

// The corner of the lattice that walls from meshes and reservoirs share: the domain's
// lowest corner, lowered (by less than dp) so that the first reservoir's level falls on a
// face of the lattice and its water stands exactly to the level.
Vec3d lattice_origin(const Case& c);

// Lattice origin + (i + 1/2) dp inside the domain; a point is water when its top lies at
// most at the level (z + dp/2 <= level), `blocked` is false and it connects face to face to
// the seed column's highest such point.
ReservoirFill fill_reservoir(const FluidRegion& f, const Box& domain, const Vec3d& origin, double dp,
                             const std::function<bool(const Vec3d&)>& blocked);

} // namespace surge::geometry
