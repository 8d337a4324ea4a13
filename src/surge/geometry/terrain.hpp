// Terrain from elevation grids: the surfaces a case's walls are made of when they come from
// a raster (geometry/raster.hpp) instead of an STL file.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/raster.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <string>

namespace surge::geometry {

// Two triangles per pixel square of r (the split surface_height uses), normals up, in r's
// (world) coordinates.
Mesh terrain_mesh(const Raster& r);
// The terrain grid `path` cropped to the domain's x-y extent (InputError naming the file
// when it does not cover it, has no data there or is not projected).
Raster read_terrain(const std::string& path, const Box& domain);
// The surface of a wall or DEM wall: its STL file, or with `terrain` its elevation grid
// cropped to the domain.
Mesh load_surface(const std::string& path, bool terrain, const Box& domain);

} // namespace surge::geometry
