// Body particles (SPEC §4): the SPH boundary layers that cover each DEM sphere.
#pragma once
#include "surge/core/case.hpp"
#include "surge/dem/dem_solver.hpp"
#include "surge/sph/wcsph_solver.hpp"

#include <cstdint>
#include <vector>

namespace surge::coupling {

// n_l = ceil(2h / dp): enough layers to fill the kernel support of the nearest fluid.
[[nodiscard]] int default_layers(double h, double dp);

// Body-frame offsets of one sphere's body particles: layer k (k = 0 .. layers-1) on
// the shell of radius r - (k + 1/2) dp, with about 4 pi r_k^2 / dp^2 points on a
// Fibonacci lattice (quasi-uniform, spacing ~dp). When the layers reach the centre
// (r_k <= dp/2) one particle at the centre closes the sphere and no further layer
// is made, so a sphere smaller than the layers is filled.
[[nodiscard]] std::vector<Vec3d> body_offsets(double radius, double dp, int layers);

// Which body particle belongs to which sphere. Body particles of sphere k have ids
// first_id + start[k] .. first_id + start[k+1] - 1.
struct BodyLayout {
  std::uint32_t first_id = 0;
  std::vector<Vec3> offset;         // body frame, by body index (id - first_id)
  std::vector<Vec3> ghost;          // mDBC ghost node - particle, body frame, by body index
  std::vector<std::uint32_t> owner; // sphere id, by body index
  std::vector<std::uint32_t> start; // n_spheres + 1 entries
  [[nodiscard]] std::size_t size() const { return offset.size(); }
};

// Appends the body particles of `spheres` (local coordinates, identity orientation) to
// `init`, after removing the fluid particles whose centres lie inside a sphere.
// Submerged body particles start at the hydrostatic density of the fluid box they lie
// in (as the water around them does). Returns the layout and the number of fluid
// particles removed.
struct BodySetup {
  BodyLayout layout;
  std::size_t fluid_removed = 0;
};
BodySetup add_body_particles(const Case& c, const std::vector<dem::Sphere>& spheres, int layers,
                             sph::InitialState& init);

} // namespace surge::coupling
