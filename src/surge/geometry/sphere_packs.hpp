// DEM sphere packs: touching spheres on a cubic lattice with jitter, or a CSV list.
#pragma once
#include "surge/core/case.hpp"

#include <vector>

namespace surge::geometry {

struct SphereSpec {
  Vec3d centre;
  double radius;
};

// Spheres of `radius` on the lattice of spacing 2 radius inside the box, each moved by a
// uniform random offset of at most jitter * radius per axis (fixed seed: reproducible).
std::vector<SphereSpec> lattice_pack(const Box& box, double radius, double jitter, unsigned seed = 12345);
// One sphere per line: x, y, z, r (commas or spaces; '#' starts a comment).
// Throws InputError naming the file and line.
std::vector<SphereSpec> read_sphere_csv(const std::string& path);

} // namespace surge::geometry
