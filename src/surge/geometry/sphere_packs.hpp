// DEM sphere packs: touching spheres on a cubic lattice with jitter, or a CSV list.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/raster.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <vector>

namespace surge::geometry {

struct SphereSpec {
  Vec3d centre;
  double radius;
};

// Spheres of `radius` on the lattice of spacing 2 radius inside the box, each moved by a
// uniform random offset of at most jitter * radius per axis (fixed seed: reproducible).
std::vector<SphereSpec> lattice_pack(const Box& box, double radius, double jitter, unsigned seed = 12345);
// A pack region: a box, or the inside of a closed mesh (outward normals) within the box,
// or the space between two elevation grids within the box.
struct PackRegion {
  Box box;
  const Mesh* mesh = nullptr; // when set: only points inside the mesh count
  // When set: a sphere's centre lies at or below `top` and the sphere above `bottom`
  // (clear of its highest point under the sphere's footprint).
  const Raster* top = nullptr;
  const Raster* bottom = nullptr;
  // True when a sphere (c, r) lies wholly inside the region.
  [[nodiscard]] bool holds(const Vec3d& c, double r) const;
};
// The lattice pack of `region.box`, keeping the spheres that lie wholly inside the region.
std::vector<SphereSpec> lattice_pack(const PackRegion& region, double radius, double jitter, unsigned seed = 12345);
// A random loose pack: `count` spheres placed one by one at uniformly random points of
// the region where they overlap no earlier sphere (random sequential addition, fixed
// seed). Returns fewer when the region is full (the caller reports it).
std::vector<SphereSpec> random_pack(const PackRegion& region, double radius, long count, unsigned seed = 12345);
// Each sphere's radius drawn uniformly from [radius_min, radius_max] (fixed seed), its
// centre kept: a pack whose spacing the largest radius set stays free of overlaps.
void draw_radii(std::vector<SphereSpec>& list, double radius_min, double radius_max, unsigned seed = 54321);
// The spheres' total volume [m^3].
double solid_volume(const std::vector<SphereSpec>& list);
// True when p is inside the closed mesh (ray parity along a fixed oblique direction).
bool inside_mesh(const Mesh& m, const Vec3d& p);
// Distance from p to the mesh surface.
double distance_to_mesh(const Mesh& m, const Vec3d& p);

// One sphere per line: x, y, z, r (commas or spaces; '#' starts a comment).
// Throws InputError naming the file and line.
std::vector<SphereSpec> read_sphere_csv(const std::string& path);

} // namespace surge::geometry
