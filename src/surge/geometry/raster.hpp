// Grids of values on a horizontal lattice, read and written through GDAL (any raster format
// it reads: GeoTIFF, ESRI ASCII grid, ...): terrain and slide surfaces in, hazard maps out.
// The only code that calls GDAL.
#pragma once
#include <cmath>
#include <string>
#include <vector>

namespace surge::geometry {

// Node (i, j) holds the value of pixel column i, row j counted from the south, at the
// pixel's centre (x0 + i dx, y0 + j dy): rows run north-up in the file and are flipped here.
struct Raster {
  std::string path;      // where it was read from (messages)
  double x0 = 0, y0 = 0; // world coordinates of node (0, 0), the south-west pixel's centre
  double dx = 1, dy = 1; // pixel size along x (east) and y (north), > 0
  long nx = 0, ny = 0;
  std::vector<double> v; // v[j * nx + i]; NaN where the file has no data
  std::string crs_wkt;   // the coordinate system, as WKT ("" when the file has none)

  [[nodiscard]] double x(long i) const { return x0 + static_cast<double>(i) * dx; }
  [[nodiscard]] double y(long j) const { return y0 + static_cast<double>(j) * dy; }
  [[nodiscard]] double at(long i, long j) const { return v[static_cast<std::size_t>(j * nx + i)]; }
  [[nodiscard]] double& at(long i, long j) { return v[static_cast<std::size_t>(j * nx + i)]; }
};

// Band 1 of a raster file. InputError naming the file when GDAL cannot read it as a raster,
// when it is rotated or sheared, or (`need_projected`) when its coordinate system is missing
// or not projected (surge's coordinates are metres).
Raster read_raster(const std::string& path, bool need_projected = true);
// The nodes of r whose pixels meet [xlo, xhi] x [ylo, yhi], grown by one node each way where
// r has them. InputError naming r.path and `what` when r's nodes do not span the area or
// a node inside it has no data.
Raster crop(const Raster& r, double xlo, double ylo, double xhi, double yhi, const std::string& what);
// The value on the surface through the nodes, two triangles per pixel square (the diagonal
// from (i, j) to (i + 1, j + 1)), as terrain_mesh triangulates it; NaN outside the nodes.
double surface_height(const Raster& r, double x, double y);
// The surface's highest point over the disc of radius `radius` about (x, y) (exact: each
// triangle's maximum over its part of the disc); NaN where the disc misses the grid. The
// part of the disc off the grid is not counted.
double highest_under(const Raster& r, double x, double y, double radius);

// Writes bands of values on r's lattice (r.v unused) as a GeoTIFF with r's coordinate
// system, north-up; NaN written as no data. Throws std::runtime_error naming the file.
void write_geotiff(const std::string& path, const Raster& lattice, const std::vector<std::vector<double>>& bands,
                   const std::vector<std::string>& names);

} // namespace surge::geometry
