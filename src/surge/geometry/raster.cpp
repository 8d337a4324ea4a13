#include "surge/geometry/raster.hpp"

#include "surge/core/error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <dlfcn.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace surge::geometry {
namespace {
// GDAL is opened on first use, not linked: linking it loads its hundred-odd libraries into
// every run, 30 MB of resident memory (115 B per particle of the benchmark dam break) that
// a run without rasters never uses. The headers give each function's type; SURGE_GDAL_LIBRARY
// is the library's soname, found by CMake.
#define SURGE_GDAL_FUNCTIONS(X)                                                                                        \
  X(GDALAllRegister)                                                                                                   \
  X(CPLSetErrorHandler)                                                                                                \
  X(CPLQuietErrorHandler)                                                                                              \
  X(CPLGetLastErrorMsg)                                                                                                \
  X(CPLErrorReset)                                                                                                     \
  X(GDALOpenEx)                                                                                                        \
  X(GDALClose)                                                                                                         \
  X(GDALGetGeoTransform)                                                                                               \
  X(GDALGetRasterXSize)                                                                                                \
  X(GDALGetRasterYSize)                                                                                                \
  X(GDALGetRasterCount)                                                                                                \
  X(GDALGetProjectionRef)                                                                                              \
  X(OSRNewSpatialReference)                                                                                            \
  X(OSRIsProjected)                                                                                                    \
  X(OSRDestroySpatialReference)                                                                                        \
  X(GDALGetRasterBand)                                                                                                 \
  X(GDALGetRasterNoDataValue)                                                                                          \
  X(GDALRasterIO)                                                                                                      \
  X(GDALGetDriverByName)                                                                                               \
  X(GDALCreate)                                                                                                        \
  X(GDALSetGeoTransform)                                                                                               \
  X(GDALSetProjection)                                                                                                 \
  X(GDALSetRasterNoDataValue)                                                                                          \
  X(GDALSetDescription)

struct Gdal {
// NOLINTNEXTLINE(bugprone-macro-parentheses): f names a member, which parentheses would break
#define SURGE_GDAL_POINTER(f) decltype(&::f) f = nullptr;
  SURGE_GDAL_FUNCTIONS(SURGE_GDAL_POINTER)
#undef SURGE_GDAL_POINTER
};

Gdal open_gdal() {
  void* lib = dlopen(SURGE_GDAL_LIBRARY, RTLD_NOW | RTLD_LOCAL); // kept open for the run
  if (!lib) {
    const char* why = dlerror();
    throw std::runtime_error(std::string("reading or writing rasters needs GDAL (" SURGE_GDAL_LIBRARY "): ") +
                             (why ? why : "cannot open it"));
  }
  Gdal g;
#define SURGE_GDAL_LOAD(f)                                                                                             \
  g.f = reinterpret_cast<decltype(g.f)>(dlsym(lib, #f));                                                               \
  if (!g.f) throw std::runtime_error(SURGE_GDAL_LIBRARY " has no " #f);
  SURGE_GDAL_FUNCTIONS(SURGE_GDAL_LOAD)
#undef SURGE_GDAL_LOAD
  g.GDALAllRegister();
  g.CPLSetErrorHandler(g.CPLQuietErrorHandler); // GDAL's messages reach the user through ours
  return g;
}

// The library, opened and its drivers registered on the first call (once, thread-safe).
const Gdal& gdal() {
  static const Gdal g = open_gdal();
  return g;
}
std::string last_gdal_error() {
  const char* m = gdal().CPLGetLastErrorMsg();
  return m && *m ? std::string(" (") + m + ")" : std::string();
}
// Closes a dataset on every path out.
struct Dataset {
  GDALDatasetH h = nullptr;
  ~Dataset() {
    if (h) gdal().GDALClose(h);
  }
};
} // namespace

Raster read_raster(const std::string& path, bool need_projected) {
  const Gdal& g = gdal();
  g.CPLErrorReset();
  Dataset ds{g.GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)};
  if (!ds.h) throw InputError(path, 0, "", "not a raster GDAL can read" + last_gdal_error());
  double gt[6];
  if (g.GDALGetGeoTransform(ds.h, gt) != CE_None)
    throw InputError(path, 0, "", "the raster has no georeferencing (no origin and pixel size)");
  if (gt[2] != 0 || gt[4] != 0)
    throw InputError(path, 0, "", "the raster is rotated or sheared; warp it north-up first (gdalwarp)");
  if (!(gt[1] > 0) || gt[5] == 0) throw InputError(path, 0, "", "the raster's pixel size is not positive");
  Raster r;
  r.path = path;
  r.nx = g.GDALGetRasterXSize(ds.h);
  r.ny = g.GDALGetRasterYSize(ds.h);
  if (r.nx < 2 || r.ny < 2 || g.GDALGetRasterCount(ds.h) < 1)
    throw InputError(path, 0, "", "the raster needs a band of at least 2 x 2 pixels");
  const char* wkt = g.GDALGetProjectionRef(ds.h);
  r.crs_wkt = wkt ? wkt : "";
  if (need_projected) {
    OGRSpatialReferenceH srs = r.crs_wkt.empty() ? nullptr : g.OSRNewSpatialReference(r.crs_wkt.c_str());
    const bool projected = srs && g.OSRIsProjected(srs);
    if (srs) g.OSRDestroySpatialReference(srs);
    if (!projected)
      throw InputError(path, 0, "",
                       r.crs_wkt.empty() ? "the raster has no coordinate system; surge needs a projected one (metres)"
                                         : "the raster's coordinate system is not projected; reproject it to one in "
                                           "metres (gdalwarp -t_srs)");
  }
  r.dx = gt[1];
  r.dy = std::fabs(gt[5]);
  r.x0 = gt[0] + 0.5 * gt[1];
  // North-up files (gt[5] < 0) store the northern row first.
  const bool north_up = gt[5] < 0;
  r.y0 = north_up ? gt[3] + (static_cast<double>(r.ny) - 0.5) * gt[5] : gt[3] + 0.5 * gt[5];
  GDALRasterBandH band = g.GDALGetRasterBand(ds.h, 1);
  int has_nodata = 0;
  const double nodata = g.GDALGetRasterNoDataValue(band, &has_nodata);
  r.v.assign(static_cast<std::size_t>(r.nx * r.ny), 0.0);
  std::vector<double> row(static_cast<std::size_t>(r.nx));
  for (long k = 0; k < r.ny; ++k) {
    if (g.GDALRasterIO(band, GF_Read, 0, static_cast<int>(k), static_cast<int>(r.nx), 1, row.data(),
                       static_cast<int>(r.nx), 1, GDT_Float64, 0, 0) != CE_None)
      throw InputError(path, 0, "", "cannot read row " + std::to_string(k) + last_gdal_error());
    const long j = north_up ? r.ny - 1 - k : k;
    for (long i = 0; i < r.nx; ++i) {
      const double z = row[static_cast<std::size_t>(i)];
      r.at(i, j) = (has_nodata && z == nodata) || !std::isfinite(z) ? std::numeric_limits<double>::quiet_NaN() : z;
    }
  }
  return r;
}

Raster crop(const Raster& r, double xlo, double ylo, double xhi, double yhi, const std::string& what) {
  // The nodes must span the area: the surface between nodes is what the area holds.
  const double tol = 1e-9 * std::max(r.dx, r.dy);
  if (xlo < r.x(0) - tol || xhi > r.x(r.nx - 1) + tol || ylo < r.y(0) - tol || yhi > r.y(r.ny - 1) + tol) {
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "%s: the grid's pixel centres span x [%.3f, %.3f], y [%.3f, %.3f]; the area needs x [%.3f, %.3f], "
                  "y [%.3f, %.3f]",
                  what.c_str(), r.x(0), r.x(r.nx - 1), r.y(0), r.y(r.ny - 1), xlo, xhi, ylo, yhi);
    throw InputError(r.path, 0, "", msg);
  }
  auto first = [&](double lo, double o, double d) { return static_cast<long>(std::floor((lo - o) / d + 1e-9)) - 1; };
  auto last = [&](double hi, double o, double d) { return static_cast<long>(std::ceil((hi - o) / d - 1e-9)) + 1; };
  const long i0 = std::max(0L, first(xlo, r.x0, r.dx)), i1 = std::min(r.nx - 1, last(xhi, r.x0, r.dx));
  const long j0 = std::max(0L, first(ylo, r.y0, r.dy)), j1 = std::min(r.ny - 1, last(yhi, r.y0, r.dy));
  Raster c = r;
  c.x0 = r.x(i0);
  c.y0 = r.y(j0);
  c.nx = i1 - i0 + 1;
  c.ny = j1 - j0 + 1;
  c.v.assign(static_cast<std::size_t>(c.nx * c.ny), 0.0);
  for (long j = 0; j < c.ny; ++j)
    for (long i = 0; i < c.nx; ++i) {
      const double z = r.at(i0 + i, j0 + j);
      if (std::isnan(z)) {
        char msg[300];
        std::snprintf(msg, sizeof msg, "%s: no data at the pixel centred on (%.3f, %.3f), inside the area in use",
                      what.c_str(), c.x(i), c.y(j));
        throw InputError(r.path, 0, "", msg);
      }
      c.at(i, j) = z;
    }
  return c;
}

double surface_height(const Raster& r, double x, double y) {
  const double u = (x - r.x0) / r.dx, w = (y - r.y0) / r.dy;
  if (!(u >= 0 && w >= 0 && u <= static_cast<double>(r.nx - 1) && w <= static_cast<double>(r.ny - 1)))
    return std::numeric_limits<double>::quiet_NaN();
  const long i = std::min(static_cast<long>(u), r.nx - 2), j = std::min(static_cast<long>(w), r.ny - 2);
  const double s = u - static_cast<double>(i), t = w - static_cast<double>(j);
  const double z00 = r.at(i, j), z11 = r.at(i + 1, j + 1);
  // Split along the diagonal (i, j)-(i + 1, j + 1): below it the triangle with (i + 1, j).
  if (s >= t) return z00 + s * (r.at(i + 1, j) - z00) + t * (z11 - r.at(i + 1, j));
  return z00 + t * (r.at(i, j + 1) - z00) + s * (z11 - r.at(i, j + 1));
}

namespace {
// The highest point of the plane through triangle (p0, p1, p2) (x, y, z each) over the
// part of the triangle inside the disc (c, radius): the maximum of a linear function over
// that convex set lies at one of its corners (vertices inside the disc, edges crossing the
// rim) or on one of its arcs, where the rim points along the plane's rising gradient.
void raise_to_triangle_max(const double (&p)[3][3], double cx, double cy, double radius, double& top) {
  auto take = [&](double h) { top = std::max(top, h); };
  const double r2 = radius * radius;
  for (int a = 0; a < 3; ++a) {
    const double* u = p[a];
    const double* v = p[(a + 1) % 3];
    if ((u[0] - cx) * (u[0] - cx) + (u[1] - cy) * (u[1] - cy) <= r2) take(u[2]);
    // |u + t (v - u) - c|^2 = r^2 for t in [0, 1].
    const double ex = v[0] - u[0], ey = v[1] - u[1], fx = u[0] - cx, fy = u[1] - cy;
    const double qa = ex * ex + ey * ey, qb = 2 * (ex * fx + ey * fy), qc = fx * fx + fy * fy - r2;
    const double disc = qb * qb - 4 * qa * qc;
    if (qa <= 0 || disc < 0) continue;
    for (const double t : {(-qb - std::sqrt(disc)) / (2 * qa), (-qb + std::sqrt(disc)) / (2 * qa)})
      if (t >= 0 && t <= 1) take(u[2] + t * (v[2] - u[2]));
  }
  // The plane z = z0 + gx (x - x0) + gy (y - y0) and the rim point along its gradient.
  const double ax = p[1][0] - p[0][0], ay = p[1][1] - p[0][1], az = p[1][2] - p[0][2];
  const double bx = p[2][0] - p[0][0], by = p[2][1] - p[0][1], bz = p[2][2] - p[0][2];
  const double det = ax * by - ay * bx;
  if (det == 0) return;
  const double gx = (az * by - ay * bz) / det, gy = (ax * bz - az * bx) / det, g = std::hypot(gx, gy);
  if (g == 0) return;
  const double qx = cx + radius * gx / g - p[0][0], qy = cy + radius * gy / g - p[0][1];
  const double s = (qx * by - qy * bx) / det, t = (ax * qy - ay * qx) / det; // q = s a + t b
  if (s >= 0 && t >= 0 && s + t <= 1) take(p[0][2] + s * az + t * bz);
}
} // namespace

double highest_under(const Raster& r, double x, double y, double radius) {
  double top = surface_height(r, x, y);
  if (std::isnan(top)) top = -std::numeric_limits<double>::infinity();
  const long i0 = std::max(0L, static_cast<long>(std::floor((x - radius - r.x0) / r.dx)));
  const long i1 = std::min(r.nx - 2, static_cast<long>(std::floor((x + radius - r.x0) / r.dx)));
  const long j0 = std::max(0L, static_cast<long>(std::floor((y - radius - r.y0) / r.dy)));
  const long j1 = std::min(r.ny - 2, static_cast<long>(std::floor((y + radius - r.y0) / r.dy)));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const double x0 = r.x(i), x1 = r.x(i + 1), y0 = r.y(j), y1 = r.y(j + 1);
      // The two triangles of surface_height: split along (i, j)-(i + 1, j + 1).
      const double lower[3][3] = {{x0, y0, r.at(i, j)}, {x1, y0, r.at(i + 1, j)}, {x1, y1, r.at(i + 1, j + 1)}};
      const double upper[3][3] = {{x0, y0, r.at(i, j)}, {x1, y1, r.at(i + 1, j + 1)}, {x0, y1, r.at(i, j + 1)}};
      raise_to_triangle_max(lower, x, y, radius, top);
      raise_to_triangle_max(upper, x, y, radius, top);
    }
  return std::isinf(top) ? std::numeric_limits<double>::quiet_NaN() : top;
}

