// Terrain from elevation grids: GDAL reading (GeoTIFF and ESRI ASCII give the same grid,
// errors name the file), the surface through the nodes, the triangle index against a loop
// over all triangles, and a reservoir filled to its level.
#include "surge/core/error.hpp"
#include "surge/geometry/particle_generators.hpp"
#include "surge/geometry/raster.hpp"
#include "surge/geometry/reservoir.hpp"
#include "surge/geometry/slide_body.hpp"
#include "surge/geometry/sphere_packs.hpp"
#include "surge/geometry/terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

using namespace surge;
using namespace surge::geometry;

namespace {
// WGS 84 / UTM zone 32N, as GDAL writes it (a projected system in metres).
const char* utm32n_wkt =
    R"(PROJCS["WGS 84 / UTM zone 32N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],)"
    R"(PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],)"
    R"(PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",9],PARAMETER["scale_factor",0.9996],)"
    R"(PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1]])";

std::string temp_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("surge_terrain_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}

// A valley: z = 10 + 0.5 |y - 20| + 0.1 x on nodes 2 m apart, x in [500000, 500040],
// y in [4000000, 4000040].
Raster valley() {
  Raster r;
  r.x0 = 500000;
  r.y0 = 4000000;
  r.dx = r.dy = 2;
  r.nx = r.ny = 21;
  r.crs_wkt = utm32n_wkt;
  r.v.resize(static_cast<std::size_t>(r.nx * r.ny));
  for (long j = 0; j < r.ny; ++j)
    for (long i = 0; i < r.nx; ++i) r.at(i, j) = 10 + 0.5 * std::fabs(r.y(j) - r.y0 - 20) + 0.1 * (r.x(i) - r.x0);
  return r;
}

// ESRI ASCII grid with its .prj: the same grid as a GeoTIFF.
void write_ascii(const std::string& path, const Raster& r, bool prj, long nodata_at = -1) {
  std::ofstream f(path);
  f.precision(12);
  f << "ncols " << r.nx << "\nnrows " << r.ny << "\nxllcorner " << r.x0 - r.dx / 2 << "\nyllcorner " << r.y0 - r.dy / 2
    << "\ncellsize " << r.dx << "\nNODATA_value -9999\n";
  for (long j = r.ny - 1; j >= 0; --j) {
    for (long i = 0; i < r.nx; ++i) f << (i == nodata_at && j == nodata_at ? -9999.0 : r.at(i, j)) << " ";
    f << "\n";
  }
  if (prj) std::ofstream(path.substr(0, path.size() - 4) + ".prj") << utm32n_wkt;
}
// Top: the plane z = 10 + 0.3 x on 31 x 31 nodes 1 m apart; bottom: 4 m below it on the
// nodes i, j in [5, 25], on it elsewhere (a slide body of 1764 m^3).
std::pair<Raster, Raster> slope_slide() {
  Raster top;
  top.nx = top.ny = 31;
  top.dx = top.dy = 1;
  top.v.resize(31 * 31);
  for (long j = 0; j < 31; ++j)
    for (long i = 0; i < 31; ++i) top.at(i, j) = 10 + 0.3 * top.x(i);
  Raster bottom = top;
  for (long j = 5; j <= 25; ++j)
    for (long i = 5; i <= 25; ++i) bottom.at(i, j) -= 4;
  return {top, bottom};
}

// True when the sphere lies above the surface: its lowest point above the surface at its
// centre, at 64 points of its footprint's rim and at the nodes under it.
bool clear_of(const Raster& bottom, const SphereSpec& s) {
  const double r = s.radius, z = s.centre.z - r + 1e-9;
  if (!(z >= surface_height(bottom, s.centre.x, s.centre.y))) return false;
  for (int a = 0; a < 64; ++a) {
    const double phi = a * M_PI / 32,
                 h = surface_height(bottom, s.centre.x + r * std::cos(phi), s.centre.y + r * std::sin(phi));
    if (h > z) return false;
  }
  for (long j = 0; j < bottom.ny; ++j)
    for (long i = 0; i < bottom.nx; ++i)
      if (std::hypot(bottom.x(i) - s.centre.x, bottom.y(j) - s.centre.y) <= r && bottom.at(i, j) > z) return false;
  return true;
}
} // namespace

