// Volume, centroid and inertia of a solid: a box, or the inside of a closed triangle mesh
// (signed tetrahedra from the origin; the mesh's winding may point either way). For unit
// density: a body's mass and inertia scale them.
#pragma once
#include "surge/core/case.hpp"
#include "surge/geometry/stl_mesh.hpp"

#include <array>

namespace surge::geometry {

struct MassProperties {
  double volume = 0;
  Vec3d centroid{};
  std::array<std::array<double, 3>, 3> inertia{}; // about the centroid, per unit density
};

[[nodiscard]] MassProperties box_mass_properties(const Box& b);
[[nodiscard]] MassProperties mesh_mass_properties(const Mesh& m);

} // namespace surge::geometry