void write_geotiff(const std::string& path, const Raster& lattice, const std::vector<std::vector<double>>& bands,
                   const std::vector<std::string>& names) {
  const Gdal& g = gdal();
  GDALDriverH drv = g.GDALGetDriverByName("GTiff");
  if (!drv) throw std::runtime_error(path + ": GDAL has no GeoTIFF driver");
  const std::string tmp = path + ".part";
  g.CPLErrorReset();
  {
    Dataset ds{g.GDALCreate(drv, tmp.c_str(), static_cast<int>(lattice.nx), static_cast<int>(lattice.ny),
                            static_cast<int>(bands.size()), GDT_Float32, nullptr)};
    if (!ds.h) throw std::runtime_error(tmp + ": cannot create the GeoTIFF" + last_gdal_error());
    double gt[6] = {lattice.x0 - 0.5 * lattice.dx,
                    lattice.dx,
                    0,
                    lattice.y0 + (static_cast<double>(lattice.ny) - 0.5) * lattice.dy,
                    0,
                    -lattice.dy};
    g.GDALSetGeoTransform(ds.h, gt);
    if (!lattice.crs_wkt.empty()) g.GDALSetProjection(ds.h, lattice.crs_wkt.c_str());
    std::vector<float> row(static_cast<std::size_t>(lattice.nx));
    const float nodata = -9999.0F;
    for (std::size_t b = 0; b < bands.size(); ++b) {
      GDALRasterBandH band = g.GDALGetRasterBand(ds.h, static_cast<int>(b) + 1);
      g.GDALSetRasterNoDataValue(band, nodata);
      if (b < names.size()) g.GDALSetDescription(band, names[b].c_str());
      for (long k = 0; k < lattice.ny; ++k) {
        const long j = lattice.ny - 1 - k;
        for (long i = 0; i < lattice.nx; ++i) {
          const double z = bands[b][static_cast<std::size_t>(j * lattice.nx + i)];
          row[static_cast<std::size_t>(i)] = std::isnan(z) ? nodata : static_cast<float>(z);
        }
        if (g.GDALRasterIO(band, GF_Write, 0, static_cast<int>(k), static_cast<int>(lattice.nx), 1, row.data(),
                           static_cast<int>(lattice.nx), 1, GDT_Float32, 0, 0) != CE_None)
          throw std::runtime_error(tmp + ": cannot write" + last_gdal_error());
      }
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error(path + ": cannot rename " + tmp);
}

} // namespace surge::geometry