TEST(Raster, GeoTiffAndAsciiGridGiveTheSameNodes) {
  const std::string d = temp_dir();
  const Raster r = valley();
  std::vector<std::vector<double>> bands{r.v};
  write_geotiff(d + "/v.tif", r, bands, {"elevation"});
  write_ascii(d + "/v.asc", r, true);
  for (const std::string& f : {d + "/v.tif", d + "/v.asc"}) {
    const Raster g = read_raster(f);
    ASSERT_EQ(g.nx, r.nx) << f;
    ASSERT_EQ(g.ny, r.ny) << f;
    EXPECT_NEAR(g.x0, r.x0, 1e-9) << f;
    EXPECT_NEAR(g.y0, r.y0, 1e-9) << f;
    EXPECT_DOUBLE_EQ(g.dx, 2.0);
    for (std::size_t k = 0; k < r.v.size(); ++k) ASSERT_NEAR(g.v[k], r.v[k], 1e-5) << f << " node " << k;
  }
}

TEST(Raster, ErrorsNameTheFile) {
  const std::string d = temp_dir();
  const Raster r = valley();
  std::ofstream(d + "/not.tif") << "this is not a raster\n";
  write_ascii(d + "/noprj.asc", r, false);
  write_ascii(d + "/hole.asc", r, true, 5);
  auto message = [](const auto& f) {
    try {
      f();
    } catch (const InputError& e) { return std::string(e.what()); }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { (void)read_raster(d + "/not.tif"); }).find("not.tif: not a raster"), std::string::npos);
  EXPECT_NE(message([&] { (void)read_raster(d + "/noprj.asc"); }).find("no coordinate system"), std::string::npos);
  // The hole at node (5, 5) = (500010, 4000010): inside a domain over it, outside one beside it.
  const Box over{{500004, 4000004, 0}, {500030, 4000030, 50}}, beside{{500020, 4000020, 0}, {500040, 4000040, 50}};
  const auto hole = message([&] { (void)read_terrain(d + "/hole.asc", over); });
  EXPECT_NE(hole.find("hole.asc"), std::string::npos) << hole;
  EXPECT_NE(hole.find("no data at the pixel centred on (500010.000, 4000010.000)"), std::string::npos) << hole;
  EXPECT_NO_THROW((void)read_terrain(d + "/hole.asc", beside));
  const Box wide{{499990, 4000000, 0}, {500040, 4000040, 50}};
  EXPECT_NE(message([&] { (void)read_terrain(d + "/hole.asc", wide); }).find("the area needs x [499990.000"),
            std::string::npos);
}

TEST(Terrain, SurfaceHeightIsTheMeshAndExactOnPlanes) {
  const Raster r = valley();
  const Mesh m = terrain_mesh(r);
  ASSERT_EQ(m.tris.size(), 2U * 20 * 20);
  for (const auto& t : m.tris) ASSERT_GT(t.normal().z, 0);
  // The valley's surface is planar on each side of its axis (y = 4000020, a node row): the
  // triangulated surface is exact there.
  for (double x = 500000; x <= 500040; x += 1.37)
    for (double y = 4000000; y <= 4000040; y += 0.91)
      ASSERT_NEAR(surface_height(r, x, y), 10 + 0.5 * std::fabs(y - 4000020) + 0.1 * (x - 500000), 1e-9)
          << x << " " << y;
  EXPECT_TRUE(std::isnan(surface_height(r, 499999, 4000010)));
}

TEST(Terrain, IndexedWallLayersEqualTheLoopOverAllTriangles) {
  const Mesh m = terrain_mesh(valley());
  Mesh plain;
  plain.tris = m.tris; // no index, no heights: every query loops over all triangles
  const Vec3d origin{500000, 4000000, 0};
  // Wall bands wider and narrower than the index's cells (2 m): a band of 0.5 m once found
  // no particle at all (the search gave up before looking).
  for (const double dp : {0.5, 0.25}) {
    const Box clip{{500012, 4000012, 8}, {500024, 4000024, 20}};
    const auto a = mesh_wall(m, origin, dp, 2, &clip), b = mesh_wall(plain, origin, dp, 2, &clip);
    ASSERT_GT(a.size(), 2 * 144 / (dp * dp)); // two layers under 12 m x 12 m, and more on the slopes
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(norm(a[k] - b[k]), 0.0) << k;
  }
  WallSpec w;
  w.is_mesh = w.terrain = w.solid = true;
  for (double z = 0.25; z < 30; z += 0.5) {
    const Vec3d p{500013.25, 4000007.75, z};
    ASSERT_EQ(blocked_by(w, &m, p, 0.5), blocked_by(w, &plain, p, 0.5)) << z;
    ASSERT_EQ(behind_wall(w, &m, p, 1.5), behind_wall(w, &plain, p, 1.5)) << z;
    ASSERT_EQ(norm(ghost_point(w, &m, p) - ghost_point(w, &plain, p)), 0.0) << z;
  }
}

TEST(Reservoir, FillsTheConnectedLakeToItsLevel) {
  // The valley with a closed pit beside it (floor 12 m, below the level 14 m; its rim at
  // 16.7 m): the lake's volume is the integral of level - terrain over the valley alone,
  // int_0^40 2 (4 - 0.1 x)^2 dx = 1280/3 m^3, and the pit stays dry.
  Raster r = valley();
  const double px = 500010, py = 4000036;
  for (long j = 0; j < r.ny; ++j)
    for (long i = 0; i < r.nx; ++i) r.at(i, j) = std::min(r.at(i, j), 12 + std::hypot(r.x(i) - px, r.y(j) - py));
  const Mesh m = terrain_mesh(r);
  WallSpec w;
  w.is_mesh = w.terrain = w.solid = true;
  const double dp = 0.25;
  const Box domain{{500000, 4000000, 9}, {500040, 4000040, 20}};
  FluidRegion f;
  f.reservoir = true;
  f.level = 14;
  f.seed_x = 500005;
  f.seed_y = 4000020;
  const auto fill =
      fill_reservoir(f, domain, domain.min, dp, [&](const Vec3d& p) { return keeps_water_out(w, &m, p, dp); });
  ASSERT_TRUE(fill.seed_problem.empty()) << fill.seed_problem;
  const double volume = static_cast<double>(fill.points.size()) * dp * dp * dp, exact = 1280.0 / 3;
  EXPECT_NEAR(volume / exact, 1.0, 0.02) << volume << " m^3 placed";
  for (const auto& p : fill.points) {
    ASSERT_LE(p.z + dp / 2, f.level + 1e-9);
    ASSERT_GT(std::hypot(p.x - px, p.y - py), 4.0) << "water in the closed pit";
  }
  // The free surface: the top width 2 (8 - 0.2 x) integrated, 320 m^2, less the shore strips
  // whose ground lies above the top layer's centre (level - dp/2): dp/2 / 0.5 per shore,
  // 20 m^2 over the valley's 40 m.
  EXPECT_NEAR(static_cast<double>(fill.columns) * dp * dp / 300.0, 1.0, 0.02);
  // Seeded in the pit, the pit alone fills (about pi 2^2 2 / 3 = 8.4 m^3); on the bank, an error.
  f.seed_x = px;
  f.seed_y = py;
  const auto pit =
      fill_reservoir(f, domain, domain.min, dp, [&](const Vec3d& p) { return keeps_water_out(w, &m, p, dp); });
  EXPECT_NEAR(static_cast<double>(pit.points.size()) * dp * dp * dp, 8 * M_PI / 3, 2.5);
  f.seed_x = 500005;
  f.seed_y = 4000035;
  const auto dry =
      fill_reservoir(f, domain, domain.min, dp, [&](const Vec3d& p) { return keeps_water_out(w, &m, p, dp); });
  EXPECT_TRUE(dry.points.empty());
  EXPECT_NE(dry.seed_problem.find("the seed point (500005.000, 4000035.000) is on dry land"), std::string::npos)
      << dry.seed_problem;
}

TEST(SlideBody, VolumeAndSpheresBetweenTheSurfaces) {
  // slope_slide: the thickness is linear on each triangle, so the node sum is its exact
  // integral: 21 x 21 nodes x 4 m x 1 m^2 = 1764 m^3.
  auto [top, bottom] = slope_slide();
  const double r = 0.25;
  const auto body = fill_slide(top, bottom, r, {0, 0, 0}, "bottom.tif");
  EXPECT_NEAR(body.volume, 1764.0, 1e-9);
  // Each column holds the lattice levels between the surfaces: the cells' volume is the
  // body's to the rounding of each column (within 2 % here).
  const double cells = static_cast<double>(body.spheres.size()) * 8 * r * r * r;
  EXPECT_NEAR(cells / body.volume, 1.0, 0.02) << body.spheres.size() << " spheres";
  for (const auto& s : body.spheres)
    for (int a = 0; a < 16; ++a) {
      const double phi = a * M_PI / 8, x = s.centre.x + r * std::cos(phi), y = s.centre.y + r * std::sin(phi);
      ASSERT_GE(s.centre.z - r, surface_height(bottom, x, y) - 1e-9) << "a sphere cuts the sliding surface";
    }
  // Crossed surfaces: the error names the file, the nodes, their area and extent.
  bottom.at(2, 3) += 1;
  bottom.at(3, 3) += 1;
  try {
    (void)fill_slide(top, bottom, r, {0, 0, 0}, "bottom.tif");
    FAIL() << "crossed surfaces accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bottom.tif: the sliding surface lies above the pre-failure surface at 2 "
                                         "nodes (2.0 m^2) within x [2.000, 3.000], y [3.000, 3.000]"),
              std::string::npos)
        << e.what();
  }
}

TEST(Raster, HighestUnderADisc) {
  // On the plane z = 2 + 0.3 x - 0.2 y the highest point under a disc of radius r lies on
  // its rim, r |grad z| above the centre. A node raised inside the disc is the highest
  // point; a ridge raised along a grid line through the disc, its top where it crosses.
  Raster g;
  g.nx = g.ny = 21;
  g.v.resize(21 * 21);
  for (long j = 0; j < 21; ++j)
    for (long i = 0; i < 21; ++i) g.at(i, j) = 2 + 0.3 * g.x(i) - 0.2 * g.y(j);
  const double x = 10.3, y = 10.7, r = 1.7, rise = r * std::hypot(0.3, 0.2);
  const double exact = 2 + 0.3 * x - 0.2 * y + rise, got = highest_under(g, x, y, r);
  EXPECT_NEAR(got, exact, 1e-12);
  Raster spike = g;
  spike.at(11, 11) += 5; // 0.86 m from the centre
  EXPECT_DOUBLE_EQ(highest_under(spike, x, y, r), spike.at(11, 11));
  // Flat ground with the nodes of column i = 12 raised by 1 (a ridge along x = 12, rising
  // from x = 11, 1.7 m from the centre: the disc touches its crest at (12, 10.7); moved
  // 0.01 m west, it reaches x = 11.99, where the ridge stands 0.99 high).
  Raster flat = g;
  for (auto& z : flat.v) z = 0;
  for (long j = 0; j < 21; ++j) flat.at(12, j) = 1;
  EXPECT_NEAR(highest_under(flat, x, y, r), 1.0, 1e-12);
  EXPECT_NEAR(highest_under(flat, x - 0.01, y, r), 0.99, 1e-12);
  EXPECT_TRUE(std::isnan(highest_under(g, -5, -5, 1)));
}

TEST(SlideBody, BondedColumnsSitOnTheLatticeAndTouch) {
  // Aligned columns (bonded bodies): every centre on a lattice level, every sphere clear of
  // the sliding surface and less than a diameter above it, the same spheres per column as
  // the columns stacked on the surface, and lattice neighbours along the slope touching.
  // Stacked on the surface instead, neighbours along x are 0.3 d apart in height: none
  // touch (what the aligned columns are for).
  const auto [top, bottom] = slope_slide();
  const double r = 0.25, d = 2 * r;
  const Vec3d origin{0, 0, 0.1};
  const auto on_surface = fill_slide(top, bottom, r, origin, "bottom.tif");
  const auto aligned = fill_slide(top, bottom, r, origin, "bottom.tif", 0, true);
  ASSERT_EQ(aligned.spheres.size(), on_surface.spheres.size());
  for (const auto& s : aligned.spheres) {
    const double level = (s.centre.z - origin.z) / d - 0.5;
    ASSERT_NEAR(level, std::round(level), 1e-9);
    ASSERT_TRUE(clear_of(bottom, s)) << s.centre.x << " " << s.centre.y << " " << s.centre.z;
  }
  // Each column's lowest sphere rests less than a diameter above the surface.
  for (const auto& s : aligned.spheres) {
    bool lowest = true;
    for (const auto& o : aligned.spheres)
      lowest = lowest && !(o.centre.x == s.centre.x && o.centre.y == s.centre.y && o.centre.z < s.centre.z);
    if (lowest) { ASSERT_LT(s.centre.z - r - highest_under(bottom, s.centre.x, s.centre.y, r), d * 1.001); }
  }
  // The share of spheres with a touching neighbour one column along x.
  auto touching_along_x = [&](const std::vector<SphereSpec>& list) {
    long n = 0;
    for (const auto& a : list) {
      bool t = false;
      for (const auto& b : list)
        t = t || (std::fabs(std::fabs(b.centre.x - a.centre.x) - d) < 1e-9 &&
                  std::fabs(b.centre.y - a.centre.y) < 1e-9 && std::fabs(b.centre.z - a.centre.z) < 1e-9);
      n += t ? 1 : 0;
    }
    return static_cast<double>(n) / static_cast<double>(list.size());
  };
  EXPECT_GT(touching_along_x(aligned.spheres), 0.9);
  EXPECT_LT(touching_along_x(on_surface.spheres), 0.1);
}

TEST(SlideBody, JitteredColumnsStayClearOfTheSurface) {
  const auto [top, bottom] = slope_slide();
  const double r = 0.25, d = 2 * r;
  const auto plain = fill_slide(top, bottom, r, {0, 0, 0}, "bottom.tif");
  const auto moved = fill_slide(top, bottom, r, {0, 0, 0}, "bottom.tif", 0.5);
  ASSERT_EQ(moved.spheres.size(), plain.spheres.size());
  double largest = 0;
  for (const auto& s : moved.spheres) {
    ASSERT_TRUE(clear_of(bottom, s));
    // Each column moved by at most r / 2 per axis from its lattice point (i + 1/2) d.
    for (const double c : {s.centre.x, s.centre.y}) {
      const double off = c - (std::floor(c / d) + 0.5) * d;
      ASSERT_LE(std::fabs(off), 0.5 * r + 1e-9);
      largest = std::max(largest, std::fabs(off));
    }
  }
  EXPECT_GT(largest, 0.4 * r); // moved, not merely copied
}

TEST(SlideBody, RandomPackBetweenTheGrids) {
  // A random pack of the slide's space: every centre under the pre-failure surface, every
  // sphere clear of the sliding surface, no two overlapping, as many as asked.
  const auto [top, bottom] = slope_slide();
  const double r = 0.4;
  const auto region = slide_region(top, bottom);
  EXPECT_NEAR(region.box.min.x, 4, 1e-9);
  EXPECT_NEAR(region.box.max.x, 26, 1e-9);
  const auto pack = random_pack(region, r, 1500);
  ASSERT_EQ(pack.size(), 1500U);
  for (std::size_t a = 0; a < pack.size(); ++a) {
    const auto& s = pack[a];
    ASSERT_LE(s.centre.z, surface_height(top, s.centre.x, s.centre.y));
    ASSERT_TRUE(clear_of(bottom, s));
    for (std::size_t b = a + 1; b < pack.size(); ++b) ASSERT_GE(norm(pack[b].centre - s.centre), 2 * r - 1e-12);
  }
}

TEST(SpherePacks, RadiiDrawnFromTheRange) {
  std::vector<SphereSpec> list(20000, SphereSpec{{0, 0, 0}, 1.0});
  draw_radii(list, 0.6, 1.0);
  double sum = 0, volume = 0;
  for (const auto& s : list) {
    ASSERT_GE(s.radius, 0.6);
    ASSERT_LE(s.radius, 1.0);
    sum += s.radius;
    volume += 4.0 / 3.0 * M_PI * std::pow(s.radius, 3);
  }
  EXPECT_NEAR(sum / 20000, 0.8, 0.005); // uniform: the mean within 4 standard errors
  EXPECT_NEAR(solid_volume(list), volume, 1e-9 * volume);
}

TEST(Reservoir, CountsTheSurfaceNearTheShore) {
  // A channel 6 dp wide (y in [3, 9]) and 40 long, water to z = 3: 240 columns; within 2 dp
  // of a dry column or the lattice's end: the two rows by each bank (160) and, in the two
  // middle rows, the two columns at each end (8).
  FluidRegion f;
  f.reservoir = true;
  f.level = 3;
  f.seed_x = 20;
  f.seed_y = 6;
  const Box domain{{0, 0, 0}, {40, 12, 4}};
  const auto fill = fill_reservoir(f, domain, domain.min, 1.0, [](const Vec3d& p) { return p.y < 3 || p.y > 9; });
  EXPECT_EQ(fill.columns, 240);
  EXPECT_EQ(fill.near_shore, 168);
}
